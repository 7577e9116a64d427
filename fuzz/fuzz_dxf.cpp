// Fuzzes the DXF-AAMA reader (libdxflib behind a scan of the raw file) on bytes, then meshes what loads at 3 cm: bad
// input ends in one InputError.
#include <cstddef>
#include <cstdint>

#include "drape/core/input_error.h"
#include "drape/garment/garment_builder.h"
#include "drape/pattern/dxf_aama.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const drape::Pattern pattern = drape::readDxfAamaPattern(drape::fuzz::inputFile(data, size, ".dxf"));
    drape::MeshingOptions options;
    options.targetEdgeLength = 0.03;
    (void)drape::buildGarment(pattern, options);
  } catch (const drape::InputError&) {
  }
  return 0;
}
