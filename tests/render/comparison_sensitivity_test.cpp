// The golden comparison must be able to fail: a shifted camera, a changed colour and one moved triangle
// are each detected with the golden tolerance, while re-rendering the same input matches exactly.
#include <gtest/gtest.h>

#include <cstdio>

#include "golden_support.h"
#include "render_fixture.h"
#include "synthetic_scenes.h"

namespace drape::test {
namespace {

using render::compareImages;

class ComparisonSensitivityTest : public RenderTest {
 protected:
  void SetUp() override {
    m_scene = tableclothScene();
    m_options = smallOptions();
    m_camera = render::presetCamera(render::ViewPreset::ThreeQuarter, m_scene.bounds(), 1.0);
    m_reference = renderer().render(m_scene, m_camera, m_options);
  }
  Snapshot m_scene;
  render::RenderOptions m_options;
  render::Camera m_camera;
  render::Image m_reference;
};

TEST_F(ComparisonSensitivityTest, SameInputRendersIdenticalPixels) {
  for (int run = 0; run < 3; ++run) {
    const render::CompareResult r = compareImages(m_reference, renderer().render(m_scene, m_camera, m_options));
    EXPECT_EQ(r.mismatchedPixels, 0);
    EXPECT_EQ(r.maxChannelDifference, 0) << "run " << run;
  }
}

TEST_F(ComparisonSensitivityTest, ShiftedCameraIsDetected) {
  render::Camera shifted = m_camera;
  shifted.eye += Eigen::Vector3d(0.02, 0.0, 0.0);  // 2 cm at ~2.5 m: about 2 pixels at 256 x 256
  shifted.target += Eigen::Vector3d(0.02, 0.0, 0.0);
  const render::CompareResult r = compareImages(m_reference, renderer().render(m_scene, shifted, m_options),
                                                goldenTolerance());
  EXPECT_FALSE(r.matches) << r.summary();
}

TEST_F(ComparisonSensitivityTest, ChangedPanelColourIsDetected) {
  Snapshot changed = m_scene;
  changed.panelColors[1] = Eigen::Vector3f(0.12f, 0.30f, 0.50f);  // a slightly greener blue
  const render::CompareResult r = compareImages(m_reference, renderer().render(changed, m_camera, m_options),
                                                goldenTolerance());
  EXPECT_FALSE(r.matches) << r.summary();
}

TEST_F(ComparisonSensitivityTest, OneRecolouredTriangleIsDetected) {
  Snapshot changed = m_scene;
  changed.panelColors.push_back(Eigen::Vector3f(0.9f, 0.8f, 0.1f));
  // A triangle on the cap, facing the three-quarter camera: make it the only one of panel 2.
  changed.trianglePanel(2 * (16 * 32 + 20)) = 2;
  const render::CompareResult r = compareImages(m_reference, renderer().render(changed, m_camera, m_options),
                                                goldenTolerance());
  EXPECT_GT(r.mismatchedPixels, 0);
  EXPECT_FALSE(r.matches) << r.summary();
}

TEST_F(ComparisonSensitivityTest, OneMovedVertexIsDetected) {
  Snapshot changed = m_scene;
  const int vertex = 28 * 33 + 20;  // on the front of the hanging skirt, in view
  changed.positions.row(vertex) += Eigen::RowVector3d(0.0, 0.0, 0.04);
  const render::CompareResult r = compareImages(m_reference, renderer().render(changed, m_camera, m_options),
                                                goldenTolerance());
  EXPECT_FALSE(r.matches) << r.summary();
  std::printf("moved vertex: %s\n", r.summary().c_str());
}

}  // namespace
}  // namespace drape::test
