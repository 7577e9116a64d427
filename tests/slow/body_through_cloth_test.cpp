// Finished drapes of real garments drawn as a designer sees them: no patch of body shows through the cloth from the
// front or the back, for GarmentCode's shirt on the body it was made for and the library trousers. The placed shirt
// seen from the back is in tests/render/body_through_cloth_test.cpp.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <utility>

#include "body_through_cloth_support.h"
#include "drape/render/camera.h"
#include "drape/render/png_io.h"
#include "drape/scene/scene.h"
#include "drape/sim/simulation.h"
#include "render_fixture.h"
#include "shared_data.h"

namespace drape::test {
namespace {

// The garment is drawn red. Its outside is then clearly red, while its inside (seen through the neckline, the hems
// or a sleeve) is drawn in a dull "inside" tint (renderer_content_test.cpp). Counts the pixels of `cloth` (the
// garment without the body) that show the garment's outside, shrunk by one pixel so that anti-aliased silhouette
// edges do not count, and how many of them are no longer red in `full` (the same view with the body): the body drawn
// over the outside of the cloth.
std::pair<int, int> bodyThroughCloth(const render::Image& full, const render::Image& cloth) {
  const auto red = [](const render::Image& image, int x, int y) {
    const std::uint8_t* p = image.at(x, y);
    return int(p[0]) > int(p[1]) + 80 && int(p[0]) > int(p[2]) + 80;
  };
  int covered = 0, through = 0;
  for (int y = 1; y + 1 < cloth.height; ++y) {
    for (int x = 1; x + 1 < cloth.width; ++x) {
      bool inside = true;
      for (int dy = -1; dy <= 1 && inside; ++dy)
        for (int dx = -1; dx <= 1 && inside; ++dx) inside = red(cloth, x + dx, y + dy);
      if (!inside) continue;
      ++covered;
      if (!red(full, x, y)) ++through;
    }
  }
  return {covered, through};
}

void expectNoBodyThroughCloth(render::OffscreenRenderer& renderer, const Scene& sceneIn) {
  Simulation simulation(sceneIn);
  while (!simulation.finished()) ASSERT_NE(simulation.step().status, StepStatus::Diverged);
  Snapshot snapshot = simulation.snapshot();
  snapshot.panelColors.assign(snapshot.panelColors.size(), Eigen::Vector3f(0.8f, 0.05f, 0.05f));
  render::RenderOptions o;
  o.width = o.height = 384;
  o.showGround = false;
  for (const render::ViewPreset view : {render::ViewPreset::Front, render::ViewPreset::Back}) {
    const render::Camera camera = render::presetCamera(view, snapshot.bounds(), 1.0);
    const render::Image full = renderer.render(snapshot, camera, o);
    render::RenderOptions noBody = o;
    noBody.showAvatar = false;
    const render::Image cloth = renderer.render(snapshot, camera, noBody);
    const auto [covered, through] = bodyThroughCloth(full, cloth);
    EXPECT_GT(covered, o.width * o.height / 50) << "the garment's outside covers little of the view";
    if (through > covered / 1000) {
      const std::string name = "body_through_" + std::to_string(static_cast<int>(view));
      render::writePng(testOutputDir() / (name + ".full.png"), full);
      render::writePng(testOutputDir() / (name + ".cloth.png"), cloth);
    }
    EXPECT_LE(through, covered / 1000) << through << " of " << covered << " cloth pixels show the body, view "
                                       << static_cast<int>(view);
  }
}

TEST_F(RenderTest, NoBodyThroughTheDrapedGarmentCodeShirt) {
  DRAPE_SHARED_FILE(pattern, "garmentcode/shirt_mean_specification.json");
  DRAPE_SHARED_FILE(body, "garmentcode/mean_all.obj");
  expectNoBodyThroughCloth(renderer(), sceneOf(pattern, body, "drape"));
}

TEST_F(RenderTest, NoBodyThroughTheDrapedTrousers) {
  SceneRequest request;
  request.input = assetsDir() / "scenes" / "trousers.json";
  request.overrides = {{"solver.stage", "drape"}, {"solver.max_sim_time", "1.5"}};
  expectNoBodyThroughCloth(renderer(), loadScene(request));
}

}  // namespace
}  // namespace drape::test
