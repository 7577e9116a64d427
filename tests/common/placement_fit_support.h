#pragma once
// What the placement fit's tests share (tests/unit/garment/placement_fit_test.cpp and the slow drape of the fitted shirt,
// tests/slow/placement_fit_drape_test.cpp): the scene with the fit on or off, and GarmentCode's shirt on the broad,
// tall mannequin (tests/data/bodies/broad_tall.yaml).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "drape/avatar/body_measurements.h"
#include "drape/avatar/mannequin.h"
#include "drape/scene/scene.h"
#include "shared_data.h"

namespace drape {

inline Scene sceneWithFit(SceneRequest request, bool fit) {
  request.overrides.push_back({"placement.fit", fit ? "true" : "false"});
  return loadScene(request);
}

// GarmentCode's shirt on the broad, tall mannequin, placed with the fit on or off.
class BroadTallBody : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    MannequinOptions coarse;
    coarse.facetSize = 0.015;
    s_body = new TriangleMesh(
        makeMannequin(loadBodyMeasurements(test::testDataDir() / "bodies" / "broad_tall.yaml"), coarse));
  }
  static void TearDownTestSuite() { delete s_body; }

  static Scene shirt(const std::filesystem::path& pattern, bool fit, double edge) {
    SceneRequest request;
    request.input = pattern;
    request.overrides.push_back({"mesh.target_edge_length", std::to_string(edge)});
    Scene scene = sceneWithFit(request, fit);
    scene.avatar = *s_body;
    return scene;
  }

  static inline TriangleMesh* s_body = nullptr;
};

}  // namespace drape
