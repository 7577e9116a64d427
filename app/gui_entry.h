#pragma once
// Starts the desktop application (or explains why it cannot) for `drape [SCENE]`.
#include "cli_options.h"

namespace drape::app {

int runGui(int argc, char** argv, const CliOptions& options);

}  // namespace drape::app
