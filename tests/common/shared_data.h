#pragma once
// Access to ../shared/data (real-world patterns and bodies). Where it is absent the test is skipped with a
// message; with DRAPE_REQUIRE_SHARED_DATA=1 in the environment (CI) its absence fails the test instead.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace drape::test {

inline std::filesystem::path sharedDataDir() {
  if (const char* env = std::getenv("DRAPE_SHARED_DATA")) return env;
  return DRAPE_SHARED_DATA_DIR;
}

inline bool sharedDataRequired() {
  const char* env = std::getenv("DRAPE_REQUIRE_SHARED_DATA");
  return env && std::string(env) == "1";
}

inline std::filesystem::path testDataDir() { return DRAPE_TEST_DATA_DIR; }
inline std::filesystem::path assetsDir() { return DRAPE_ASSETS_DIR; }
inline std::filesystem::path testOutputDir() { return DRAPE_TEST_OUTPUT_DIR; }

}  // namespace drape::test

// Use at the top of a test: yields the path of a file under ../shared/data, or skips (fails in CI).
#define DRAPE_SHARED_FILE(var, relative)                                                                 \
  const std::filesystem::path var = ::drape::test::sharedDataDir() / (relative);                        \
  if (!std::filesystem::exists(var)) {                                                                   \
    if (::drape::test::sharedDataRequired()) FAIL() << "required shared data file missing: " << var;    \
    GTEST_SKIP() << "shared data not found (" << var << "); clone ../shared beside the repository to run"; \
  }
