// Headless contexts: EGL surfaceless and the OSMesa fallback run the same renderer and agree; the backend
// can be forced through DRAPE_GL_BACKEND; a bad value gives a clear error.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "drape/render/headless.h"
#include "drape/render/image_compare.h"
#include "golden_support.h"
#include "synthetic_scenes.h"

namespace drape::test {
namespace {

render::RenderOptions options256(render::DisplayMode mode) {
  render::RenderOptions o;
  o.width = o.height = 256;
  o.mode = mode;
  return o;
}

class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : m_name(name) {
    if (const char* old = std::getenv(name)) m_old = old, m_had = true;
    setenv(name, value, 1);
  }
  ~ScopedEnv() {
    if (m_had)
      setenv(m_name, m_old.c_str(), 1);
    else
      unsetenv(m_name);
  }

 private:
  const char* m_name;
  std::string m_old;
  bool m_had = false;
};

TEST(OffscreenBackendTest, EglSurfacelessGivesCoreContextOnMesa) {
  render::OffscreenRenderer renderer(render::GlBackend::Egl);
  EXPECT_EQ(renderer.backendName(), "egl");
  EXPECT_FALSE(renderer.glRendererName().empty());
}

TEST(OffscreenBackendTest, OsMesaRendersTheSameImageAsEgl) {
  const Snapshot scene = skirtScene();
  for (render::DisplayMode mode : {render::DisplayMode::Shaded, render::DisplayMode::Strain}) {
    render::Image egl, osmesa;
    {
      render::OffscreenRenderer renderer(render::GlBackend::Egl);
      egl = renderer.render(scene, render::ViewPreset::ThreeQuarter, options256(mode));
    }
    {
      render::OffscreenRenderer renderer(render::GlBackend::OsMesa);
      ASSERT_EQ(renderer.backendName(), "osmesa");
      osmesa = renderer.render(scene, render::ViewPreset::ThreeQuarter, options256(mode));
    }
    const render::CompareResult r = render::compareImages(egl, osmesa, goldenTolerance());
    EXPECT_TRUE(r.matches) << r.summary();
    // and it drew something: not just the background
    const render::CompareResult vsEmpty =
        render::compareImages(osmesa, render::OffscreenRenderer(render::GlBackend::OsMesa)
                                          .render(Snapshot{}, render::ViewPreset::Front, options256(mode)));
    EXPECT_GT(vsEmpty.mismatchedPixels, 5000);
  }
}

TEST(OffscreenBackendTest, EnvironmentForcesOsMesa) {
  ScopedEnv env("DRAPE_GL_BACKEND", "osmesa");
  render::OffscreenRenderer renderer;
  EXPECT_EQ(renderer.backendName(), "osmesa");
  const render::Image image = renderer.render(tableclothScene(), render::ViewPreset::Front,
                                              options256(render::DisplayMode::Shaded));
  EXPECT_TRUE(matchesGolden(image, "tablecloth_front_shaded"));
}

TEST(OffscreenBackendTest, EnvironmentForcesEgl) {
  ScopedEnv env("DRAPE_GL_BACKEND", "egl");
  EXPECT_EQ(render::OffscreenRenderer().backendName(), "egl");
}

TEST(OffscreenBackendTest, UnknownBackendNameIsAClearError) {
  ScopedEnv env("DRAPE_GL_BACKEND", "vulkan");
  try {
    render::OffscreenRenderer renderer;
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("DRAPE_GL_BACKEND='vulkan'"), std::string::npos) << e.what();
  }
}

TEST(OffscreenBackendTest, ConvenienceFunctionsRenderAndTile) {
  const Snapshot scene = skirtScene(8, 24, 2);
  render::RenderOptions o = options256(render::DisplayMode::Shaded);
  o.width = 96, o.height = 64;
  const render::Image single = render::renderSnapshot(scene, render::ViewPreset::Front, o);
  EXPECT_EQ(single.width, 96);
  EXPECT_EQ(single.height, 64);
  const render::Image sheet = render::contactSheet(scene, o, false);
  EXPECT_EQ(sheet.width, 3 * 96);
  EXPECT_EQ(sheet.height, 2 * 64);
  // The front tile (top-left) of an unlabelled sheet is the front view itself.
  render::Image tile(96, 64);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 96; ++x)
      for (int c = 0; c < 4; ++c) tile.at(x, y)[c] = sheet.at(x, y)[c];
  EXPECT_EQ(render::compareImages(single, tile).mismatchedPixels, 0);
}

}  // namespace
}  // namespace drape::test
