#pragma once
// What the quasi-Newton preview's tests share (tests/unit/sim/quasi_newton_preview_test.cpp and its drapes of the default
// scene, tests/slow/quasi_newton_preview_drape_test.cpp): the default scene in a stage, with further settings
// overridden.
#include <string>
#include <utility>
#include <vector>

#include "drape/scene/scene.h"
#include "shared_data.h"

namespace drape::test {

inline Scene defaultScene(const char* stage, std::vector<std::pair<std::string, std::string>> extra = {}) {
  SceneRequest request;
  request.input = assetsDir() / "scenes" / "default.json";
  request.overrides = {{"solver.stage", stage}};
  for (auto& kv : extra) request.overrides.push_back(kv);
  return loadScene(request);
}

}  // namespace drape::test
