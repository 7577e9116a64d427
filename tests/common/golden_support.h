#pragma once
// Golden-image comparison for render tests. DRAPE_BLESS=1 in the environment rewrites the golden files
// instead of comparing (see docs/RENDERING.md); on a mismatch the actual image and a diff image are
// written to testOutputDir() and the test fails with their paths.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "drape/render/image_compare.h"
#include "drape/render/png_io.h"
#include "shared_data.h"

namespace drape::test {

// The tolerance of every golden test: llvmpipe is deterministic, so identical inputs give identical
// pixels; the slack absorbs rounding differences between Mesa builds, while one changed triangle (tens of
// pixels at 256 x 256) exceeds it (see comparison_sensitivity_test.cpp).
inline render::CompareTolerance goldenTolerance() { return {8, 0.9997}; }

inline std::filesystem::path goldenDir() { return std::filesystem::path(DRAPE_RENDER_GOLDEN_DIR); }

inline bool blessing() {
  const char* env = std::getenv("DRAPE_BLESS");
  return env && std::string(env) == "1";
}

inline ::testing::AssertionResult matchesGolden(const render::Image& actual, const std::string& name) {
  const std::filesystem::path golden = goldenDir() / (name + ".png");
  if (blessing()) {
    render::writePng(golden, actual);
    return ::testing::AssertionSuccess() << "blessed " << golden;
  }
  if (!std::filesystem::exists(golden))
    return ::testing::AssertionFailure() << "golden image " << golden
                                         << " is missing; run with DRAPE_BLESS=1 to create it";
  const render::Image expected = render::readPng(golden);
  const render::CompareResult result = render::compareImages(expected, actual, goldenTolerance());
  if (result.matches) return ::testing::AssertionSuccess() << result.summary();
  std::filesystem::create_directories(testOutputDir());
  const auto actualPath = testOutputDir() / (name + ".actual.png");
  const auto diffPath = testOutputDir() / (name + ".diff.png");
  render::writePng(actualPath, actual);
  if (result.sameSize) render::writePng(diffPath, result.diff);
  return ::testing::AssertionFailure() << name << ": " << result.summary() << "; actual: " << actualPath
                                       << ", diff: " << diffPath;
}

}  // namespace drape::test
