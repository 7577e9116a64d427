#pragma once
// The headless modes of `drape`. Each returns the process exit status and throws InputError for bad input.
#include <filesystem>
#include <iosfwd>
#include <string>

#include "cli_options.h"
#include "drape/sim/snapshot.h"

namespace drape::app {

int runInfo(const CliOptions& options, std::ostream& out);
int runSimulate(const CliOptions& options, std::ostream& out);
int runRender(const CliOptions& options, std::ostream& out);
int runBench(const CliOptions& options, std::ostream& out);
int runMakeAvatar(const CliOptions& options, std::ostream& out);

// Draws snapshot with the command line's --view/--size/--mode (cameraView and fov: the scene's camera settings
// when --view is not given) and writes the PNG atomically. Throws InputError for bad paths or no GL context.
void renderToPng(const Snapshot& snapshot, const CliOptions& options, const std::string& cameraView, double fov,
                 const std::filesystem::path& output, std::ostream& out);
// Throws InputError naming file when its directory does not exist or is not writable.
void checkWritableDirectory(const std::filesystem::path& file);
// Throws InputError unless output ends in .png.
void checkPngPath(const std::filesystem::path& output, const std::string& option);
int runListSettings(std::ostream& out);
int runListFabrics(std::ostream& out);

}  // namespace drape::app
