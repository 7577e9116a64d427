#include "fuzz_input.h"

#include <unistd.h>

#include <fstream>

namespace drape::fuzz {

const std::filesystem::path& scratchDir() {
  static const std::filesystem::path dir = [] {
    namespace fs = std::filesystem;
    const fs::path d = fs::temp_directory_path() / ("drape_fuzz_" + std::to_string(getpid()));
    fs::create_directories(d / "scenes");
    for (const char* sub : {"patterns", "avatars", "fabrics"}) {
      std::error_code ec;
      fs::create_directory_symlink(fs::path(DRAPE_ASSETS_DIR) / sub, d / sub, ec);
    }
    return d;
  }();
  return dir;
}

std::filesystem::path inputFile(const std::uint8_t* data, std::size_t size, const std::string& extension) {
  const std::filesystem::path file = scratchDir() / "scenes" / ("input" + extension);
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return file;
}

}  // namespace drape::fuzz
