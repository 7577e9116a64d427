#include "avatar/ply_header.h"

#include <fstream>
#include <sstream>

namespace drape::detail {

std::string plyHeaderProblem(const std::filesystem::path& file, bool namedPly) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return "";  // assimp says why it cannot open it
  std::error_code ec;
  const auto size = std::filesystem::file_size(file, ec);
  std::size_t read = 0;
  std::string line;
  bool first = true;
  while (read < kMaxPlyHeaderBytes && std::getline(in, line)) {
    read += line.size() + 1;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (first && line != "ply") return namedPly ? "PLY header: the first line is not 'ply'" : "";
    first = false;
    if (line == "end_header") return "";
    std::istringstream words(line);
    std::string keyword, name;
    unsigned long long count = 0;
    if (words >> keyword && keyword == "element" && words >> name >> count && !ec && count > size)
      return "PLY header: element '" + name + "' declares " + std::to_string(count) + " items in a file of " +
             std::to_string(size) + " bytes";
  }
  return "PLY header: no 'end_header' line in its first " + std::to_string(kMaxPlyHeaderBytes) + " bytes";
}

}  // namespace drape::detail
