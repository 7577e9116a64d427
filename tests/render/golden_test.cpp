// Screenshot regression: synthetic scenes x views x modes against tests/render/golden/*.png.
#include <gtest/gtest.h>

#include <ostream>
#include <string>

#include "golden_support.h"
#include "render_fixture.h"
#include "synthetic_scenes.h"

namespace drape::test {
namespace {

using render::DisplayMode;
using render::ViewPreset;

struct GoldenCase {
  const char* scene;  // "tablecloth" or "skirt"
  ViewPreset view;
  DisplayMode mode;
  bool wireframeOverlay = false;
};

std::string caseName(const GoldenCase& c) {
  std::string view(render::viewPresetName(c.view));
  for (char& ch : view)
    if (ch == '-') ch = '_';
  return std::string(c.scene) + "_" + view + "_" + std::string(render::displayModeName(c.mode)) +
         (c.wireframeOverlay ? "_wire" : "");
}

void PrintTo(const GoldenCase& c, std::ostream* os) { *os << caseName(c); }

const Snapshot& scene(const std::string& name) {
  static const Snapshot tablecloth = tableclothScene();
  static const Snapshot skirt = skirtScene();
  return name == "tablecloth" ? tablecloth : skirt;
}

class GoldenImageTest : public RenderTest, public ::testing::WithParamInterface<GoldenCase> {};

TEST_P(GoldenImageTest, MatchesGolden) {
  const GoldenCase& c = GetParam();
  render::RenderOptions options = smallOptions(c.mode);
  options.wireframeOverlay = c.wireframeOverlay;
  const render::Image image = renderer().render(scene(c.scene), c.view, options);
  // Opaque everywhere: blending (ground fade, legend panel) must not leave alpha < 1 in the framebuffer,
  // or Qt would composite the viewport with its window and PNG viewers show holes.
  long translucent = 0;
  for (size_t i = 3; i < image.pixels.size(); i += 4) translucent += image.pixels[i] != 255;
  EXPECT_EQ(translucent, 0);
  EXPECT_TRUE(matchesGolden(image, caseName(c)));
}

INSTANTIATE_TEST_SUITE_P(
    Scenes, GoldenImageTest,
    ::testing::Values(GoldenCase{"tablecloth", ViewPreset::Front, DisplayMode::Shaded},
                      GoldenCase{"tablecloth", ViewPreset::ThreeQuarter, DisplayMode::Shaded},
                      GoldenCase{"tablecloth", ViewPreset::ThreeQuarter, DisplayMode::Strain},
                      GoldenCase{"tablecloth", ViewPreset::ThreeQuarter, DisplayMode::Wireframe},
                      GoldenCase{"tablecloth", ViewPreset::Left, DisplayMode::Contacts},
                      GoldenCase{"skirt", ViewPreset::ThreeQuarter, DisplayMode::Shaded},
                      GoldenCase{"skirt", ViewPreset::Front, DisplayMode::Domains},
                      GoldenCase{"skirt", ViewPreset::Back, DisplayMode::Strain},
                      GoldenCase{"skirt", ViewPreset::Right, DisplayMode::Shaded, true}),
    [](const ::testing::TestParamInfo<GoldenCase>& info) { return caseName(info.param); });

TEST_F(RenderTest, ContactSheetMatchesGolden) {
  render::RenderOptions options = smallOptions();
  options.width = options.height = 128;
  const render::Image sheet = renderer().contactSheet(scene("skirt"), options);
  ASSERT_EQ(sheet.width, 3 * 128);
  ASSERT_EQ(sheet.height, 2 * 128);
  EXPECT_TRUE(matchesGolden(sheet, "skirt_contact_sheet"));
}

}  // namespace
}  // namespace drape::test
