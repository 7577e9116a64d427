// drape --render SCENE -o OUT.png: filled in when the renderer lands (issue 3).
#include <ostream>

#include "commands.h"
#include "drape/core/input_error.h"

namespace drape::app {

int runRender(const CliOptions& options, std::ostream& out) {
  throw InputError("--render: the renderer is not available yet");
}

}  // namespace drape::app
