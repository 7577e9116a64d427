// Fuzzes the pattern loader (GarmentCode JSON) on bytes, then meshes what loads at 3 cm: bad input ends in one
// InputError.
#include <cstddef>
#include <cstdint>
#include <string>

#include "drape/core/input_error.h"
#include "drape/garment/garment_builder.h"
#include "drape/pattern/pattern_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const drape::Pattern pattern =
        drape::parsePattern(std::string(reinterpret_cast<const char*>(data), size), "fuzz.json");
    drape::MeshingOptions options;
    options.targetEdgeLength = 0.03;
    (void)drape::buildGarment(pattern, options);
  } catch (const drape::InputError&) {
  }
  return 0;
}
