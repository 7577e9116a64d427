#pragma once
// The `drape` command line: one mode plus its options.
#include <string>
#include <utility>
#include <vector>

#include "drape/scene/scene.h"

namespace drape::app {

enum class Mode {
  Gui,
  Help,
  Version,
  Info,
  Simulate,
  Render,
  Bench,
  TradePlot,
  ScalingPlot,
  WritePattern,
  TradeLevels,
  MakeAvatar,
  Batch,
  ListSettings,
  ListFabrics
};

struct CliOptions {
  Mode mode = Mode::Gui;
  SceneRequest scene;                  // input file, --avatar, --avatar-units, --fabric, --set
  std::string output;                  // -o
  std::string stats;                   // --stats
  std::string png;                     // --png (simulate: also render the final state)
  std::string solver;                  // --solver none|preview|drape|full (empty: the scene's solver.stage)
  std::string simulateStage = "none";  // --simulate value in --render mode (renders the placed garment by default)
  std::string view = "three-quarter";  // --view
  bool viewGiven = false;              // --view was on the command line
  std::string renderMode = "shaded";   // --mode
  int width = 1024, height = 768;      // --size WxH
  double maxSimTime = -1.0;            // --max-sim-time
  std::string from;                    // --from STATE.obj (simulate, render): the stage starts at its positions
  std::vector<std::string> sweeps;     // --sweep KEY=V1,V2 (bench)
  bool extremes = false;               // --extremes (bench): the extremes grid instead of the trade
  std::vector<std::string> cells;      // --cell NAME (extremes): only these cells; none: all
  bool levels = false;                 // --levels (bench): run the speed/accuracy level candidates
  std::string reference;               // --reference FILE (bench): the reference drape, kept there and reused
  std::string plot;                    // --plot FILE.png (bench): the report's Pareto plot
  int rounds = 1;                      // --rounds N (bench): every run N times, interleaved; the fastest counts
  std::vector<std::string> reports;    // the reports of --trade-plot, --trade-levels, --scaling-plot
  std::string batch;                   // --batch MANIFEST.json
  int jobs = 0;                        // --jobs N (batch): jobs at a time; 0: the core count
  bool list = false;                   // --list (batch): print the job list, run nothing
  int shardIndex = 0, shardCount = 0;  // --shard I/N (batch): only the jobs whose index is I modulo N; 0: all
  bool gather = false;                 // --gather (batch): write the summary and contact sheet, run nothing
  bool slurm = false;                  // --slurm (batch): submit a Slurm job array instead of running here
  std::string partition;               // --partition P (slurm)
  std::string timeLimit;               // --time T (slurm), as sbatch takes it
  int cpusPerTask = 0;                 // --cpus-per-task N (slurm); 0: the cluster's default
  int tasks = 0;                       // --tasks N (slurm): array tasks; 0: one per job, at most kMaxArrayTasks
  int threads = 0;                     // --threads N (every mode): at most N threads; 0: every core
};

// Slurm's default MaxArraySize is 1001: array indices 0..1000.
constexpr int kMaxArrayTasks = 1000;

// Parses argv; throws InputError with a one-line message for anything malformed.
CliOptions parseCommandLine(int argc, char** argv);

std::string usageText();

}  // namespace drape::app
