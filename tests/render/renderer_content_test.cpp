// What the renderer draws, checked on pixels: back faces differ from front faces, panel colours show,
// the strain legend appears only in strain mode, modes change the garment and not the background, bad
// snapshots give a clear error.
#include <gtest/gtest.h>

#include <cmath>

#include "drape/geometry/primitives.h"
#include "drape/render/image_compare.h"
#include "render_fixture.h"
#include "synthetic_scenes.h"

namespace drape::test {
namespace {

using render::DisplayMode;

// A single flat square (2 triangles) facing +z, filling the middle of a front view.
Snapshot flatSquare(Eigen::Vector3f color) {
  Snapshot s;
  s.positions.resize(4, 3);
  s.positions << -0.5, 0.0, 0.0, 0.5, 0.0, 0.0, 0.5, 1.0, 0.0, -0.5, 1.0, 0.0;
  s.triangles.resize(2, 3);
  s.triangles << 0, 1, 2, 0, 2, 3;  // counter-clockwise seen from +z
  s.trianglePanel = Eigen::VectorXi::Zero(2);
  s.panelColors = {color};
  return s;
}

Eigen::Vector3i centerPixel(const render::Image& image) {
  const std::uint8_t* p = image.at(image.width / 2, image.height / 2);
  return {p[0], p[1], p[2]};
}

TEST_F(RenderTest, FrontAndBackFacesAreVisiblyDifferent) {
  const Snapshot square = flatSquare({0.8f, 0.1f, 0.1f});
  render::RenderOptions o = smallOptions();
  o.showGround = false;
  const auto bounds = square.bounds();
  const Eigen::Vector3i front =
      centerPixel(renderer().render(square, render::presetCamera(render::ViewPreset::Front, bounds, 1.0), o));
  const Eigen::Vector3i back =
      centerPixel(renderer().render(square, render::presetCamera(render::ViewPreset::Back, bounds, 1.0), o));
  // Front: clearly red. Back: darker and less saturated.
  EXPECT_GT(front.x(), front.y() + 80) << front.transpose();
  EXPECT_LT(back.x() - back.y(), front.x() - front.y() - 30) << front.transpose() << " / " << back.transpose();
  EXPECT_LT(back.sum(), front.sum());
}

// A body whose surface comes through the cloth by less than the contact thickness is drawn behind it (a cloth
// resting within its thickness of the skin is not covered by patches of body); a body deeper through it shows.
TEST_F(RenderTest, BodyWithinTheContactThicknessStaysBehindTheCloth) {
  render::RenderOptions o = smallOptions();
  o.showGround = false;
  Snapshot s = flatSquare({0.8f, 0.05f, 0.05f});
  const auto camera = render::presetCamera(render::ViewPreset::Front, s.bounds(), 1.0);
  const auto redAt = [&](double through, double thickness) {
    // A 1 m sphere whose front point lies `through` in front of the square's centre.
    s.avatar = makeIcosphere(Eigen::Vector3d(0.0, 0.5, -1.0), 1.0 + through, 5);
    s.contactThickness = thickness;
    const Eigen::Vector3i c = centerPixel(renderer().render(s, camera, o));
    return c.x() > c.y() + 80;
  };
  EXPECT_FALSE(redAt(0.001, 0.0)) << "without a contact thickness the body 1 mm through the cloth covers it";
  EXPECT_TRUE(redAt(0.001, 0.002));
  EXPECT_FALSE(redAt(0.005, 0.002)) << "a body 5 mm through the cloth is drawn over it";
}

TEST_F(RenderTest, PanelColourReachesThePixels) {
  render::RenderOptions o = smallOptions();
  o.showGround = false;
  const Snapshot red = flatSquare({0.8f, 0.05f, 0.05f}), blue = flatSquare({0.05f, 0.05f, 0.8f});
  const auto camera = render::presetCamera(render::ViewPreset::Front, red.bounds(), 1.0);
  const Eigen::Vector3i r = centerPixel(renderer().render(red, camera, o));
  const Eigen::Vector3i b = centerPixel(renderer().render(blue, camera, o));
  EXPECT_GT(r.x(), r.z() + 80);
  EXPECT_GT(b.z(), b.x() + 80);
}

TEST_F(RenderTest, StrainLegendOnlyInStrainModeAndColourFollowsStrain) {
  Snapshot square = flatSquare({0.5f, 0.5f, 0.5f});
  square.triangleStrain = Eigen::VectorXd::Constant(2, 0.10);
  render::RenderOptions o = smallOptions(DisplayMode::Strain);
  o.showGround = false;
  o.strainMin = 0.0, o.strainMax = 0.10;  // the square sits at the top of the scale: red
  const auto camera = render::presetCamera(render::ViewPreset::Front, square.bounds(), 1.0);
  const render::Image strain = renderer().render(square, camera, o);
  const Eigen::Vector3i hot = centerPixel(strain);
  EXPECT_GT(hot.x(), hot.z() + 60) << hot.transpose();
  square.triangleStrain.setZero();  // bottom of the scale: blue
  const Eigen::Vector3i cold = centerPixel(renderer().render(square, camera, o));
  EXPECT_GT(cold.z(), cold.x() + 40) << cold.transpose();
  // The legend sits in the top-right corner: its background panel is near white in strain mode only.
  o.mode = DisplayMode::Shaded;
  const render::Image shaded = renderer().render(square, camera, o);
  auto corner = [](const render::Image& im) {
    int bright = 0;
    for (int y = 8; y < 40; ++y)
      for (int x = im.width - 60; x < im.width - 8; ++x) bright += im.at(x, y)[0] > 240 && im.at(x, y)[2] > 240;
    return bright;
  };
  EXPECT_GT(corner(strain), 200);
  EXPECT_EQ(corner(shaded), 0);
}

TEST_F(RenderTest, ModesChangeTheGarmentOnly) {
  const Snapshot scene = skirtScene();
  render::Image images[5];
  int k = 0;
  for (DisplayMode mode :
       {DisplayMode::Shaded, DisplayMode::Wireframe, DisplayMode::Strain, DisplayMode::Domains, DisplayMode::Contacts})
    images[k++] = renderer().render(scene, render::ViewPreset::Front, smallOptions(mode));
  for (int a = 0; a < 5; ++a)
    for (int b = a + 1; b < 5; ++b) {
      EXPECT_GT(render::compareImages(images[a], images[b]).mismatchedPixels, 500) << a << " vs " << b;
      // bottom-left corner: background, identical in every mode
      EXPECT_EQ(std::vector<std::uint8_t>(images[a].at(2, 250), images[a].at(2, 250) + 4),
                std::vector<std::uint8_t>(images[b].at(2, 250), images[b].at(2, 250) + 4));
    }
}

// Print mode lays the image on the garment by its pattern coordinates, upright and at its stated width: a tile of the
// square's width whose top half is red and bottom half blue shows red over the square's top and blue over its bottom;
// at half that width it repeats, so the quarter below the top is blue.
TEST_F(RenderTest, PrintFollowsThePatternCoordinates) {
  Snapshot square = flatSquare({0.5f, 0.5f, 0.5f});
  square.uvs.resize(4, 2);
  square.uvs << 0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0;  // metres in the panel's frame (y up)
  auto image = std::make_shared<render::Image>(64, 64);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      std::uint8_t* p = image->at(x, y);
      p[0] = y < 32 ? 220 : 20, p[1] = 20, p[2] = y < 32 ? 20 : 220, p[3] = 255;
    }
  render::RenderOptions o = smallOptions();
  o.showGround = false;
  o.mode = DisplayMode::Print;
  o.print = image;
  o.printWidth = 1.0;
  const auto camera = render::presetCamera(render::ViewPreset::Front, square.bounds(), 1.0);
  const auto colourAt = [&](const render::Image& shot, double y) {
    const Eigen::Vector4f clip = camera.projectionMatrix(double(shot.width) / shot.height) * camera.viewMatrix() *
                                 Eigen::Vector4f(0.0f, float(y), 0.0f, 1.0f);
    const int px = static_cast<int>((clip.x() / clip.w() + 1.0f) * 0.5f * shot.width);
    const int py = static_cast<int>((1.0f - clip.y() / clip.w()) * 0.5f * shot.height);
    const std::uint8_t* p = shot.at(px, py);
    return Eigen::Vector3i(p[0], p[1], p[2]);
  };
  const render::Image whole = renderer().render(square, camera, o);
  for (double y : {0.6, 0.9}) EXPECT_GT(colourAt(whole, y).x(), colourAt(whole, y).z() + 60) << "red at " << y;
  for (double y : {0.1, 0.4}) EXPECT_GT(colourAt(whole, y).z(), colourAt(whole, y).x() + 60) << "blue at " << y;
  o.printWidth = 0.5;
  const render::Image half = renderer().render(square, camera, o);
  EXPECT_GT(colourAt(half, 0.9).x(), colourAt(half, 0.9).z() + 60);
  EXPECT_GT(colourAt(half, 0.6).z(), colourAt(half, 0.6).x() + 60);
  // Without an image the garment is the neutral fabric, as in contacts mode without contacts.
  o.print.reset();
  const Eigen::Vector3i plain = colourAt(renderer().render(square, camera, o), 0.5);
  EXPECT_LT(std::abs(plain.x() - plain.z()), 40) << plain.transpose();
}

TEST_F(RenderTest, BadSnapshotIsAClearError) {
  Snapshot s = flatSquare({0.5f, 0.5f, 0.5f});
  s.triangles(1, 2) = 7;
  try {
    renderer().render(s, render::ViewPreset::Front, smallOptions());
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("garment triangle 1 refers to vertex 7"), std::string::npos) << e.what();
  }
  Snapshot t = flatSquare({0.5f, 0.5f, 0.5f});
  t.triangleStrain = Eigen::VectorXd::Zero(5);
  EXPECT_THROW(renderer().render(t, render::ViewPreset::Front, smallOptions()), std::invalid_argument);
}

TEST_F(RenderTest, EmptySnapshotDrawsBackgroundOnly) {
  const render::Image image = renderer().render(Snapshot{}, render::ViewPreset::Front, smallOptions());
  ASSERT_EQ(image.width, 256);
  const std::uint8_t* top = image.at(128, 0);
  EXPECT_NEAR(top[0], std::lround(0.93 * 255), 3);
  EXPECT_NEAR(top[2], std::lround(0.96 * 255), 3);
}

}  // namespace
}  // namespace drape::test
