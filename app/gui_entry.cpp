#include "gui_entry.h"

#include <iostream>

namespace drape::app {

int runGui(int argc, char** argv, const CliOptions& options) {
  // The desktop application lands with issue 7; until then point at the headless modes.
  std::cerr << "drape: the desktop application is not available yet; headless modes:\n\n" << usageText();
  return 2;
}

}  // namespace drape::app
