// Fuzzes the body-measurement loader (GarmentCode YAML and JSON): the bytes as a .yaml file, then as a .json file.
// Bad input ends in one InputError.
#include <cstddef>
#include <cstdint>

#include "drape/avatar/body_measurements.h"
#include "drape/core/input_error.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  for (const char* extension : {".yaml", ".json"}) {
    try {
      (void)drape::loadBodyMeasurements(drape::fuzz::inputFile(data, size, extension));
    } catch (const drape::InputError&) {
    }
  }
  return 0;
}
