#pragma once
// The headless modes of `drape`. Each returns the process exit status and throws InputError for bad input.
#include <iosfwd>

#include "cli_options.h"

namespace drape::app {

int runInfo(const CliOptions& options, std::ostream& out);
int runSimulate(const CliOptions& options, std::ostream& out);
int runRender(const CliOptions& options, std::ostream& out);
int runListSettings(std::ostream& out);
int runListFabrics(std::ostream& out);

}  // namespace drape::app
