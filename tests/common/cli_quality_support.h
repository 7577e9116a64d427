#pragma once
// What the tests of the quality verdict through the executable share (tests/cli/cli_quality_test.cpp and the garment
// too small for its body, tests/slow/cli_quality_small_garment_test.cpp): drape run in their scratch folder, the
// largest stretch of a written OBJ, and the lines of drape's output that start with a prefix. In an anonymous
// namespace, as they were in the test file: the other command-line tests' helpers of the same names (drape() in
// batch_manifests.h, for one) end up in the same test executable.
#include <Eigen/Dense>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "run_process.h"
#include "shared_data.h"

namespace drape::test {
namespace {

const std::filesystem::path kScratch = testOutputDir() / "cli_quality";

inline ProcessResult drape(const std::string& args) {
  return runProcess(quote(DRAPE_EXECUTABLE) + " " + args + " </dev/null", kScratch);
}

// The largest principal stretch minus one over the faces of an OBJ written by drape: v (metres), vt (the pattern
// coordinates, metres) and f a/a/a lines, from the singular values of each face's deformation gradient.
inline double maxStretchOfObj(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::vector<Eigen::Vector3d> v;
  std::vector<Eigen::Vector2d> vt;
  double best = -1.0;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream ss(line);
    std::string tag;
    ss >> tag;
    if (tag == "v") {
      Eigen::Vector3d p;
      ss >> p.x() >> p.y() >> p.z();
      v.push_back(p);
    } else if (tag == "vt") {
      Eigen::Vector2d p;
      ss >> p.x() >> p.y();
      vt.push_back(p);
    } else if (tag == "f") {
      int idx[3];
      for (int& k : idx) {
        std::string corner;
        ss >> corner;
        k = std::stoi(corner.substr(0, corner.find('/'))) - 1;
      }
      Eigen::Matrix2d dm;
      dm << vt[idx[1]] - vt[idx[0]], vt[idx[2]] - vt[idx[0]];
      Eigen::Matrix<double, 3, 2> ds;
      ds << v[idx[1]] - v[idx[0]], v[idx[2]] - v[idx[0]];
      const Eigen::Matrix<double, 3, 2> f = ds * dm.inverse();
      best = std::max(best, Eigen::JacobiSVD<Eigen::Matrix<double, 3, 2>>(f).singularValues()(0) - 1.0);
    }
  }
  return best;
}

inline int countLines(const std::string& text, const std::string& prefix) {
  int n = 0;
  for (size_t at = text.find(prefix); at != std::string::npos; at = text.find(prefix, at + 1))
    n += at == 0 || text[at - 1] == '\n';
  return n;
}

}  // namespace
}  // namespace drape::test
