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
// --bench --extremes: the extremes grid (drape/sim/extremes_grid.h) on the scene, in --solver's stage or all three.
int runExtremes(const CliOptions& options, std::ostream& out);
// --trade-plot REPORT.json... -o TRADE.png: the Pareto plot of trade reports (trade_report.cpp).
int runTradePlot(const CliOptions& options, std::ostream& out);
// --scaling-plot SCALING.json -o SCALING.png: time to rest and peak memory against vertices (scaling_plot.cpp).
int runScalingPlot(const CliOptions& options, std::ostream& out);
// --write-pattern PATTERN -o OUT.(json|dxf|pdf|svg): the pattern as GarmentCode JSON, DXF-AAMA or printed at full
// scale (write_pattern_command.cpp).
int runWritePattern(const CliOptions& options, std::ostream& out);
// --trade-levels REPORT.json... -o LEVELS.json: the GUI's speed/accuracy levels from the reports' candidates.
int runTradeLevels(const CliOptions& options, std::ostream& out);
int runMakeAvatar(const CliOptions& options, std::ostream& out);
// --batch MANIFEST -o OUTDIR: every job of the manifest in child processes (batch_command.cpp); --list: the job list.
int runBatch(const CliOptions& options, std::ostream& out);
// Exit status of a batch in which some jobs failed (the summary and contact sheet are still written).
constexpr int kBatchJobsFailedExit = 5;

// The scene's camera settings: a preset view, or an explicit eye (and target, up) when camera.eye is set.
struct SceneCamera {
  std::string view = "three-quarter";
  double fovDegrees = 35.0;
  bool explicitEye = false;
  bool explicitTarget = false;
  Eigen::Vector3d eye = Eigen::Vector3d::Zero();
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
  Eigen::Vector3d up = Eigen::Vector3d::UnitY();
};
SceneCamera sceneCamera(const Settings& settings);

// Draws snapshot with the command line's --view/--size/--mode (the scene's camera when --view is not given) and
// writes the PNG atomically. Throws InputError for bad paths or no GL context.
void renderToPng(const Snapshot& snapshot, const CliOptions& options, const SceneCamera& camera,
                 const std::filesystem::path& output, std::ostream& out);
// Throws InputError naming file when its directory does not exist or is not writable.
void checkWritableDirectory(const std::filesystem::path& file);
// Throws InputError unless output ends in .png.
void checkPngPath(const std::filesystem::path& output, const std::string& option);
int runListSettings(std::ostream& out);
int runListFabrics(std::ostream& out);

}  // namespace drape::app
