#pragma once
// What the tests of the pipeline's preview -> drape hand-off share (tests/unit/sim/pipeline_handoff_test.cpp and the
// library garments' hand-offs, tests/slow/pipeline_handoff_drape_test.cpp): a library scene with settings overridden.
#include <string>
#include <utility>
#include <vector>

#include "drape/scene/scene.h"
#include "shared_data.h"

namespace drape::test {

using Overrides = std::vector<std::pair<std::string, std::string>>;

// A library scene (assets/scenes/<file>) with settings overridden.
inline Scene libraryScene(const char* file, Overrides overrides) {
  SceneRequest request;
  request.input = assetsDir() / "scenes" / file;
  request.overrides = std::move(overrides);
  return loadScene(request);
}

}  // namespace drape::test
