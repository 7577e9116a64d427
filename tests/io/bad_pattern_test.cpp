// Every malformed pattern in tests/data/bad/pattern_*.json raises InputError naming the file, the element
// (panel, edge, stitch) and the problem. Table: file -> substrings the message must contain.
#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "drape/core/input_error.h"
#include "drape/garment/garment_builder.h"
#include "drape/pattern/pattern_loader.h"
#include "shared_data.h"

namespace drape {
namespace {

struct BadPatternCase {
  const char* file;
  std::vector<std::string> expected;  // besides the file name, which every message must contain
};

const std::vector<BadPatternCase>& badPatternCases() {
  static const std::vector<BadPatternCase> cases = {
      {"pattern_invalid_json.json", {"invalid JSON", "line 4, column"}},
      {"pattern_top_level_array.json", {"top level must be an object"}},
      {"pattern_missing_pattern_field.json", {"missing field 'pattern'"}},
      {"pattern_no_panels.json", {"no panels"}},
      {"pattern_panels_not_object.json", {"'panels' must be an object"}},
      {"pattern_empty_vertices.json", {"panel 'front'", "empty panel", "'vertices' is empty"}},
      {"pattern_empty_edges.json", {"panel 'front'", "empty panel", "'edges' is empty"}},
      {"pattern_missing_vertices.json", {"panel 'front'", "missing field 'vertices'"}},
      {"pattern_vertex_not_pair.json", {"panel 'front'", "vertex 2 must be an array of 2 numbers"}},
      {"pattern_vertex_mistyped.json", {"panel 'front'", "vertex 1 x must be a number", "\"40\""}},
      {"pattern_nonfinite_number.json", {"invalid JSON", "non-finite number at line 60, column 11"}},
      {"pattern_endpoint_out_of_range.json", {"panel 'front' edge 3: endpoint 9 out of range (panel has 4 vertices)"}},
      {"pattern_endpoint_negative.json", {"panel 'front' edge 1", "endpoint -2 is out of range"}},
      {"pattern_endpoints_mistyped.json", {"panel 'front' edge 2", "'endpoints' must be an array of 2"}},
      {"pattern_edge_missing_endpoints.json", {"panel 'front' edge 2", "missing field 'endpoints'"}},
      {"pattern_open_edge_loop.json", {"panel 'front' edge 0", "open edge loop", "edge 1 starts at vertex 2"}},
      {"pattern_edge_loop_not_closed.json", {"panel 'front' edge 3", "open edge loop", "loop does not close"}},
      {"pattern_non_simple_edge_loop.json",
       {"panel 'front' edge 3", "non-simple edge loop", "vertex 0 is visited twice"}},
      {"pattern_self_intersecting_outline.json",
       {"panel 'front' edge 0", "self-intersecting outline", "crosses edge 2"}},
      {"pattern_curve_crosses_edge.json", {"panel 'front' edge 0", "self-intersecting outline", "crosses edge 2"}},
      {"pattern_cubic_self_loop.json", {"panel 'front' edge 0", "self-intersecting outline", "crosses itself"}},
      {"pattern_zero_length_edge.json", {"panel 'front' edge 1", "zero-length edge", "vertices 1 and 2"}},
      {"pattern_edge_same_endpoints.json", {"panel 'front' edge 1", "zero-length edge", "vertex 1"}},
      {"pattern_stitch_missing_panel.json", {"stitch 1", "panel 'sleeve' does not exist"}},
      {"pattern_stitch_missing_edge.json", {"stitch 1", "panel 'back' has no edge 12 (it has 4 edges)"}},
      {"pattern_stitch_mistyped.json", {"stitch 2", "must be an array [{panel, edge}, {panel, edge}]"}},
      {"pattern_edge_stitched_twice.json",
       {"stitch 2", "panel 'back' edge 3 is stitched twice", "already in stitch 0"}},
      {"pattern_edge_stitched_to_itself.json", {"stitch 2", "panel 'front' edge 0 is stitched to itself"}},
      {"pattern_unknown_stitch_flag.json", {"stitch 0", "unknown stitch flag 'inside_out'"}},
      {"pattern_stitch_lengths_too_different.json",
       {"stitch 1: panel 'front' edge 0 (length 40) and panel 'back' edge 0 (length 10) differ by 75%",
        "more than twice the other"}},
      {"pattern_unknown_curvature_type.json", {"panel 'front' edge 2", "unknown curvature type 'spline'"}},
      {"pattern_curvature_mistyped.json", {"panel 'front' edge 2", "curvature must be [x, y] or an object"}},
      {"pattern_cubic_wrong_params.json", {"panel 'front' edge 2", "cubic curvature params must hold 2"}},
      {"pattern_circle_radius_too_small.json", {"panel 'front' edge 2", "circle radius 5", "smaller than half"}},
      {"pattern_bad_units_negative.json", {"properties", "bad units", "-100"}},
      {"pattern_bad_units_string.json", {"properties", "bad units", "\"cm\""}},
      {"pattern_bad_curvature_coords.json", {"properties", "unknown curvature_coords 'polar'"}},
      {"pattern_missing_translation.json", {"panel 'front'", "missing field 'translation'"}},
      {"pattern_rotation_wrong_size.json", {"panel 'front'", "'rotation' must be an array of 3 numbers"}},
      {"pattern_panel_order_unknown_panel.json", {"panel_order", "'collar'", "not in 'panels'"}},
      {"pattern_duplicate_panel.json", {"panel 'front' defined twice"}},
      {"pattern_duplicate_key_in_panel.json", {"panel 'front': key 'translation' appears twice"}},
      {"pattern_tiny_panel.json",
       {"panel 'tiny': area 1e-18 m^2 is too small to mesh (its outline is 1.414e-09 m across"}},
      {"pattern_huge_panel.json", {"panel 'front': outline is 1414 m across (at most 100 m)"}},
      {"pattern_translation_1e308.json",
       {"panel 'front': 'translation' (1e+308, 0, 0) is 1e+306 m from the origin (at most 100 m)"}},
      {"pattern_rotation_1e308.json", {"panel 'front': 'rotation' y = 1e+308 degrees is out of range [-360, 360]"}},
  };
  return cases;
}

class BadPattern : public ::testing::TestWithParam<BadPatternCase> {};

TEST_P(BadPattern, RaisesInputErrorNamingFileElementAndProblem) {
  const BadPatternCase& c = GetParam();
  const std::filesystem::path file = test::testDataDir() / "bad" / c.file;
  ASSERT_TRUE(std::filesystem::exists(file)) << file;
  try {
    loadPattern(file);
    FAIL() << c.file << ": no InputError";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(file.string() + ": ", 0), 0u) << "message must start with the file: " << message;
    for (const std::string& part : c.expected)
      EXPECT_NE(message.find(part), std::string::npos) << "expected '" << part << "' in: " << message;
  }
}

std::string caseName(const ::testing::TestParamInfo<BadPatternCase>& info) {
  std::string name = std::filesystem::path(info.param.file).stem().string();
  for (char& ch : name)
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return name;
}

INSTANTIATE_TEST_SUITE_P(Files, BadPattern, ::testing::ValuesIn(badPatternCases()), caseName);

// Every pattern_*.json under tests/data/bad/ has a row in the table (and there are enough of them).
TEST(BadPatternTable, CoversEveryBadPatternFile) {
  std::set<std::string> listed;
  for (const auto& c : badPatternCases()) listed.insert(c.file);
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(test::testDataDir() / "bad")) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("pattern_", 0) != 0) continue;
    ++count;
    EXPECT_TRUE(listed.count(name)) << name << " has no row in the table";
  }
  EXPECT_GE(count, 22);
  EXPECT_EQ(size_t(count), listed.size());
}

// A needle-thin spike (tip angle 1e-10 rad) passes the pattern checks but meshes into triangles of almost no
// area; the garment builder refuses it naming the panel, before a solver divides by that area.
TEST(BadPatternMeshing, NeedleSpikeIsRefusedWhenMeshed) {
  const std::filesystem::path file = test::testDataDir() / "bad" / "garment_needle_spike.json";
  const Pattern pattern = loadPattern(file);
  MeshingOptions options;
  options.targetEdgeLength = 0.02;
  try {
    buildGarment(pattern, options);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(file.string() + ": panel 'spiked': meshing gives triangle ", 0), 0u) << message;
    EXPECT_NE(message.find("too sharp"), std::string::npos) << message;
  }
}

TEST(BadPatternTable, MissingFileIsAnInputError) {
  const std::filesystem::path file = test::testDataDir() / "bad" / "no_such_pattern.json";
  try {
    loadPattern(file);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no_such_pattern.json: cannot open"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace drape
