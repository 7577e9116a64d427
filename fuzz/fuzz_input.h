#pragma once
// What the fuzz harnesses share: an input is handed to a loader, and bad input must end in one InputError (the
// message the CLI prints). Anything else (another exception, a crash, a sanitizer report, a hang) is a finding.
// Loaders that read files get the input as a file in a per-process scratch directory whose patterns/, avatars/ and
// fabrics/ link to the repository's assets, so that a scene's relative paths resolve as in assets/scenes/.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

namespace drape::fuzz {

// The scratch directory (created once): DIR/scenes is where inputFile writes, DIR/{patterns,avatars,fabrics} link to
// the assets.
const std::filesystem::path& scratchDir();
// Writes the input bytes to DIR/scenes/input<extension> and returns that path.
std::filesystem::path inputFile(const std::uint8_t* data, std::size_t size, const std::string& extension);

}  // namespace drape::fuzz
