// drape --bench --extremes end to end through the executable: every cell of the extremes grid on the hanging cloth is
// run in the drape and reported with its verdict, and the exit status says whether every cell held. --bench's sweep is
// checked in tests/cli/cli_solver_render_test.cpp.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_solver_support.h"
#include "run_process.h"

namespace drape::test {
namespace {

TEST(CliBench, ExtremesGridReportsEveryCellAndItsVerdict) {
  // The hanging cloth at 20 cm for 0.01 s: every cell of the grid runs in the drape and is reported with its verdict;
  // the exit status says whether every cell held.
  const auto report = kScratch / "extremes.json";
  auto r = drape("--bench " + asset("scenes/hanging_cloth.json") +
                 " --set mesh.target_edge_length=0.2 --extremes --solver drape --max-sim-time 0.01 -o " +
                 quote(report.string()));
  const auto j = nlohmann::json::parse(readWhole(report));
  const auto& cells = j.at("cells");
  ASSERT_EQ(cells.size(), 27u);  // 12 settings at both ends, 3 combinations
  int failed = 0;
  for (const auto& cell : cells) {
    EXPECT_EQ(cell.at("stage"), "drape");
    EXPECT_FALSE(cell.at("settings").empty()) << cell.at("cell");
    EXPECT_TRUE(cell.at("finite").get<bool>()) << cell.at("cell");
    failed += !cell.at("holds").get<bool>();
  }
  EXPECT_EQ(j.at("failed_cells"), failed);
  EXPECT_EQ(r.exitCode, failed == 0 ? 0 : 1) << r.err << r.out;
  EXPECT_NE(r.out.find(std::to_string(27 - failed) + " of 27 cells hold"), std::string::npos) << r.out;
  auto both = drape("--bench " + asset("scenes/hanging_cloth.json") + " --extremes --sweep solver.cg.tolerance=1e-1");
  EXPECT_EQ(both.exitCode, 1);
  EXPECT_NE(both.err.find("--extremes: only with --bench, and not with --sweep"), std::string::npos) << both.err;
}

TEST(CliBench, ExtremesCellRunsOnlyTheCellsNamed) {
  // --cell reruns chosen cells: only those, in every stage asked for; a name that is no cell, or --cell without
  // --extremes, is refused with one line before anything runs.
  const auto report = kScratch / "extremes_cells.json";
  auto r = drape("--bench " + asset("scenes/hanging_cloth.json") +
                 " --set mesh.target_edge_length=0.2 --extremes --solver drape --max-sim-time 0.01 --cell \"bending max\""
                 " --cell \"time step min\" -o " + quote(report.string()));
  const auto j = nlohmann::json::parse(readWhole(report));
  const auto& cells = j.at("cells");
  ASSERT_EQ(cells.size(), 2u) << r.out;
  EXPECT_EQ(cells[0].at("cell"), "bending max");
  EXPECT_EQ(cells[1].at("cell"), "time step min");
  EXPECT_NE(r.out.find("of 2 cells hold"), std::string::npos) << r.out;
  auto unknown = drape("--bench " + asset("scenes/hanging_cloth.json") + " --extremes --cell \"bending maximum\"");
  EXPECT_EQ(unknown.exitCode, 1);
  EXPECT_NE(unknown.err.find("--cell: no extremes cell 'bending maximum'"), std::string::npos) << unknown.err;
  auto alone = drape("--bench " + asset("scenes/hanging_cloth.json") + " --cell \"bending max\"");
  EXPECT_EQ(alone.exitCode, 1);
  EXPECT_NE(alone.err.find("--cell: only with --bench --extremes"), std::string::npos) << alone.err;
}

}  // namespace
}  // namespace drape::test
