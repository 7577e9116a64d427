#pragma once
// Writes a file atomically: the content goes to a temporary file in the same directory, which is then
// renamed over the target, so a reader never sees a half-written file and a failure leaves the old one.
#include <filesystem>
#include <functional>
#include <string>

namespace drape {

// Calls write(tempPath) to produce the content, then renames it to target. Throws InputError naming target
// when the directory is not writable or write fails; the temporary file is removed on failure.
void writeFileAtomically(const std::filesystem::path& target,
                         const std::function<void(const std::filesystem::path& tempPath)>& write);

// Convenience: writes the bytes atomically.
void writeFileAtomically(const std::filesystem::path& target, const std::string& bytes);

}  // namespace drape
