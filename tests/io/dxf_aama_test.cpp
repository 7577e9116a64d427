// DXF-AAMA pattern files. The files read here are written at test time by ezdxf, an independent DXF writer
// (tests/data/dxf/write_aama.py), which also reports, worked out in Python, the geometry a reader must find;
// malformed files must be refused with one line naming the file and the piece, garbage must never crash the
// reader. Our writer's files must read back the same and be read by ezdxf. Without python3-ezdxf these tests
// fail (they never skip): scripts/setup.sh installs it.
#include "drape/pattern/dxf_aama.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "drape/core/input_error.h"
#include "drape/pattern/edge_curve.h"
#include "run_process.h"
#include "shared_data.h"

namespace drape {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

// The Python that has ezdxf: $DRAPE_PYTHON, else Debian's /usr/bin/python3 (python3-ezdxf), else python3.
std::string python() {
  if (const char* env = std::getenv("DRAPE_PYTHON")) return env;
  return fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
}

fs::path scratch() {
  const fs::path dir = test::testOutputDir() / "dxf_aama";
  fs::create_directories(dir);
  return dir;
}

Eigen::Vector2d vec(const Json& j) {
  return {j.at(0).get<double>(), j.at(1).get<double>()};
}

double signedArea(const std::vector<Eigen::Vector2d>& p) {
  double twice = 0.0;
  for (size_t i = 0; i < p.size(); ++i)
    twice += p[i].x() * p[(i + 1) % p.size()].y() - p[(i + 1) % p.size()].x() * p[i].y();
  return 0.5 * twice;
}

class DxfAama : public ::testing::Test {
 protected:
  void SetUp() override {
    static const test::ProcessResult check = test::runProcess(python() + " -c 'import ezdxf'", scratch());
    ASSERT_EQ(check.exitCode, 0) << "python3-ezdxf is missing (" << python() << "): " << check.err
                                 << " -- install it with scripts/setup.sh";
  }

  // Writes the script's case into the scratch directory; returns the .dxf (the .json beside it for good cases).
  // The file is named after the test too: ctest runs tests in parallel.
  static fs::path writeCase(const std::string& name) {
    const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    const fs::path out = scratch() / (test + "_" + name + ".dxf");
    const fs::path script = test::testDataDir() / "dxf" / "write_aama.py";
    const auto r = test::runProcess(
        python() + " " + test::quote(script.string()) + " " + test::quote(out.string()) + " --case " + name, scratch());
    EXPECT_EQ(r.exitCode, 0) << r.err;
    return out;
  }

  static Json expected(const fs::path& dxf) {
    std::ifstream in(fs::path(dxf).replace_extension(".json"));
    return Json::parse(in);
  }

  // The pattern read from file equals what the script says: units, names, vertices, curves, markings.
  static void expectPieces(const Pattern& pattern, const Json& want) {
    const double units = want.at("units_in_meter").get<double>();
    EXPECT_NEAR(pattern.unitsInMeter, units, 1e-12 * units);
    EXPECT_TRUE(pattern.stitches.empty());
    ASSERT_EQ(pattern.panels.size(), want.at("pieces").size());
    for (size_t i = 0; i < pattern.panels.size(); ++i) {
      const Panel& panel = pattern.panels[i];
      const Json& w = want["pieces"][i];
      SCOPED_TRACE("piece " + w.at("name").get<std::string>());
      EXPECT_EQ(panel.name, w.at("name").get<std::string>());
      ASSERT_EQ(panel.vertices.size(), w.at("vertices").size());
      for (size_t v = 0; v < panel.vertices.size(); ++v)
        EXPECT_LT((panel.vertices[v] - vec(w["vertices"][v])).norm(), 1e-9) << "vertex " << v;
      ASSERT_EQ(panel.edges.size(), panel.vertices.size());
      std::vector<bool> arc(panel.edges.size(), false);
      for (const Json& a : w.at("arcs")) {
        const int e = a.at("edge").get<int>();
        arc[e] = true;
        ASSERT_EQ(panel.edges[e].curve.type, CurveType::Circle);
        for (double t : {0.1, 0.3, 0.7, 0.9})
          EXPECT_NEAR((evaluateEdge(panel, e, t) - vec(a.at("center"))).norm(), a.at("radius").get<double>(), 1e-9);
        EXPECT_LT((evaluateEdge(panel, e, 0.5) - vec(a.at("middle"))).norm(), 1e-9);
      }
      for (size_t e = 0; e < panel.edges.size(); ++e) {
        EXPECT_EQ(panel.edges[e].start, int(e));
        EXPECT_EQ(panel.edges[e].end, int((e + 1) % panel.edges.size()));
        if (!arc[e]) {
          EXPECT_EQ(panel.edges[e].curve.type, CurveType::Straight) << "edge " << e;
        }
      }
      EXPECT_GT(signedArea(panelOutline(panel, 1.0)), 0.0) << "the outline must run counter-clockwise";
      // Hung in front of the body, facing it (+z), unturned.
      EXPECT_NEAR(panel.translation.z(), 0.35 * pattern.unitsInMeter, 1e-9);
      EXPECT_EQ(panel.rotationDeg, Eigen::Vector3d::Zero());
      ASSERT_EQ(panel.grainLine.has_value(), !w.at("grain").is_null());
      if (panel.grainLine) {
        EXPECT_LT(((*panel.grainLine)[0] - vec(w["grain"][0])).norm(), 1e-9);
        EXPECT_LT(((*panel.grainLine)[1] - vec(w["grain"][1])).norm(), 1e-9);
      }
      ASSERT_EQ(panel.notches.size(), w.at("notches").size());
      for (size_t n = 0; n < panel.notches.size(); ++n)
        EXPECT_LT((panel.notches[n] - vec(w["notches"][n])).norm(), 1e-9) << "notch " << n;
      ASSERT_EQ(panel.internalLines.size(), w.at("internal_lines").size());
      for (size_t l = 0; l < panel.internalLines.size(); ++l) {
        ASSERT_EQ(panel.internalLines[l].size(), w["internal_lines"][l].size());
        for (size_t k = 0; k < panel.internalLines[l].size(); ++k)
          EXPECT_LT((panel.internalLines[l][k] - vec(w["internal_lines"][l][k])).norm(), 1e-9);
      }
    }
  }
};

bool anyWarningContains(const Diagnostics& d, const std::string& text) {
  for (const auto& w : d.warnings())
    if (w.find(text) != std::string::npos) return true;
  return false;
}

TEST_F(DxfAama, ReadsTwoPiecesInMillimetres) {
  const fs::path file = writeCase("two_pieces");
  Diagnostics diagnostics;
  const Pattern pattern = readDxfAamaPattern(file, &diagnostics);
  expectPieces(pattern, expected(file));
  EXPECT_EQ(pattern.source, file.string());
  EXPECT_TRUE(diagnostics.warnings().empty()) << diagnostics.warnings().front();
}

TEST_F(DxfAama, PiecesHangApartInFrontOfTheBody) {
  const Pattern pattern = readDxfAamaPattern(writeCase("two_pieces"));
  ASSERT_EQ(pattern.panels.size(), 2u);
  // Each piece's outline placed in metres: x and y ranges, in front of a body at the origin.
  std::vector<Eigen::Vector4d> boxes;  // min x, max x, min y, max y
  for (const Panel& p : pattern.panels) {
    Eigen::Vector4d b(INFINITY, -INFINITY, INFINITY, -INFINITY);
    for (const Eigen::Vector2d& q : p.vertices) {
      const Eigen::Vector2d placed = (q + p.translation.head<2>()) / pattern.unitsInMeter;
      b = Eigen::Vector4d(std::min(b[0], placed.x()), std::max(b[1], placed.x()), std::min(b[2], placed.y()),
                          std::max(b[3], placed.y()));
    }
    EXPECT_GT(b[2], 0.3) << p.name;  // above the floor
    EXPECT_LT(b[3], 2.0) << p.name;
    boxes.push_back(b);
  }
  const bool apart = boxes[0][1] < boxes[1][0] || boxes[1][1] < boxes[0][0] || boxes[0][3] < boxes[1][2] ||
                     boxes[1][3] < boxes[0][2];
  EXPECT_TRUE(apart);
  EXPECT_NEAR(0.5 * (std::min(boxes[0][0], boxes[1][0]) + std::max(boxes[0][1], boxes[1][1])), 0.0, 1e-9);
}

TEST_F(DxfAama, ReadsInchesFromTheUnitsText) {
  const fs::path file = writeCase("inches");
  expectPieces(readDxfAamaPattern(file), expected(file));
}

TEST_F(DxfAama, MakesAClockwiseBoundaryCounterClockwise) {
  const fs::path file = writeCase("clockwise");
  expectPieces(readDxfAamaPattern(file), expected(file));
}

TEST_F(DxfAama, ReadsCentimetresFromInsunitsAndBlocksWithoutInserts) {
  const fs::path file = writeCase("cm_insunits");
  expectPieces(readDxfAamaPattern(file), expected(file));
}

TEST_F(DxfAama, ChainsLinesNamesPiecesReadsArcsAndAssumesMillimetres) {
  const fs::path file = writeCase("names");
  Diagnostics diagnostics;
  expectPieces(readDxfAamaPattern(file, &diagnostics), expected(file));
  EXPECT_TRUE(anyWarningContains(diagnostics, "assuming millimetres"));
  EXPECT_TRUE(anyWarningContains(diagnostics, "piece name 'SLEEVE' is used more than once"));
}

TEST_F(DxfAama, RefusesMalformedPiecesWithOneLineNamingFileAndPiece) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"no_boundary", "piece 'CUFF': no boundary"},
      {"two_points", "piece 'STRAP': boundary has 2 distinct points (at least 3 needed)"},
      {"self_intersecting", "piece 'BOWTIE': boundary crosses itself"},
      {"sliver", "piece 'SLIVER': boundary encloses no area"},
      {"nan", "piece 'GHOST': LINE on layer 7"},
      {"open_chain", "piece 'GAP': boundary is not one closed loop"},
      {"far_notch", "piece 'FAR': the notch (0, 200100) is 200 m from the piece's corners (at most 100 m)"},
      {"no_pieces", ": no pieces"},
      {"truncated", ": truncated DXF file"},
  };
  for (const auto& [name, message] : cases) {
    SCOPED_TRACE(name);
    const fs::path file = writeCase(name);
    try {
      readDxfAamaPattern(file);
      ADD_FAILURE() << "accepted";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind(file.string() + ": ", 0), 0u) << what;
      EXPECT_NE(what.find(message), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  }
}

// Every outcome of reading garbage is a pattern or an InputError: no crash, no hang, no other exception.
void expectReadOrRefused(const fs::path& file) {
  try {
    readDxfAamaPattern(file);
  } catch (const InputError&) {
  }
}

TEST_F(DxfAama, NeverCrashesOnGarbage) {
  const fs::path dir = scratch();
  auto write = [&](const std::string& name, const std::string& bytes) {
    std::ofstream(dir / name, std::ios::binary) << bytes;
    return dir / name;
  };
  auto refusal = [](const fs::path& file) -> std::string {
    try {
      readDxfAamaPattern(file);
    } catch (const InputError& e) {
      return e.what();
    }
    return "accepted";
  };
  EXPECT_NE(refusal(dir / "missing.dxf").find("missing.dxf: cannot open"), std::string::npos);
  EXPECT_NE(refusal(dir).find("cannot open"), std::string::npos);
  EXPECT_NE(refusal(write("empty.dxf", "")).find("not a DXF file"), std::string::npos);
  EXPECT_NE(refusal(write("prose.dxf", "hello\nworld\n")).find("prose.dxf: not a DXF file"), std::string::npos);
  EXPECT_NE(refusal(write("binary.dxf", std::string("AutoCAD Binary DXF\r\n\x1a\0", 22) + "junk")).find("binary DXF"),
            std::string::npos);
  std::mt19937 random(7);
  std::string junk(4096, '\0');
  for (char& c : junk) c = char(random());
  EXPECT_NE(refusal(write("junk.dxf", junk)).find("not a DXF file"), std::string::npos);
  // Counts and lines that would make libdxflib overrun a buffer or spin.
  const std::string head = "0\nSECTION\n2\nBLOCKS\n0\nBLOCK\n2\nP\n";
  const std::string tail = "0\nENDBLK\n0\nENDSEC\n0\nEOF\n";
  expectReadOrRefused(write("count.dxf", head + "0\nLWPOLYLINE\n8\n1\n90\n2000000000\n42\n1\n10\n0\n20\n0\n" + tail));
  expectReadOrRefused(
      write("long.dxf", head + "0\nTEXT\n8\n1\n1\nPiece Name: " + std::string(5000, 'x') + "\n" + tail));
  EXPECT_NE(
      refusal(write("code.dxf", head + "abc\n1\n" + tail)).find("code.dxf: line 9: 'abc' is not a DXF group code"),
      std::string::npos);

  // A real file cut anywhere, and with bytes changed at random.
  const fs::path good = writeCase("two_pieces");
  std::ifstream in(good, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (int k = 1; k < 40; ++k) expectReadOrRefused(write("cut.dxf", bytes.substr(0, bytes.size() * k / 40)));
  for (int k = 0; k < 60; ++k) {
    std::string changed = bytes;
    for (int j = 0; j < 8; ++j) changed[random() % changed.size()] = "0123456789-.\nE x"[random() % 16];
    expectReadOrRefused(write("changed.dxf", changed));
  }
}

// Two panels in centimetres: a straight hexagon with all markings, and one with a curved edge and no grain line.
Pattern patternToWrite() {
  Pattern pattern;
  pattern.source = "written";
  pattern.unitsInMeter = 100.0;
  Panel front;
  front.name = "front panel";
  front.vertices = {{0, 0}, {40.5, 0}, {44, 30}, {38, 61.25}, {4, 62}, {-3, 30}};
  for (int i = 0; i < 6; ++i) front.edges.push_back(PanelEdge{i, (i + 1) % 6, {}, ""});
  front.grainLine = std::array<Eigen::Vector2d, 2>{Eigen::Vector2d(20, 10), Eigen::Vector2d(20, 50)};
  front.notches = {{20.25, 0}, {44, 30}};
  front.internalLines = {{{10, 61}, {14, 40}, {18, 61.5}}, {{5, 30}, {35, 30}}};
  Panel hem;
  hem.name = "hem";
  hem.vertices = {{0, 0}, {30, 0}, {30, 10}};
  hem.edges = {PanelEdge{0, 1, {}, ""}, PanelEdge{1, 2, {}, ""}, PanelEdge{2, 0, {}, ""}};
  hem.edges[2].curve.type = CurveType::Quadratic;
  hem.edges[2].curve.controls = {Eigen::Vector2d(0.5, -0.2)};  // bulging away from the hem
  pattern.panels = {front, hem};
  return pattern;
}

TEST_F(DxfAama, WrittenFilesReadBackTheSame) {
  const Pattern original = patternToWrite();
  const fs::path dir = scratch() / "written";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path file = dir / "round_trip.dxf";
  writeDxfAamaPattern(original, file);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1) << "a temporary file was left";

  Diagnostics diagnostics;
  const Pattern back = readDxfAamaPattern(file, &diagnostics);
  EXPECT_TRUE(diagnostics.warnings().empty()) << diagnostics.warnings().front();
  EXPECT_EQ(back.unitsInMeter, 1000.0);
  ASSERT_EQ(back.panels.size(), 2u);
  const double mm = 10.0;  // per centimetre
  auto near = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a - b).norm() <= 1e-6 * b.norm() + 1e-9;
  };

  const Panel& front = back.panels[0];
  const Panel& source = original.panels[0];
  EXPECT_EQ(front.name, "front panel");
  ASSERT_EQ(front.vertices.size(), source.vertices.size());
  for (size_t v = 0; v < source.vertices.size(); ++v)
    EXPECT_TRUE(near(front.vertices[v], mm * source.vertices[v])) << v << ": " << front.vertices[v].transpose();
  ASSERT_TRUE(front.grainLine);
  EXPECT_TRUE(near((*front.grainLine)[0], mm * (*source.grainLine)[0]));
  EXPECT_TRUE(near((*front.grainLine)[1], mm * (*source.grainLine)[1]));
  ASSERT_EQ(front.notches.size(), 2u);
  for (size_t n = 0; n < 2; ++n) EXPECT_TRUE(near(front.notches[n], mm * source.notches[n])) << n;
  ASSERT_EQ(front.internalLines.size(), 2u);
  for (size_t l = 0; l < 2; ++l) {
    ASSERT_EQ(front.internalLines[l].size(), source.internalLines[l].size());
    for (size_t k = 0; k < source.internalLines[l].size(); ++k)
      EXPECT_TRUE(near(front.internalLines[l][k], mm * source.internalLines[l][k]));
  }

  // The curved edge comes back sampled: the straight corners, then points on the curve.
  const Panel& hem = back.panels[1];
  EXPECT_EQ(hem.name, "hem");
  ASSERT_GE(hem.vertices.size(), 3u + 7u);
  for (int v = 0; v < 3; ++v) EXPECT_TRUE(near(hem.vertices[v], mm * original.panels[1].vertices[v]));
  const std::vector<Eigen::Vector2d> curve = sampleEdge(original.panels[1], 2, 4000);
  for (size_t v = 3; v < hem.vertices.size(); ++v) {
    double nearest = 1e300;
    for (size_t k = 0; k + 1 < curve.size(); ++k) {
      const Eigen::Vector2d a = mm * curve[k], d = mm * curve[k + 1] - a;
      const double t = std::clamp((hem.vertices[v] - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
      nearest = std::min(nearest, (a + t * d - hem.vertices[v]).norm());
    }
    EXPECT_LT(nearest, 1e-3) << "vertex " << v << " is off the curve (mm)";
  }
  // No grain line: the writer drew the warp, horizontal through the centroid.
  ASSERT_TRUE(hem.grainLine);
  const auto& grain = *hem.grainLine;
  EXPECT_NEAR(grain[0].y(), grain[1].y(), 1e-9);
  EXPECT_GT(grain[1].x() - grain[0].x(), 50.0);
  const std::vector<Eigen::Vector2d> outline = panelOutline(hem, 0.0);
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (size_t i = 0; i < outline.size(); ++i) {
    const auto& a = outline[i];
    const auto& b = outline[(i + 1) % outline.size()];
    centroid += (a + b) * (a.x() * b.y() - b.x() * a.y());
  }
  centroid /= 6.0 * signedArea(outline);
  EXPECT_LT((0.5 * (grain[0] + grain[1]) - centroid).norm(), 1e-6);
}

TEST_F(DxfAama, EzdxfReadsWrittenFiles) {
  const Pattern original = patternToWrite();
  const fs::path file = scratch() / "for_ezdxf.dxf";
  writeDxfAamaPattern(original, file);
  const fs::path lister = scratch() / "list_dxf.py";
  std::ofstream(lister) << R"(import json, sys
import ezdxf
from ezdxf import bbox, recover
doc = ezdxf.readfile(sys.argv[1])
_, auditor = recover.readfile(sys.argv[1])
out = {"version": doc.dxfversion, "insunits": doc.header.get("$INSUNITS"), "audit_errors": len(auditor.errors),
       "blocks": {}, "inserts": [], "texts": [e.dxf.text for e in doc.modelspace().query("TEXT")]}
for block in doc.blocks:
    if block.name.startswith("*"):
        continue
    b = out["blocks"][block.name] = {"layers": {}, "boundary": [], "closed": None, "texts": []}
    for e in block:
        b["layers"][e.dxf.layer] = b["layers"].get(e.dxf.layer, 0) + 1
        if e.dxftype() == "POLYLINE" and e.dxf.layer == "1":
            b["boundary"] = [list(v.dxf.location)[:2] for v in e.vertices]
            b["closed"] = e.is_closed
        if e.dxftype() == "TEXT":
            b["texts"].append(e.dxf.text)
for e in doc.modelspace().query("INSERT"):
    box = bbox.extents(e.virtual_entities())
    out["inserts"].append({"name": e.dxf.name, "min": list(box.extmin)[:2], "max": list(box.extmax)[:2]})
print(json.dumps(out))
)";
  const auto r =
      test::runProcess(python() + " " + test::quote(lister.string()) + " " + test::quote(file.string()), scratch());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const Json dxf = Json::parse(r.out);
  EXPECT_EQ(dxf.at("version"), "AC1009");
  EXPECT_EQ(dxf.at("insunits"), 4);
  EXPECT_EQ(dxf.at("audit_errors"), 0);
  EXPECT_NE(std::find(dxf["texts"].begin(), dxf["texts"].end(), "UNITS: METRIC"), dxf["texts"].end());
  ASSERT_EQ(dxf.at("blocks").size(), 2u);
  ASSERT_EQ(dxf.at("inserts").size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    const std::string blockName = dxf["inserts"][i].at("name");
    const Json& block = dxf["blocks"].at(blockName);
    EXPECT_EQ(block.at("texts").at(0), "Piece Name: " + original.panels[i].name);
    EXPECT_EQ(block.at("closed"), true);
    EXPECT_EQ(block.at("layers").at("7"), 1);  // one grain line
  }
  const Json& front = dxf["blocks"].at(dxf["inserts"][0].at("name").get<std::string>());
  EXPECT_EQ(front["layers"].at("4"), 2);  // notches
  EXPECT_EQ(front["layers"].at("8"), 2);  // internal lines
  ASSERT_EQ(front.at("boundary").size(), original.panels[0].vertices.size());
  for (size_t v = 0; v < original.panels[0].vertices.size(); ++v)
    EXPECT_LT((vec(front["boundary"][v]) - 10.0 * original.panels[0].vertices[v]).norm(), 1e-9);
  // Laid out side by side: the placed pieces do not overlap.
  EXPECT_LT(dxf["inserts"][0]["max"][0].get<double>(), dxf["inserts"][1]["min"][0].get<double>());
}

TEST_F(DxfAama, WriterRefusesWhatItCannotWrite) {
  const fs::path file = scratch() / "refused.dxf";
  Pattern empty;
  try {
    writeDxfAamaPattern(empty, file);
    ADD_FAILURE() << "wrote an empty pattern";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("refused.dxf: the pattern has no panels"), std::string::npos) << e.what();
  }
  Pattern broken = patternToWrite();
  broken.panels[0].vertices[2].x() = std::nan("");
  EXPECT_THROW(writeDxfAamaPattern(broken, file), InputError);
  EXPECT_FALSE(fs::exists(file));
}

TEST(DxfAamaFiles, RecognisesTheExtension) {
  EXPECT_TRUE(isDxfFile("a/b/pattern.dxf"));
  EXPECT_TRUE(isDxfFile("PATTERN.DXF"));
  EXPECT_FALSE(isDxfFile("pattern.dxf.json"));
  EXPECT_FALSE(isDxfFile("dxf"));
}

}  // namespace
}  // namespace drape
