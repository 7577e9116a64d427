// Fuzzes the avatar loader (through assimp): the bytes as an OBJ, a binary glTF and a PLY file. Bad input ends in one
// InputError.
#include <cstddef>
#include <cstdint>

#include "drape/avatar/avatar_loader.h"
#include "drape/core/input_error.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  for (const char* extension : {".obj", ".glb", ".ply"}) {
    try {
      (void)drape::loadAvatar(drape::fuzz::inputFile(data, size, extension));
    } catch (const drape::InputError&) {
    }
  }
  return 0;
}
