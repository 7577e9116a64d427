// drape --make-avatar end to end through the executable: two runs make the same mannequin from the same measurements.
// A bad measurement file is checked in tests/cli/cli_solver_render_test.cpp.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cli_solver_support.h"
#include "run_process.h"

namespace drape::test {
namespace {

// Two runs write the same file: a batch's mannequin is the same body whichever run or node made it.
TEST(CliMakeAvatar, BuildsTheSameMannequinFromMeasurementsInEveryRun) {
  const auto body = kScratch / "female.obj", again = kScratch / "again" / "female.obj";
  std::filesystem::create_directories(again.parent_path());
  auto r = drape("--make-avatar " + asset("avatars/female.yaml") + " -o " + quote(body.string()));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  auto info = drape("--info " + quote(body.string()));
  ASSERT_EQ(info.exitCode, 0) << info.err;
  EXPECT_NE(info.out.find("triangles: 2"), std::string::npos) << info.out;  // 20k-29k triangles
  r = drape("--make-avatar " + asset("avatars/female.yaml") + " -o " + quote(again.string()));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_TRUE(readWhole(body) == readWhole(again));
}

}  // namespace
}  // namespace drape::test
