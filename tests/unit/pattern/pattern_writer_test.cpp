// Saving patterns as GarmentCode JSON: load -> write -> load gives the same Pattern, field by field and in its
// sampled geometry, for the library (assets/patterns), our own test patterns (tests/data/patterns: circle arcs,
// right_wrong stitches, absolute and legacy curvature) and every GarmentCode pattern in ../shared/data. Also the
// panel markings (grain line, notches, internal lines): read, written, read back, and refused when malformed.
#include "drape/pattern/pattern_writer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "drape/core/input_error.h"
#include "drape/pattern/edge_curve.h"
#include "drape/pattern/pattern_loader.h"
#include "shared_data.h"

namespace drape {
namespace {

namespace fs = std::filesystem;
using Eigen::Vector2d;

// Exact comparison of two point lists (the writer promises round-trippable numbers).
void expectSamePoints(const std::vector<Vector2d>& a, const std::vector<Vector2d>& b, const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].x(), b[i].x()) << what << " " << i;
    EXPECT_EQ(a[i].y(), b[i].y()) << what << " " << i;
  }
}

// Every field of the two patterns but `source`, exactly.
void expectSamePattern(const Pattern& a, const Pattern& b) {
  EXPECT_EQ(a.unitsInMeter, b.unitsInMeter);
  ASSERT_EQ(a.panels.size(), b.panels.size());
  for (size_t p = 0; p < a.panels.size(); ++p) {
    const Panel& pa = a.panels[p];
    const Panel& pb = b.panels[p];
    SCOPED_TRACE("panel " + std::to_string(p) + " '" + pa.name + "'");
    EXPECT_EQ(pa.name, pb.name);
    EXPECT_EQ(pa.label, pb.label);
    expectSamePoints(pa.vertices, pb.vertices, "vertex");
    EXPECT_EQ(pa.translation, pb.translation);
    EXPECT_EQ(pa.rotationDeg, pb.rotationDeg);
    ASSERT_EQ(pa.edges.size(), pb.edges.size());
    for (size_t e = 0; e < pa.edges.size(); ++e) {
      SCOPED_TRACE("edge " + std::to_string(e));
      const PanelEdge& ea = pa.edges[e];
      const PanelEdge& eb = pb.edges[e];
      EXPECT_EQ(ea.start, eb.start);
      EXPECT_EQ(ea.end, eb.end);
      EXPECT_EQ(ea.label, eb.label);
      EXPECT_EQ(ea.curve.type, eb.curve.type);
      expectSamePoints(ea.curve.controls, eb.curve.controls, "control point");
      EXPECT_EQ(ea.curve.radius, eb.curve.radius);
      EXPECT_EQ(ea.curve.largeArc, eb.curve.largeArc);
      EXPECT_EQ(ea.curve.right, eb.curve.right);
    }
    ASSERT_EQ(pa.grainLine.has_value(), pb.grainLine.has_value());
    if (pa.grainLine)
      expectSamePoints({(*pa.grainLine)[0], (*pa.grainLine)[1]}, {(*pb.grainLine)[0], (*pb.grainLine)[1]},
                       "grain line");
    expectSamePoints(pa.notches, pb.notches, "notch");
    ASSERT_EQ(pa.internalLines.size(), pb.internalLines.size());
    for (size_t k = 0; k < pa.internalLines.size(); ++k)
      expectSamePoints(pa.internalLines[k], pb.internalLines[k], "internal line " + std::to_string(k));
  }
  ASSERT_EQ(a.stitches.size(), b.stitches.size());
  for (size_t k = 0; k < a.stitches.size(); ++k) {
    SCOPED_TRACE("stitch " + std::to_string(k));
    const Stitch& sa = a.stitches[k];
    const Stitch& sb = b.stitches[k];
    EXPECT_EQ(sa.a.panel, sb.a.panel);
    EXPECT_EQ(sa.a.edge, sb.a.edge);
    EXPECT_EQ(sa.b.panel, sb.b.panel);
    EXPECT_EQ(sa.b.edge, sb.b.edge);
    EXPECT_EQ(sa.rightWrong, sb.rightWrong);
  }
}

// Independent of the fields: the outlines the two patterns describe, as arc lengths and points sampled by arc
// length along every edge, and the lengths of every stitch's two edges.
void expectSameGeometry(const Pattern& a, const Pattern& b) {
  ASSERT_EQ(a.panels.size(), b.panels.size());
  for (size_t p = 0; p < a.panels.size(); ++p) {
    const Panel& pa = a.panels[p];
    const Panel& pb = b.panels[p];
    ASSERT_EQ(pa.edges.size(), pb.edges.size()) << pa.name;
    for (int e = 0; e < int(pa.edges.size()); ++e) {
      const double length = edgeLength(pa, e);
      EXPECT_GT(length, 0.0) << pa.name << " edge " << e;
      EXPECT_DOUBLE_EQ(length, edgeLength(pb, e)) << pa.name << " edge " << e;
      const std::vector<Vector2d> sa = sampleEdge(pa, e, 16), sb = sampleEdge(pb, e, 16);
      ASSERT_EQ(sa.size(), sb.size());
      for (size_t i = 0; i < sa.size(); ++i)
        EXPECT_LE((sa[i] - sb[i]).norm(), 1e-12 * length) << pa.name << " edge " << e << " sample " << i;
    }
  }
  for (size_t k = 0; k < b.stitches.size(); ++k) {
    const Stitch& s = b.stitches[k];
    EXPECT_DOUBLE_EQ(edgeLength(a.panels.at(s.a.panel), s.a.edge), edgeLength(b.panels.at(s.a.panel), s.a.edge));
    EXPECT_DOUBLE_EQ(edgeLength(a.panels.at(s.b.panel), s.b.edge), edgeLength(b.panels.at(s.b.panel), s.b.edge));
  }
}

// load -> write -> load, compared; then the second write must be the first one again (a fixed point).
void expectRoundTrip(const fs::path& file) {
  SCOPED_TRACE(file.string());
  const Pattern original = loadPattern(file);
  const std::string text = patternToJson(original);
  const Pattern reloaded = parsePattern(text, "saved " + file.filename().string());
  expectSamePattern(original, reloaded);
  expectSameGeometry(original, reloaded);
  EXPECT_EQ(patternToJson(reloaded), text);
  EXPECT_NE(text.find("\"curvature_coords\": \"relative\""), std::string::npos);
}

std::vector<fs::path> jsonFilesUnder(const fs::path& dir) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    if (entry.is_regular_file() && entry.path().extension() == ".json") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

TEST(PatternWriter, LibraryPatternsRoundTrip) {
  const std::vector<fs::path> files = jsonFilesUnder(test::assetsDir() / "patterns");
  ASSERT_GE(files.size(), 9u);
  for (const fs::path& file : files) expectRoundTrip(file);
}

// Circle arcs (flags as booleans and as 0/1), right_wrong stitches, absolute and legacy curvature, labels.
TEST(PatternWriter, TestPatternsRoundTrip) {
  const std::vector<fs::path> files = jsonFilesUnder(test::testDataDir() / "patterns");
  ASSERT_GE(files.size(), 5u);
  for (const fs::path& file : files) expectRoundTrip(file);
}

// Every GarmentCode pattern in ../shared/data; a JSON file without a "pattern" is a scene or a body spec, which
// the loader says.
TEST(PatternWriter, SharedGarmentCodePatternsRoundTrip) {
  DRAPE_SHARED_FILE(shirt, "garmentcode/shirt_mean_specification.json");
  int patterns = 0;
  for (const fs::path& file : jsonFilesUnder(test::sharedDataDir())) {
    try {
      loadPattern(file);
    } catch (const InputError& e) {
      const std::string message = e.what();
      if (message.find("missing field 'pattern'") != std::string::npos ||
          message.find("'pattern' must be an object") != std::string::npos)
        continue;  // not a pattern
      ADD_FAILURE() << message;
      continue;
    }
    expectRoundTrip(file);
    ++patterns;
  }
  EXPECT_GE(patterns, 4);  // garmentcode/ (shirt, pencil dress) and garment-pattern-generator/ (tee, skirt)
}

TEST(PatternWriter, WritesGarmentCodeLayout) {
  const Pattern p = loadPattern(test::testDataDir() / "patterns" / "circle_patch.json");
  const std::string text = patternToJson(p);
  for (const char* part :
       {"\"panel_order\": [\"lens\", \"patch\"]", "\"units_in_meter\": 100.0",
        R"({"endpoints": [2, 3], "curvature": {"type": "circle", "params": [10.0, false, true]}, "label": "dome"})",
        R"([{"panel": "patch", "edge": 1}, {"panel": "patch", "edge": 3}, "right_wrong"])",
        "\"label\": \"patch_label\"", "\"translation\": [0.0, 120.0, 20.0]"})
    EXPECT_NE(text.find(part), std::string::npos) << part << " in\n" << text;
  // Straight edges carry no curvature, absent markings no keys, panels without a label no label.
  EXPECT_NE(text.find(R"({"endpoints": [1, 2]})"), std::string::npos) << text;
  for (const char* absent : {"grainline", "notches", "internal_lines", "\"absolute\""})
    EXPECT_EQ(text.find(absent), std::string::npos) << absent;
  EXPECT_EQ(text.back(), '\n');
}

// A single square panel in centimetres with `extra` added to its keys.
std::string squareWith(const std::string& extra) {
  return R"({"pattern": {"panels": {"patch": {"vertices": [[0, 0], [20, 0], [20, 20], [0, 20]],
    "edges": [{"endpoints": [0, 1]}, {"endpoints": [1, 2]}, {"endpoints": [2, 3]}, {"endpoints": [3, 0]}],
    "translation": [0, 100, 0], "rotation": [0, 0, 0])" +
         (extra.empty() ? "" : ", " + extra) + R"(}}}, "properties": {"units_in_meter": 100}})";
}

TEST(PatternMarkings, ReadAsGivenAndRoundTrip) {
  const Pattern p = parsePattern(squareWith(R"("grainline": [[10, 2], [10, 18.5]], "notches": [[5, 0], [20, 7.25]],
      "internal_lines": [[[8, 20], [10, 12], [12, 20]], [[0, 10], [20, 10]]])"),
                                 "marked.json");
  const Panel& panel = p.panels.at(0);
  ASSERT_TRUE(panel.grainLine.has_value());
  EXPECT_EQ((*panel.grainLine)[0], Vector2d(10, 2));
  EXPECT_EQ((*panel.grainLine)[1], Vector2d(10, 18.5));
  ASSERT_EQ(panel.notches.size(), 2u);
  EXPECT_EQ(panel.notches[1], Vector2d(20, 7.25));
  ASSERT_EQ(panel.internalLines.size(), 2u);
  ASSERT_EQ(panel.internalLines[0].size(), 3u);
  EXPECT_EQ(panel.internalLines[0][1], Vector2d(10, 12));
  EXPECT_EQ(panel.internalLines[1][1], Vector2d(20, 10));

  const std::string text = patternToJson(p);
  for (const char* part :
       {"\"grainline\": [[10.0, 2.0], [10.0, 18.5]]", "\"notches\": [[5.0, 0.0], [20.0, 7.25]]",
        "\"internal_lines\": [[[8.0, 20.0], [10.0, 12.0], [12.0, 20.0]], [[0.0, 10.0], [20.0, 10.0]]]"})
    EXPECT_NE(text.find(part), std::string::npos) << part << " in\n" << text;
  expectSamePattern(p, parsePattern(text, "saved.json"));

  // Without the keys, no markings.
  const Panel plain = parsePattern(squareWith(""), "plain.json").panels.at(0);
  EXPECT_FALSE(plain.grainLine.has_value());
  EXPECT_TRUE(plain.notches.empty());
  EXPECT_TRUE(plain.internalLines.empty());
}

// Markings set in code with doubles that have no short decimal form come back bit for bit, on a library pattern.
TEST(PatternMarkings, AwkwardDoublesRoundTripExactly) {
  Pattern p = loadPattern(test::assetsDir() / "patterns" / "tshirt.json");
  Panel& front = p.panels.at(0);
  const Vector2d c = front.vertices[0];
  front.grainLine =
      std::array<Vector2d, 2>{c + Vector2d(0.1 + 0.2, 1.0 / 3.0), c + Vector2d(std::nextafter(1.0, 2.0), 40.0)};
  front.notches = {c + Vector2d(1e-300, -0.0), c + Vector2d(2.0 / 3.0, std::numeric_limits<double>::denorm_min())};
  front.internalLines = {{c + Vector2d(5.5, 3.0), c + Vector2d(7.0 / 9.0, 11.0 / 13.0), c + Vector2d(12.0, 3.0)}};
  p.panels.at(1).notches = {p.panels.at(1).vertices[1]};
  const Pattern back = parsePattern(patternToJson(p), "saved.json");
  expectSamePattern(p, back);
  EXPECT_EQ((*back.panels[0].grainLine)[0].x(), c.x() + (0.1 + 0.2));  // not 0.3 after the addition
  EXPECT_TRUE(back.panels[1].internalLines.empty());
}

// Malformed markings: one InputError naming the file, the panel and the key.
TEST(PatternMarkings, MalformedValuesAreRefusedNamingPanelAndKey) {
  const std::pair<const char*, const char*> cases[] = {
      {R"("grainline": "up")", "'grainline' must be [[x0, y0], [x1, y1]], got the string \"up\""},
      {R"("grainline": [[0, 0]])", "'grainline' must be [[x0, y0], [x1, y1]], got an array of 1"},
      {R"("grainline": [[0, 0], [0, "a"]])", "'grainline' point 1 y must be a number, got the string \"a\""},
      {R"("grainline": [[5, 5], [5, 5]])", "'grainline' has zero length"},
      {R"("notches": {"a": 1})", "'notches' must be an array, got an object"},
      {R"("notches": [[1, 2], [1, 2, 3]])", "'notches' point 1 must be an array of 2 numbers, got an array of 3"},
      {R"("notches": [[null, 1]])", "'notches' point 0 x must be a number, got null"},
      {R"("notches": [[1e9, 0]])", "'notches' point 0 [1000000000.0,0] is 1e+07 m from the panel's corners"},
      {R"("internal_lines": 5)", "'internal_lines' must be an array, got the number 5"},
      {R"("internal_lines": [[[0, 0], [1, 1]], [[0, 0]]])",
       "'internal_lines' line 1 must be a polyline of at least 2 points [[x, y], ...], got an array of 1"},
      {R"("internal_lines": [[0, 0], [1, 1]])", "'internal_lines' line 0 point 0 must be an array of 2 numbers"},
      {R"("internal_lines": ["dart"])", "'internal_lines' line 0 must be an array, got the string \"dart\""},
  };
  for (const auto& [extra, problem] : cases) {
    SCOPED_TRACE(extra);
    try {
      parsePattern(squareWith(extra), "bad.json");
      ADD_FAILURE() << "no InputError";
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.rfind("bad.json: panel 'patch': " + std::string(problem), 0), 0u) << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
  }
}

TEST(PatternWriter, SavePatternWritesAtomicallyAndLoadsBack) {
  const Pattern p = loadPattern(test::testDataDir() / "patterns" / "circle_patch.json");
  const fs::path dir = test::testOutputDir() / "pattern_writer";
  fs::create_directories(dir);
  const fs::path file = dir / "circle_patch_saved.json";
  { std::ofstream(file) << "old content"; }
  savePattern(p, file);
  const Pattern back = loadPattern(file);
  expectSamePattern(p, back);
  std::ifstream in(file);
  std::stringstream content;
  content << in.rdbuf();
  EXPECT_EQ(content.str(), patternToJson(p));
  for (const auto& entry : fs::directory_iterator(dir))  // no temporary file left behind
    EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos) << entry.path();
  EXPECT_THROW(savePattern(p, dir / "no_such_directory" / "x.json"), InputError);
  EXPECT_FALSE(fs::exists(dir / "no_such_directory"));
}

// What the file format cannot say faithfully is refused before anything is written.
TEST(PatternWriter, RefusesPatternsItCannotWriteFaithfully) {
  const Pattern good = loadPattern(test::testDataDir() / "patterns" / "circle_patch.json");
  auto expectRefusal = [](const Pattern& p, const std::string& part) {
    try {
      patternToJson(p);
      ADD_FAILURE() << "no refusal for " << part;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
  };
  Pattern twoNames = good;
  twoNames.panels[1].name = twoNames.panels[0].name;
  expectRefusal(twoNames, "two panels are called 'lens'");
  Pattern badStitch = good;
  badStitch.stitches[0].b.edge = 9;
  expectRefusal(badStitch, "stitch 0: panel 'patch' has no edge 9");
  Pattern badCurve = good;
  badCurve.panels[1].edges[1].curve.type = CurveType::Cubic;
  expectRefusal(badCurve, "panel 'patch' edge 1: the curve needs 2 control points, has 0");
  Pattern nan = good;
  nan.panels[0].vertices[1].x() = std::numeric_limits<double>::quiet_NaN();
  expectRefusal(nan, "panel 'lens': vertex 1 is not finite");
  Pattern shortLine = good;
  shortLine.panels[0].internalLines = {{Vector2d(1, 0)}};
  expectRefusal(shortLine, "panel 'lens': internal line 0 has 1 points");
}

}  // namespace
}  // namespace drape
