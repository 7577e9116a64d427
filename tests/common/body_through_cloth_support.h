#pragma once
// What the renders of real garments share (tests/render/body_through_cloth_test.cpp and the finished drapes,
// tests/slow/body_through_cloth_test.cpp): a pattern on an avatar at 2 cm in a stage of the solver.
#include <filesystem>
#include <string>

#include "drape/scene/scene.h"

namespace drape::test {

inline Scene sceneOf(const std::filesystem::path& pattern, const std::filesystem::path& avatar,
                     const std::string& stage) {
  SceneRequest request;
  request.input = pattern;
  request.avatarFile = avatar.string();
  request.overrides = {{"mesh.target_edge_length", "0.02"}, {"solver.stage", stage}, {"solver.max_sim_time", "1.5"}};
  return loadScene(request);
}

}  // namespace drape::test
