#pragma once
// What the tests of stiff fabrics' previews share (tests/unit/stiff_fabric_preview_test.cpp and the torn cotton
// preview's retry, tests/slow/stiff_fabric_preview_retry_test.cpp): the default scene's t-shirt in a fabric preset
// with settings overridden.
#include <string>
#include <utility>
#include <vector>

#include "drape/scene/scene.h"
#include "shared_data.h"

namespace drape::test {

using Overrides = std::vector<std::pair<std::string, std::string>>;

// The default scene's t-shirt in `fabric` (a preset), settings overridden.
inline Scene defaultTshirt(const char* fabric, Overrides overrides) {
  SceneRequest request;
  request.input = assetsDir() / "scenes" / "default.json";
  request.fabricPreset = fabric;
  request.overrides = std::move(overrides);
  return loadScene(request);
}

inline bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace drape::test
