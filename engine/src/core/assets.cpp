#include "drape/core/assets.h"

#include <cstdlib>

namespace drape {

std::filesystem::path assetsDir() {
  if (const char* env = std::getenv("DRAPE_ASSETS"); env && *env) return env;
  return DRAPE_DEFAULT_ASSETS_DIR;
}

}  // namespace drape
