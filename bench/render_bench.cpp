// Render benchmark: time of a 1024 x 1024 frame on the headless context (llvmpipe on a CI machine), first
// frame (upload + shader warm-up) and steady state (mean of 10 frames of the uploaded scene).
//   drape_render_bench [--backend egl|osmesa] [--msaa N] [--out DIR]   (DIR receives one PNG per scene to eyeball)
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "drape/render/headless.h"
#include "drape/render/png_io.h"
#include "synthetic_scenes.h"

namespace {

using Clock = std::chrono::steady_clock;

double seconds(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); }

int g_msaa = 4;

void bench(drape::render::OffscreenRenderer& renderer, const char* name, const drape::Snapshot& scene,
           drape::render::DisplayMode mode, const std::string& outDir) {
  drape::render::RenderOptions options;
  options.width = options.height = 1024;
  options.mode = mode;
  options.msaaSamples = g_msaa;
  const auto camera = drape::render::presetCamera(drape::render::ViewPreset::ThreeQuarter, scene.bounds(), 1.0);
  const auto t0 = Clock::now();
  renderer.upload(scene);
  const drape::render::Image first = renderer.render(camera, options);
  const auto t1 = Clock::now();
  constexpr int kFrames = 10;
  for (int i = 0; i < kFrames; ++i) renderer.render(camera, options);
  const auto t2 = Clock::now();
  std::printf("| %-34s | %8ld | %-8s | %8.3f | %8.3f |\n", name, static_cast<long>(scene.triangles.rows()),
              std::string(drape::render::displayModeName(mode)).c_str(), seconds(t0, t1), seconds(t1, t2) / kFrames);
  if (!outDir.empty())
    drape::render::writePng(outDir + "/bench_" + std::string(name).substr(0, std::string(name).find(' ')) + "_" +
                                std::string(drape::render::displayModeName(mode)) + ".png",
                            first);
}

}  // namespace

int main(int argc, char** argv) {
  drape::render::GlBackend backend = drape::render::GlBackend::Auto;
  std::string outDir;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--backend") && i + 1 < argc) {
      const std::string b = argv[++i];
      backend = b == "osmesa" ? drape::render::GlBackend::OsMesa : drape::render::GlBackend::Egl;
    } else if (!std::strcmp(argv[i], "--msaa") && i + 1 < argc) {
      g_msaa = std::atoi(argv[++i]);
    } else if (!std::strcmp(argv[i], "--out") && i + 1 < argc) {
      outDir = argv[++i];
    } else {
      std::fprintf(stderr, "usage: drape_render_bench [--backend egl|osmesa] [--msaa N] [--out DIR]\n");
      return 2;
    }
  }
  try {
    drape::render::OffscreenRenderer renderer(backend);
    std::printf("backend %s, renderer %s, 1024 x 1024, %dx MSAA, three-quarter view\n\n",
                renderer.backendName().c_str(), renderer.glRendererName().c_str(), g_msaa);
    std::printf("| %-34s | %8s | %-8s | %8s | %8s |\n", "scene", "tris", "mode", "first s", "steady s");
    std::printf("|%s|%s|%s|%s|%s|\n", std::string(36, '-').c_str(), std::string(10, '-').c_str(),
                std::string(10, '-').c_str(), std::string(10, '-').c_str(), std::string(10, '-').c_str());
    // 1 m^2 tablecloth, 100 x 100 quads = 20k triangles, over a sphere.
    const drape::Snapshot tablecloth = drape::test::tableclothScene(100, 1.0, 4);
    // Garment-like: a folded skirt of ~100k triangles around a sphere torso.
    const drape::Snapshot garment = drape::test::skirtScene(160, 316, 4);
    bench(renderer, "tablecloth 1 m^2 over sphere", tablecloth, drape::render::DisplayMode::Shaded, outDir);
    bench(renderer, "tablecloth 1 m^2 over sphere", tablecloth, drape::render::DisplayMode::Strain, outDir);
    bench(renderer, "garment 100k over sphere", garment, drape::render::DisplayMode::Shaded, outDir);
    bench(renderer, "garment 100k over sphere", garment, drape::render::DisplayMode::Wireframe, outDir);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "drape_render_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
