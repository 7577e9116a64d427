#pragma once
// What the tests of drape --simulate, --render, --bench and --make-avatar through the executable share
// (tests/cli/cli_solver_render_test.cpp, and tests/slow/cli_bench_extremes_test.cpp and
// tests/slow/cli_make_avatar_test.cpp): drape run in their scratch folder, and an asset's quoted path. In an anonymous
// namespace, as they were in the test file: the other command-line tests' helpers of the same names (drape() in
// batch_manifests.h, for one) end up in the same test executable.
#include <filesystem>
#include <string>

#include "run_process.h"
#include "shared_data.h"

namespace drape::test {
namespace {

const std::filesystem::path kScratch = testOutputDir() / "cli_solver";

inline ProcessResult drape(const std::string& args) {
  return runProcess(quote(DRAPE_EXECUTABLE) + " " + args + " </dev/null", kScratch);
}

inline std::string asset(const std::string& relative) {
  return quote((assetsDir() / relative).string());
}

}  // namespace
}  // namespace drape::test
