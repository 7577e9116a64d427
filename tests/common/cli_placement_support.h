#pragma once
// What the tests of placement.fit through the executable share (tests/cli/cli_placement_test.cpp and the broad, tall
// mannequin's, tests/slow/cli_placement_fit_test.cpp): drape run in their scratch folder, and the vertices of the OBJ
// files it writes. In an anonymous namespace, as they were in the test file: the other command-line tests' helpers of
// the same names (drape() in batch_manifests.h, for one) end up in the same test executable.
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "run_process.h"
#include "shared_data.h"

namespace drape::test {
namespace {

const std::filesystem::path kScratch = testOutputDir() / "cli_placement";

inline ProcessResult drape(const std::string& args) {
  std::filesystem::create_directories(kScratch);
  return runProcess(quote(DRAPE_EXECUTABLE) + " " + args + " </dev/null", kScratch);
}

inline std::string path(const std::string& name) {
  return quote((kScratch / name).string());
}

// The "v x y z" lines of an OBJ file.
inline std::vector<std::array<double, 3>> objVertices(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::vector<std::array<double, 3>> out;
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("v ", 0) == 0) {
      std::istringstream s(line.substr(2));
      std::array<double, 3> v{};
      s >> v[0] >> v[1] >> v[2];
      out.push_back(v);
    }
  return out;
}

inline double maxDistance(const std::vector<std::array<double, 3>>& a, const std::vector<std::array<double, 3>>& b) {
  double d = 0.0;
  for (size_t i = 0; i < a.size(); ++i)
    d = std::max(d, std::hypot(a[i][0] - b[i][0], a[i][1] - b[i][1], a[i][2] - b[i][2]));
  return d;
}

}  // namespace
}  // namespace drape::test
