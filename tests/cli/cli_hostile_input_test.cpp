// Hostile inputs end the headless modes with exit code 1 and one line naming the file and the element, instead
// of hanging, diverging or an internal error.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "run_process.h"
#include "shared_data.h"

namespace drape::test {
namespace {

const std::filesystem::path kScratch = testOutputDir() / "cli_hostile";

ProcessResult drape(const std::string& args) {
  std::filesystem::create_directories(kScratch);
  return runProcess(quote(DRAPE_EXECUTABLE) + " " + args + " </dev/null", kScratch);
}

std::string bad(const std::string& name) {
  return quote((testDataDir() / "bad" / name).string());
}

void expectOneLineError(const ProcessResult& r, const std::string& expected) {
  EXPECT_EQ(r.exitCode, 1) << r.err;
  EXPECT_NE(r.err.find(expected), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

TEST(CliHostileInput, AvatarFaceOfHundredThousandCorners) {
  const std::filesystem::path body = kScratch / "huge_face_body.obj";
  std::filesystem::create_directories(kScratch);
  {
    std::ofstream out(body);
    for (int k = 0; k < 100000; ++k) out << "v " << k % 317 << " " << k / 317 << " 0\n";
    out << "f";
    for (int k = 1; k <= 100000; ++k) out << " " << k;
    out << "\n";
  }
  const auto r =
      drape("--info " + quote((assetsDir() / "scenes/tablecloth.json").string()) + " --avatar " + quote(body.string()));
  expectOneLineError(r, body.string() + ": line 100001: face 1 with 100000 vertices (at most 1000)");
}

TEST(CliHostileInput, TinyPanel) {
  expectOneLineError(drape("--info " + bad("pattern_tiny_panel.json")),
                     "pattern_tiny_panel.json: panel 'tiny': area 1e-18 m^2 is too small to mesh");
}

TEST(CliHostileInput, NeedleSpikeThatMeshesIntoZeroAreaTriangles) {
  expectOneLineError(drape("--info " + bad("garment_needle_spike.json") + " --set mesh.target_edge_length=0.02"),
                     "garment_needle_spike.json: panel 'spiked': meshing gives triangle ");
}

TEST(CliHostileInput, PanelTranslatedFarAway) {
  expectOneLineError(drape("--info " + bad("pattern_translation_1e308.json")),
                     "pattern_translation_1e308.json: panel 'front': 'translation'");
}

TEST(CliHostileInput, DuplicatePanelName) {
  expectOneLineError(drape("--info " + bad("pattern_duplicate_panel.json")),
                     "pattern_duplicate_panel.json: panel 'front' defined twice");
}

TEST(CliHostileInput, PlacementTranslateOutOfRange) {
  expectOneLineError(drape("--info " + quote((assetsDir() / "scenes/tablecloth.json").string()) +
                           " --set placement.translate=0,1e308,0"),
                     "setting 'placement.translate': '0,1e308,0': y = 1e308 is out of range [-100, 100] m");
}

TEST(CliHostileInput, FabricWithNoStretchStiffness) {
  // Zero stretch stiffness holds nothing together: refused with the range, as a fabric file's would be.
  expectOneLineError(drape("--info " + quote((assetsDir() / "scenes/tablecloth.json").string()) +
                           " --set fabric.stretch_weft=0"),
                     "setting 'fabric.stretch_weft': 0 is out of range [0.001, 1e+07] N/m");
}

// Found by the fuzz harnesses (fuzz/): a PLY header without its end_header line kept assimp reading for minutes, a PLY
// face without corners aborted the process in assimp, and a YAML measurement file with a list as a key ended in an
// internal error.
TEST(CliHostileInput, PlyAvatarWithoutEndOfHeader) {
  expectOneLineError(drape("--info " + quote((assetsDir() / "scenes/tablecloth.json").string()) + " --avatar " +
                           bad("avatar_ply_without_end_header.ply")),
                     "avatar_ply_without_end_header.ply: PLY header: no 'end_header' line in its first 65536 bytes");
}

TEST(CliHostileInput, PlyAvatarWhoseFaceHasNoVertices) {
  // Two PLY headers run together: assimp reads a face without corners, and its triangulation aborted the process.
  expectOneLineError(drape("--info " + quote((assetsDir() / "scenes/tablecloth.json").string()) + " --avatar " +
                           bad("avatar_ply_face_without_vertices.ply")),
                     "avatar_ply_face_without_vertices.ply: mesh 0 face 0 has no vertices");
}

TEST(CliHostileInput, MeasurementsWithAListAsKey) {
  expectOneLineError(drape("--make-avatar " + bad("measurements_list_as_key.yaml") + " -o " +
                           quote((kScratch / "list_key.obj").string())),
                     "measurements_list_as_key.yaml: a key that is not a name (a list or a map)");
}

}  // namespace
}  // namespace drape::test
