#pragma once
// What the exploded state's tests share (tests/unit/sim/exploded_state_test.cpp and, for every stage,
// tests/slow/exploded_state_stages_test.cpp): the settings no fabric holds together (the softest stretch stiffness
// the settings admit, no shear or bending stiffness, 1000 m/s^2 gravity and 0.1 s steps), the same held on the body
// by the most friction so that it tears instead of sliding off, and a library scene with settings overridden.
#include <string>
#include <utility>
#include <vector>

#include "drape/scene/scene.h"
#include "shared_data.h"

namespace drape::test {

inline std::vector<std::pair<std::string, std::string>> nothingHoldsIt() {
  return {{"fabric.stretch_warp", "1e-3"}, {"fabric.stretch_weft", "1e-3"}, {"fabric.shear", "0"},
          {"fabric.bend_warp", "0"},       {"fabric.bend_weft", "0"},       {"sim.gravity", "-1000"},
          {"solver.newton.h_max", "0.1"},  {"solver.max_sim_time", "0.5"}};
}

inline std::vector<std::pair<std::string, std::string>> nothingHoldsItButTheBody() {
  auto overrides = nothingHoldsIt();
  overrides.emplace_back("fabric.friction", "5");
  return overrides;
}

inline Scene sceneWith(const std::string& file, std::vector<std::pair<std::string, std::string>> overrides) {
  SceneRequest request;
  request.input = assetsDir() / "scenes" / file;
  request.overrides = std::move(overrides);
  return loadScene(request);
}

}  // namespace drape::test
