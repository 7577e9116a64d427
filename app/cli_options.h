#pragma once
// The `drape` command line: one mode plus its options.
#include <string>
#include <utility>
#include <vector>

#include "drape/scene/scene.h"

namespace drape::app {

enum class Mode { Gui, Help, Version, Info, Simulate, Render, Bench, MakeAvatar, Batch, ListSettings, ListFabrics };

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
  std::string batch;                   // --batch MANIFEST.json
  int jobs = 0;                        // --jobs N (batch): jobs at a time; 0: the core count
  bool list = false;                   // --list (batch): print the job list, run nothing
};

// Parses argv; throws InputError with a one-line message for anything malformed.
CliOptions parseCommandLine(int argc, char** argv);

std::string usageText();

}  // namespace drape::app
