#pragma once
// Writes a copy of an OBJ file with every vertex line's coordinates multiplied by a factor and everything else as
// it was: a body in other length units, for the tests of the avatar units warning.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace drape::test {

inline void writeScaledObj(const std::filesystem::path& original, double factor, const std::filesystem::path& to) {
  std::ifstream in(original);
  std::ofstream out(to);
  out.precision(9);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("v ", 0) == 0) {
      std::istringstream coords(line.substr(2));
      double x, y, z;
      coords >> x >> y >> z;
      out << "v " << x * factor << " " << y * factor << " " << z * factor << "\n";
    } else {
      out << line << "\n";
    }
  }
}

}  // namespace drape::test
