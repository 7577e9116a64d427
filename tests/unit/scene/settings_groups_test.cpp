// The settings a user holds in their head: groups in a fixed order, choices mapped to the solvers' enums by their
// position in the spec table, implementation switches refused in scene files, the stage as an enum.
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <utility>
#include <vector>

#include "drape/core/input_error.h"
#include "drape/newton/linear_solve.h"
#include "drape/scene/settings.h"
#include "drape/scene/stage_settings.h"
#include "drape/sim/stage.h"

namespace drape {
namespace {

// Every group holds settings, each group's rows are contiguous, and the groups come in SettingGroup's order.
TEST(SettingsGroups, EveryGroupIsOneRunOfRowsInTheEnumsOrder) {
  std::vector<SettingGroup> runs;
  for (const SettingSpec& spec : Settings::specs())
    if (runs.empty() || runs.back() != spec.group) runs.push_back(spec.group);
  ASSERT_EQ(runs.size(), static_cast<size_t>(kSettingGroupCount));
  for (int g = 0; g < kSettingGroupCount; ++g) EXPECT_EQ(static_cast<int>(runs[g]), g);
  std::set<std::string> names;
  for (int g = 0; g < kSettingGroupCount; ++g) {
    const auto group = static_cast<SettingGroup>(g);
    EXPECT_FALSE(std::string(settingGroupTitle(group)).empty());
    names.insert(settingGroupName(group));
  }
  EXPECT_EQ(names.size(), static_cast<size_t>(kSettingGroupCount));  // distinct names
}

// Groups follow what a setting is about, not only its key's prefix.
TEST(SettingsGroups, SettingsSitInTheGroupOfWhatTheyDecide) {
  const std::vector<std::pair<std::string, SettingGroup>> expected = {
      {"pattern", SettingGroup::Scene},
      {"sim.gravity", SettingGroup::Scene},
      {"placement.fit", SettingGroup::Scene},
      {"mesh.target_edge_length", SettingGroup::Mesh},
      {"fabric.density", SettingGroup::Fabric},
      {"contact.self_collision", SettingGroup::Contact},
      {"solver.stage", SettingGroup::Run},
      {"solver.max_sim_time", SettingGroup::Run},
      {"solver.preview.time_step", SettingGroup::Preview},
      {"solver.newton.h_max", SettingGroup::Drape},
      {"solver.cg.tolerance", SettingGroup::Drape},
      {"solver.damping.air", SettingGroup::Drape},
      {"solver.stitch_stiffness", SettingGroup::Drape},
      {"quality.max_strain", SettingGroup::Quality},
      {"camera.view", SettingGroup::Output}};
  for (const auto& [key, group] : expected) {
    const SettingSpec* spec = Settings::find(key);
    ASSERT_TRUE(spec) << key;
    EXPECT_EQ(spec->group, group) << key << " is in " << settingGroupName(spec->group);
  }
}

// choice<E> maps each name to the enumerator of the same meaning: the pairs below are written from the names,
// independently of the table's order, so a reordered choice list or enum fails here.
template <class Enum>
void expectChoices(const std::string& key, const std::vector<std::pair<std::string, Enum>>& pairs) {
  const SettingSpec* spec = Settings::find(key);
  ASSERT_TRUE(spec) << key;
  ASSERT_EQ(spec->type, SettingType::Choice) << key;
  for (const auto& [name, value] : pairs) {
    Settings s;
    s.set(key, name, "test");
    EXPECT_EQ(s.choice<Enum>(key), value) << key << " = " << name;
  }
}

TEST(SettingsChoices, MapToTheSolversEnumsByName) {
  expectChoices<newton::Preconditioner>("solver.cg.preconditioner",
                                        {{"none", newton::Preconditioner::None},
                                         {"diagonal", newton::Preconditioner::Diagonal},
                                         {"block_jacobi", newton::Preconditioner::BlockJacobi},
                                         {"incomplete_cholesky", newton::Preconditioner::IncompleteCholesky}});
  expectChoices<StagePlan>("solver.stage", {{"none", StagePlan::None},
                                            {"preview", StagePlan::Preview},
                                            {"drape", StagePlan::Drape},
                                            {"full", StagePlan::Full}});
  Settings s;
  EXPECT_EQ(s.stagePlan(), StagePlan::Drape);                                // the default
  EXPECT_THROW(s.choiceIndex("mesh.target_edge_length"), std::logic_error);  // not a choice: a bug, not input
}

// The switches between implementations that give the same drape are no scene settings: a scene naming one is told
// so, and where they are measured.
TEST(SettingsImplementationSwitches, AreRefusedWithALineNamingTheBenchmark) {
  const std::vector<std::pair<std::string, std::string>> switches = {
      {"solver.newton.block_map", "--configs on-map"},
      {"solver.newton.fold_dissipation", "--configs on-fold"},
      {"solver.newton.batched_gradients", "--configs on-batch"},
      {"solver.newton.closed_form_bending", "--configs on-bending"},
      {"solver.newton.parallel_assembly", "--configs on-parallel"},
      {"solver.newton.reorder_dofs", "--configs on-reorder"},
      {"solver.cg.fused_kernels", "--configs on-fused"},
      {"solver.preview.global_solver", "monolithic CHOLMOD"}};
  for (const auto& [key, where] : switches) {
    EXPECT_FALSE(Settings::find(key)) << key;
    Settings s;
    try {
      s.set(key, "false", "scene.json");
      ADD_FAILURE() << key << " was accepted";
    } catch (const InputError& e) {
      const std::string m = e.what();
      EXPECT_EQ(m.rfind("scene.json: '" + key + "' is no longer a setting", 0), 0u) << m;
      EXPECT_NE(m.find(where), std::string::npos) << m;
      EXPECT_EQ(m.find('\n'), std::string::npos) << "one line: " << m;
    }
  }
}

// The projective preview's settings went with it from the simulation (DESIGN.md 5a): a scene naming one is told in one
// line that the preview solves the drape's own model, and which settings it has; the two renamed ones their names.
TEST(SettingsProjectivePreview, AreRefusedWithWhatThePreviewIsNow) {
  for (const std::string key : {"solver.preview.courant_limit", "solver.preview.sewn_gap", "solver.preview.method",
                                "solver.preview.failure_strain", "solver.preview.local_step"}) {
    EXPECT_FALSE(Settings::find(key)) << key;
    Settings s;
    try {
      s.set(key, "1", "scene.json");
      ADD_FAILURE() << key << " was accepted";
    } catch (const InputError& e) {
      const std::string m = e.what();
      EXPECT_EQ(m.rfind("scene.json: '" + key + "' was a setting of the projective preview", 0), 0u) << m;
      EXPECT_NE(m.find("solver.preview.time_step"), std::string::npos) << m;
      EXPECT_EQ(m.find('\n'), std::string::npos) << "one line: " << m;
    }
  }
  Settings s;
  try {
    s.set("solver.preview.qn_time_step", "0.01", "scene.json");
    ADD_FAILURE() << "qn_time_step was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("replaced by solver.preview.time_step"), std::string::npos) << e.what();
  }
}

// Each preview default has one source, the stage's settings struct, and the table shows it.
TEST(SettingsProjectivePreview, PreviewDefaultsAreTheStagesStruct) {
  const Settings s;
  const PreviewStageSettings defaults;
  EXPECT_DOUBLE_EQ(s.number("solver.preview.time_step"), defaults.timeStep);
  EXPECT_EQ(s.integer("solver.preview.iterations"), defaults.iterations);
  EXPECT_EQ(s.integer("solver.preview.domains"), defaults.domains);
  EXPECT_DOUBLE_EQ(s.number("solver.preview.max_time"), defaults.maxTime);
  EXPECT_DOUBLE_EQ(s.number("solver.preview.handoff_speed"), defaults.handoffSpeed);
  int previewSettings = 0;
  for (const SettingSpec& spec : Settings::specs()) previewSettings += spec.key.rfind("solver.preview.", 0) == 0;
  EXPECT_LE(previewSettings, 18);  // at most half of the projective preview's 36
}

TEST(Stage, NamesAreThoseOfTheStatistics) {
  EXPECT_STREQ(stageName(Stage::Placed), "placed");
  EXPECT_STREQ(stageName(Stage::Preview), "preview");
  EXPECT_STREQ(stageName(Stage::Drape), "drape");
  EXPECT_STREQ(stageName(Stage::Done), "done");
}

}  // namespace
}  // namespace drape
