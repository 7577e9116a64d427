// Exit codes and messages of the drape executable's headless modes.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "run_process.h"
#include "shared_data.h"

namespace drape::test {
namespace {

const std::filesystem::path kScratch = testOutputDir() / "cli";

ProcessResult drape(const std::string& args) {
  return runProcess(quote(DRAPE_EXECUTABLE) + " " + args + " </dev/null", kScratch);
}

std::string asset(const std::string& relative) { return quote((assetsDir() / relative).string()); }

TEST(Cli, HelpAndVersion) {
  auto help = drape("--help");
  EXPECT_EQ(help.exitCode, 0);
  EXPECT_NE(help.out.find("--info FILE"), std::string::npos);
  EXPECT_NE(help.out.find("--set KEY=VALUE"), std::string::npos);
  auto version = drape("--version");
  EXPECT_EQ(version.exitCode, 0);
  EXPECT_EQ(version.out.rfind("drape ", 0), 0u);
}

TEST(Cli, UnknownOptionIsOneLineError) {
  auto r = drape("--frobnicate");
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("unknown option '--frobnicate'"), std::string::npos);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1);
}

TEST(Cli, InfoOnDefaultScene) {
  auto r = drape("--info " + asset("scenes/tablecloth.json"));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("panels: 1"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("triangles:"), std::string::npos);
  EXPECT_NE(r.out.find("bounding box:"), std::string::npos);
  EXPECT_NE(r.out.find("collider: sphere"), std::string::npos);
}

TEST(Cli, InfoOnMissingFileNamesIt) {
  auto r = drape("--info /nonexistent/scene.json");
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("/nonexistent/scene.json"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("not found"), std::string::npos) << r.err;
}

TEST(Cli, InfoOnMalformedPatternNamesFileAndElement) {
  auto r = drape("--info " + quote((testDataDir() / "bad" / "scene_unknown_key.json").string()));
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("scene_unknown_key.json"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("unknown key 'colour'"), std::string::npos) << r.err;
}

TEST(Cli, SetOverridesASettingAndChangesTheMesh) {
  auto coarse = drape("--info " + asset("scenes/tablecloth.json") + " --set mesh.target_edge_length=0.1");
  auto fine = drape("--info " + asset("scenes/tablecloth.json") + " --set mesh.target_edge_length=0.05");
  ASSERT_EQ(coarse.exitCode, 0) << coarse.err;
  ASSERT_EQ(fine.exitCode, 0) << fine.err;
  auto triangles = [](const std::string& out) {
    const auto g = out.find("garment");
    const auto t = out.find("triangles: ", g);
    return std::stoi(out.substr(t + 11));
  };
  // Halving the edge length roughly quadruples the triangle count.
  const double ratio = double(triangles(fine.out)) / triangles(coarse.out);
  EXPECT_GT(ratio, 2.5);
  EXPECT_LT(ratio, 6.0);
}

TEST(Cli, UnknownSetKeyListsValidKeys) {
  auto r = drape("--info " + asset("scenes/tablecloth.json") + " --set mesh.edge=0.1");
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("unknown setting 'mesh.edge'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("mesh.target_edge_length"), std::string::npos) << r.err;
}

TEST(Cli, BadSetValueIsRejected) {
  auto r = drape("--info " + asset("scenes/tablecloth.json") + " --set mesh.target_edge_length=abc");
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("'abc' is not a number"), std::string::npos) << r.err;
}

TEST(Cli, UnknownFabricListsPresets) {
  auto r = drape("--info " + asset("scenes/tablecloth.json") + " --fabric velvet");
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("unknown fabric preset 'velvet'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("denim"), std::string::npos) << r.err;
}

TEST(Cli, SimulateNoneWritesPlacedGarmentAndStats) {
  const auto obj = kScratch / "placed.obj";
  const auto stats = kScratch / "placed_stats.json";
  std::filesystem::remove(obj);
  auto r = drape("--simulate " + asset("scenes/tablecloth.json") + " --solver none -o " + quote(obj.string()) +
                 " --stats " + quote(stats.string()));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const std::string text = readWhole(obj);
  EXPECT_NE(text.find("\nv "), std::string::npos);
  EXPECT_NE(text.find("\nvt "), std::string::npos);
  EXPECT_NE(text.find("\nf "), std::string::npos);
  const auto j = nlohmann::json::parse(readWhole(stats));
  for (const char* key : {"status", "wall_time_s", "sim_time_s", "steps", "terms", "per_step"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_GT(j.at("triangles").get<int>(), 1000);
}

// Loader and avatar warnings reach the user of every headless mode, not only --info and the stats file.
TEST(Cli, SimulateAndRenderPrintTheScenesWarnings) {
  const std::string pattern = quote((testDataDir() / "patterns" / "mismatched_stitch.json").string());
  const auto stats = kScratch / "warned_stats.json";
  // A preview cut short (not at rest): the test is about the warnings, not the quality verdict.
  auto sim = drape("--simulate " + pattern + " --solver preview --max-sim-time 0.01" +
                   " --set mesh.target_edge_length=0.05 --set quality.require_rest=false --set quality.max_strain=100 -o " +
                   quote((kScratch / "warned.obj").string()) + " --stats " + quote(stats.string()));
  ASSERT_EQ(sim.exitCode, 0) << sim.err;
  const std::string expected = "stitch 0: panel 'short' edge 0 (length 20) and panel 'long' edge 1 (length 30) differ";
  EXPECT_NE(sim.out.find("warning: " + (testDataDir() / "patterns" / "mismatched_stitch.json").string() + ": " +
                         expected), std::string::npos) << sim.out;
  const auto warnings = nlohmann::json::parse(readWhole(stats)).at("warnings");
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].get<std::string>().find(expected), std::string::npos);

  auto render = drape("--render " + pattern + " --simulate none --size 32x32 -o " +
                      quote((kScratch / "warned.png").string()));
  ASSERT_EQ(render.exitCode, 0) << render.err;
  EXPECT_NE(render.out.find("warning: "), std::string::npos) << render.out;
  EXPECT_NE(render.out.find(expected), std::string::npos) << render.out;

  // A body mesh rendered on its own: a tetrahedron wound inside out is turned outward, and says so.
  const auto body = kScratch / "inside_out_tetrahedron.obj";
  std::ofstream(body) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 4 2\nf 1 3 4\nf 2 4 3\n";
  auto mesh = drape("--render " + quote(body.string()) + " --size 32x32 -o " + quote((kScratch / "body.png").string()));
  ASSERT_EQ(mesh.exitCode, 0) << mesh.err;
  EXPECT_NE(mesh.out.find("warning: " + body.string() + ": 4 of 4 faces were wound inward"), std::string::npos)
      << mesh.out;
}

TEST(Cli, SimulateWithoutOutputFails) {
  auto r = drape("--simulate " + asset("scenes/tablecloth.json"));
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("missing -o"), std::string::npos) << r.err;
}

TEST(Cli, UnwritableOutputFailsCleanly) {
  auto r = drape("--simulate " + asset("scenes/tablecloth.json") + " -o /nonexistent-dir/out.obj");
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("/nonexistent-dir/out.obj"), std::string::npos) << r.err;
}

TEST(Cli, BarePatternWithAvatarAndFabric) {
  DRAPE_SHARED_FILE(pattern, "garmentcode/shirt_mean_specification.json");
  DRAPE_SHARED_FILE(body, "garmentcode/mean_all.obj");
  auto r = drape("--info " + quote(pattern.string()) + " --avatar " + quote(body.string()) +
                 " --avatar-units m --fabric denim");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("panels: 8"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("stitches: 18"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("vertices: 23751"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("fabric: Denim"), std::string::npos) << r.out;
}

TEST(Cli, InfoOnAvatarFile) {
  DRAPE_SHARED_FILE(body, "garmentcode/mean_all.obj");
  auto r = drape("--info " + quote(body.string()));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("vertices: 23751"), std::string::npos) << r.out;
}

// A body in centimetres read as metres is 100 times too tall: --info, --render of the body alone and a scene with it
// say which unit it looks like; --avatar-units cm silences it.
TEST(Cli, AvatarInCentimetresIsWarnedAbout) {
  const auto body = kScratch / "body_box_cm.obj";
  std::ofstream out(body);
  for (int i = 0; i < 8; ++i)  // 40 x 170 x 30 cm
    out << "v " << (i & 1 ? 40 : 0) << " " << (i & 2 ? 170 : 0) << " " << (i & 4 ? 30 : 0) << "\n";
  out << "f 1 3 2\nf 2 3 4\nf 5 6 7\nf 6 8 7\nf 1 2 5\nf 2 6 5\nf 3 7 4\nf 4 7 8\nf 1 5 3\nf 3 5 7\nf 2 4 6\nf 4 8 6\n";
  out.close();
  const std::string expected = "warning: " + body.string() +
                               ": the avatar is 170.00 m tall; it looks like centimetres: load it with --avatar-units "
                               "cm (scene: \"avatar\": {\"units\": \"cm\"})";
  auto info = drape("--info " + quote(body.string()));
  ASSERT_EQ(info.exitCode, 0) << info.err;
  EXPECT_NE(info.out.find(expected), std::string::npos) << info.out;
  auto inCm = drape("--info " + quote(body.string()) + " --avatar-units cm");
  ASSERT_EQ(inCm.exitCode, 0) << inCm.err;
  EXPECT_EQ(inCm.out.find("warning"), std::string::npos) << inCm.out;

  auto render =
      drape("--render " + quote(body.string()) + " --size 32x32 -o " + quote((kScratch / "box.png").string()));
  ASSERT_EQ(render.exitCode, 0) << render.err;
  EXPECT_NE(render.out.find(expected), std::string::npos) << render.out;

  auto scene = drape("--info " + asset("patterns/tshirt.json") + " --avatar " + quote(body.string()));
  ASSERT_EQ(scene.exitCode, 0) << scene.err;
  EXPECT_NE(scene.out.find(expected.substr(9)), std::string::npos) << scene.out;  // listed under "warnings:"
}

TEST(Cli, ListSettingsAndFabrics) {
  auto s = drape("--list-settings");
  EXPECT_EQ(s.exitCode, 0);
  EXPECT_NE(s.out.find("mesh.target_edge_length = 0.01 [m]"), std::string::npos) << s.out;
  // Under group headings in the table's order: the mesh before the preview before the drape before the output.
  const size_t mesh = s.out.find("[mesh] "), preview = s.out.find("\n[preview] "), drapeGroup = s.out.find("\n[drape] "),
               output = s.out.find("\n[output] ");
  ASSERT_NE(mesh, std::string::npos) << s.out;
  EXPECT_LT(mesh, s.out.find("mesh.target_edge_length"));
  EXPECT_LT(mesh, preview);
  EXPECT_LT(preview, s.out.find("solver.preview.time_step"));
  EXPECT_LT(preview, drapeGroup);
  EXPECT_LT(drapeGroup, s.out.find("solver.newton.h_max"));
  EXPECT_LT(drapeGroup, output);
  EXPECT_NE(output, std::string::npos);
  EXPECT_EQ(s.out.find("solver.newton.block_map"), std::string::npos) << "an implementation switch is no setting";
  auto f = drape("--list-fabrics");
  EXPECT_EQ(f.exitCode, 0);
  for (const char* name : {"cotton_shirting", "denim", "silk_charmeuse", "jersey_knit", "wool_suiting",
                           "polyester_chiffon"})
    EXPECT_NE(f.out.find(name), std::string::npos) << name;
}

}  // namespace
}  // namespace drape::test
