#pragma once
// Where Drape's bundled assets (fabrics, scenes, avatars, patterns) are found.
#include <filesystem>

namespace drape {

// $DRAPE_ASSETS if set, else the assets/ folder of the source tree this binary was built from.
std::filesystem::path assetsDir();

}  // namespace drape
