// Patterns in and out of the command line: drape --info lists a DXF-AAMA file's pieces by name (a file written by
// ezdxf, an independent DXF writer); drape --write-pattern converts between GarmentCode JSON and DXF-AAMA and prints
// at full scale (the SVG's 10 cm check square measures 100 mm in the file's own millimetres, the PDF page is as large
// as the SVG's); bad requests get one line naming the file.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <regex>

#include "cli_solver_support.h"
#include "drape/pattern/pattern_loader.h"
#include "run_process.h"

namespace drape::test {
namespace {

std::string python() {
  if (const char* env = std::getenv("DRAPE_PYTHON")) return env;
  return std::filesystem::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
}

const std::filesystem::path kTshirt = std::filesystem::path(DRAPE_ASSETS_DIR) / "patterns" / "tshirt.json";

TEST(CliPatternFiles, InfoListsTheDxfPiecesByName) {
  std::filesystem::create_directories(kScratch);
  const auto file = kScratch / "two_pieces.dxf";
  const auto script = std::filesystem::path(DRAPE_TEST_DATA_DIR) / "dxf" / "write_aama.py";
  const auto made =
      runProcess(python() + " " + quote(script.string()) + " " + quote(file.string()) + " --case two_pieces", kScratch);
  ASSERT_EQ(made.exitCode, 0) << "python3-ezdxf is needed (scripts/setup.sh): " << made.err;
  const auto r = drape("--info " + quote(file.string()));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("units per metre: 1000"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("panel 'FRONT': 6 vertices"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("panel 'BACK': 4 vertices"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("2 notches, 2 internal lines"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("No meshes"), std::string::npos) << r.out;
}

TEST(CliPatternFiles, JsonToDxfAndBackKeepsThePanels) {
  std::filesystem::create_directories(kScratch);
  const auto dxf = kScratch / "tshirt.dxf", json = kScratch / "tshirt_from_dxf.json";
  auto r = drape("--write-pattern " + quote(kTshirt.string()) + " -o " + quote(dxf.string()));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("6 panels, 12 seams"), std::string::npos) << r.out;
  r = drape("--write-pattern " + quote(dxf.string()) + " -o " + quote(json.string()));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const Pattern original = loadPattern(kTshirt), back = loadPattern(json);
  ASSERT_EQ(back.panels.size(), original.panels.size());
  for (size_t p = 0; p < back.panels.size(); ++p) {
    EXPECT_EQ(back.panels[p].name, original.panels[p].name);
    // The outline is the original's, sampled: every corner of the original is a vertex of the copy (in mm).
    for (const Eigen::Vector2d& corner : original.panels[p].vertices) {
      double nearest = INFINITY;
      for (const Eigen::Vector2d& v : back.panels[p].vertices)
        nearest = std::min(nearest, (v / back.unitsInMeter - corner / original.unitsInMeter).norm());
      EXPECT_LT(nearest, 1e-6) << back.panels[p].name;
    }
  }
  EXPECT_TRUE(back.stitches.empty());  // DXF-AAMA carries no seams
}

#ifdef DRAPE_TEST_WITH_GUI
TEST(CliPatternFiles, PrintsAtFullScaleWithACheckSquare) {
  std::filesystem::create_directories(kScratch);
  const auto svg = kScratch / "tshirt.svg", pdf = kScratch / "tshirt.pdf";
  ASSERT_EQ(drape("--write-pattern " + quote(kTshirt.string()) + " -o " + quote(svg.string())).exitCode, 0);
  ASSERT_EQ(drape("--write-pattern " + quote(kTshirt.string()) + " -o " + quote(pdf.string())).exitCode, 0);
  const std::string text = readWhole(svg);
  std::smatch m;
  ASSERT_TRUE(std::regex_search(text, m, std::regex(R"re(width="([0-9.]+)mm" height="([0-9.]+)mm")re")));
  const double widthMm = std::stod(m[1]), heightMm = std::stod(m[2]);
  ASSERT_TRUE(std::regex_search(text, m, std::regex(R"re(viewBox="0 0 ([0-9.]+) ([0-9.]+)")re")));
  const double mmPerUnit = widthMm / std::stod(m[1]);
  EXPECT_NEAR(heightMm / std::stod(m[2]), mmPerUnit, 1e-3);
  // The check square: the one square <rect> of the drawing, scaled by its group's matrix.
  int squares = 0;
  const std::regex group(R"re(<g [^>]*transform="matrix\(([-0-9.e]+),)re"),
      rect(R"re(<rect x="[-0-9.]+" y="[-0-9.]+" width="([0-9.]+)" height="([0-9.]+)"/>)re");
  const std::regex element(R"(<g [^>]*>|<rect [^>]*/>)");
  double scale = 1.0;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), element); it != std::sregex_iterator(); ++it) {
    const std::string found = it->str();
    std::smatch e;
    if (std::regex_search(found, e, group)) scale = std::stod(e[1]);
    if (std::regex_match(found, e, rect) && e[1] == e[2]) {
      ++squares;
      EXPECT_NEAR(std::stod(e[1]) * scale * mmPerUnit, 100.0, 0.2) << found;
    }
  }
  EXPECT_EQ(squares, 1);
  for (const char* panel : {"front", "back", "l_sleeve_front"}) EXPECT_NE(text.find(panel), std::string::npos) << panel;
  // The PDF's page is the same size.
  const std::string bytes = readWhole(pdf);
  ASSERT_EQ(bytes.rfind("%PDF", 0), 0u);
  ASSERT_TRUE(std::regex_search(bytes, m, std::regex(R"(MediaBox \[0 0 ([0-9.]+) ([0-9.]+)\])")));
  EXPECT_NEAR(std::stod(m[1]), widthMm * 72.0 / 25.4, 1.5);
  EXPECT_NEAR(std::stod(m[2]), heightMm * 72.0 / 25.4, 1.5);
}
#endif

TEST(CliPatternFiles, BadRequestsGetOneLine) {
  std::filesystem::create_directories(kScratch);
  auto r = drape("--write-pattern " + quote(kTshirt.string()) + " -o " + quote((kScratch / "tshirt.txt").string()));
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("tshirt.txt"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  r = drape("--write-pattern " + quote(kTshirt.string()));
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("--write-pattern: missing -o OUTPUT"), std::string::npos) << r.err;
  const auto junk = kScratch / "junk.dxf";
  { std::ofstream(junk) << "this is not a DXF file\n"; }
  r = drape("--info " + quote(junk.string()));
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("junk.dxf"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

}  // namespace
}  // namespace drape::test
