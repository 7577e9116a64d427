// Fuzzes the scene loader: the bytes as a scene file beside the assets' patterns, avatars and fabrics (so that the
// library scenes' relative paths resolve), loaded with a 3 cm mesh. Bad input ends in one InputError.
#include <cstddef>
#include <cstdint>

#include "drape/core/input_error.h"
#include "drape/scene/scene.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  drape::SceneRequest request;
  request.input = drape::fuzz::inputFile(data, size, ".json");
  request.overrides = {{"mesh.target_edge_length", "0.03"}};
  try {
    (void)drape::loadScene(request);
  } catch (const drape::InputError&) {
  }
  return 0;
}
