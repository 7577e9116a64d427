#pragma once
// What the full pipeline's tests on GarmentCode's shirt on mean_all share (tests/unit/real_garment_pipeline_test.cpp
// and the denim shirt's, tests/slow/real_garment_pipeline_denim_test.cpp): the test scene with settings overridden,
// run in the full pipeline.
#include <string>
#include <utility>
#include <vector>

#include "drape/scene/scene.h"
#include "shared_data.h"

namespace drape::test {

inline Scene shirtOnMeanAll(std::vector<std::pair<std::string, std::string>> overrides) {
  SceneRequest request;
  request.input = testDataDir() / "scenes" / "shirt_mean_on_mean_all.json";
  overrides.emplace_back("solver.stage", "full");
  request.overrides = std::move(overrides);
  return loadScene(request);
}

}  // namespace drape::test
