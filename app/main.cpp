// The `drape` executable. Headless modes never create a QApplication; any error becomes one line on stderr
// and exit status 1.
#include <tbb/global_control.h>

#include <exception>
#include <iostream>
#include <memory>

#include "cli_options.h"
#include "commands.h"
#include "drape/core/input_error.h"
#include "gui_entry.h"

int main(int argc, char** argv) {
  using namespace drape::app;
  try {
    const CliOptions options = parseCommandLine(argc, argv);
    // --threads caps the engine's TBB pool (a batch gives each of its parallel jobs its share of the cores).
    std::unique_ptr<tbb::global_control> threadCap;
    if (options.threads > 0)
      threadCap = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                        static_cast<size_t>(options.threads));
    switch (options.mode) {
      case Mode::Help: std::cout << usageText(); return 0;
      case Mode::Version: std::cout << "drape " << DRAPE_VERSION << "\n"; return 0;
      case Mode::ListSettings: return runListSettings(std::cout);
      case Mode::ListFabrics: return runListFabrics(std::cout);
      case Mode::Info: return runInfo(options, std::cout);
      case Mode::Simulate: return runSimulate(options, std::cout);
      case Mode::Render: return runRender(options, std::cout);
      case Mode::Bench: return runBench(options, std::cout);
      case Mode::TradePlot: return runTradePlot(options, std::cout);
      case Mode::ScalingPlot: return runScalingPlot(options, std::cout);
      case Mode::WritePattern: return runWritePattern(options, std::cout);
      case Mode::TradeLevels: return runTradeLevels(options, std::cout);
      case Mode::MakeAvatar: return runMakeAvatar(options, std::cout);
      case Mode::Batch: return runBatch(options, std::cout);
      case Mode::Gui: return runGui(argc, argv, options);
    }
  } catch (const drape::InputError& e) {
    std::cerr << "drape: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "drape: internal error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
