// placement.fit through the executable: `--simulate SCENE --solver none` writes the placed garment, which is the
// same with the fit on and off for a pattern laid out for its avatar; on a mannequin made with --make-avatar from
// measurements 15 % broader at the shoulders and 10 % taller, the GarmentCode shirt's panels are moved and named in
// warnings.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <fstream>
#include <sstream>
#include <vector>

#include "run_process.h"
#include "shared_data.h"

namespace drape::test {
namespace {

const std::filesystem::path kScratch = testOutputDir() / "cli_placement";

ProcessResult drape(const std::string& args) {
  std::filesystem::create_directories(kScratch);
  return runProcess(quote(DRAPE_EXECUTABLE) + " " + args + " </dev/null", kScratch);
}

std::string path(const std::string& name) {
  return quote((kScratch / name).string());
}

// The "v x y z" lines of an OBJ file.
std::vector<std::array<double, 3>> objVertices(const std::filesystem::path& file) {
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

double maxDistance(const std::vector<std::array<double, 3>>& a, const std::vector<std::array<double, 3>>& b) {
  double d = 0.0;
  for (size_t i = 0; i < a.size(); ++i)
    d = std::max(d, std::hypot(a[i][0] - b[i][0], a[i][1] - b[i][1], a[i][2] - b[i][2]));
  return d;
}

TEST(CliPlacement, PatternLaidOutForItsAvatarIsPlacedAlikeWithTheFitOnAndOff) {
  const std::string scene = quote((assetsDir() / "scenes" / "tshirt.json").string());
  const auto on = drape("--simulate " + scene + " --solver none -o " + path("fit_on.obj"));
  ASSERT_EQ(on.exitCode, 0) << on.err;
  EXPECT_EQ(on.out.find("placement: panel"), std::string::npos) << on.out;
  const auto off = drape("--simulate " + scene + " --solver none --set placement.fit=false -o " + path("fit_off.obj"));
  ASSERT_EQ(off.exitCode, 0) << off.err;
  const auto a = objVertices(kScratch / "fit_on.obj"), b = objVertices(kScratch / "fit_off.obj");
  ASSERT_EQ(a.size(), b.size());
  ASSERT_FALSE(a.empty());
  EXPECT_LT(maxDistance(a, b), 0.01);
}

TEST(CliPlacement, ShirtOnABroaderTallerMannequinIsMovedWithAWarningPerPanel) {
  DRAPE_SHARED_FILE(shirt, "garmentcode/shirt_mean_specification.json");
  const auto made = drape("--make-avatar " + quote((testDataDir() / "bodies" / "broad_tall.yaml").string()) + " -o " +
                          path("broad_tall.obj"));
  ASSERT_EQ(made.exitCode, 0) << made.err;
  const std::string common = "--simulate " + quote(shirt.string()) + " --avatar " + path("broad_tall.obj") +
                             " --set mesh.target_edge_length=0.03 --solver none ";
  const auto fitted = drape(common + "-o " + path("shirt_fitted.obj"));
  ASSERT_EQ(fitted.exitCode, 0) << fitted.err;
  for (const char* panel : {"left_sleeve_f", "right_sleeve_b", "left_ftorso"})
    EXPECT_NE(fitted.out.find("shirt_mean_specification.json: placement: panel '" + std::string(panel) + "' moved"),
              std::string::npos)
        << panel << "\n"
        << fitted.out;
  const auto asLaidOut = drape(common + "--set placement.fit=false -o " + path("shirt_as_laid_out.obj"));
  ASSERT_EQ(asLaidOut.exitCode, 0) << asLaidOut.err;
  EXPECT_EQ(asLaidOut.out.find("placement: panel"), std::string::npos);
  // The torso went up to the taller body's shoulders: more than 10 cm.
  const auto a = objVertices(kScratch / "shirt_fitted.obj"), b = objVertices(kScratch / "shirt_as_laid_out.obj");
  ASSERT_EQ(a.size(), b.size());
  EXPECT_GT(maxDistance(a, b), 0.10);
}

}  // namespace
}  // namespace drape::test
