// drape --simulate (Newton drape), --render and --make-avatar end to end (--bench: cli_trade_test.cpp) through the executable. The
// extremes grid of --bench and the mannequin --make-avatar makes in every run are slow tests
// (tests/slow/cli_bench_extremes_test.cpp, tests/slow/cli_make_avatar_test.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "cli_solver_support.h"
#include "drape/render/png_io.h"
#include "run_process.h"
#include "shared_data.h"

namespace drape::test {
namespace {

TEST(CliSimulate, DrapeWritesGarmentAndPerStepStats) {
  const auto obj = kScratch / "hang.obj", stats = kScratch / "hang.json";
  // Cut short, not at rest: the rest requirement of the quality verdict is off, its other checks pass.
  auto r = drape("--simulate " + asset("scenes/hanging_cloth.json") + " --set mesh.target_edge_length=0.1" +
                 " --set quality.require_rest=false --max-sim-time 0.02 -o " + quote(obj.string()) + " --stats " +
                 quote(stats.string()));
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  const auto j = nlohmann::json::parse(readWhole(stats));
  EXPECT_EQ(j.at("status"), "MaxSimTime");
  EXPECT_TRUE(j.at("quality").at("passed").get<bool>()) << j.at("quality");
  EXPECT_EQ(j.at("quality").at("checks").at("at_rest").at("value").get<double>(), 0.0);
  EXPECT_NEAR(j.at("sim_time_s").get<double>(), 0.02, 1e-3);
  EXPECT_EQ(j.at("per_step").size(), j.at("steps").get<size_t>());
  const auto terms = j.at("terms").get<std::vector<std::string>>();
  EXPECT_NE(std::find(terms.begin(), terms.end(), "membrane"), terms.end());
  EXPECT_NE(std::find(terms.begin(), terms.end(), "pins"), terms.end());
  // Model only what the scene requires: no collider, so no contact or friction term.
  EXPECT_EQ(std::find(terms.begin(), terms.end(), "avatar_contact"), terms.end());
  EXPECT_EQ(std::find(terms.begin(), terms.end(), "friction"), terms.end());
  int reused = 0;
  for (const auto& s : j.at("per_step")) {
    EXPECT_TRUE(std::isfinite(s.at("residual").get<double>()));
    reused += s.at("hessian_reused").get<bool>();
    // Where the drape step's time went: assembly, gradient passes and linear solves, within the step's wall time.
    const double assembly = s.at("assembly_time_s"), gradient = s.at("gradient_time_s"),
                 solve = s.at("linear_solve_time_s");
    EXPECT_GT(assembly, 0.0);
    EXPECT_GT(solve, 0.0);
    EXPECT_GE(gradient, 0.0);
    const double queries = s.at("contact_query_time_s");
    EXPECT_GE(queries, 0.0);
    EXPECT_LE(assembly + gradient + solve + queries, s.at("wall_time_s").get<double>());
    // Equilibrium: the unbalanced force (largest at least the RMS) and the step's largest displacement.
    EXPECT_GE(s.at("force_max").get<double>(), s.at("force_rms").get<double>());
    EXPECT_GT(s.at("force_rms").get<double>(), 0.0);
    EXPECT_GT(s.at("displacement_max_m").get<double>(), 0.0);
  }
  // The profile: the phases sum over the steps and add up to their wall time.
  const auto& profile = j.at("profile");
  double phases = 0.0, assemblySum = 0.0, stepsWall = 0.0;
  for (const char* phase : {"assembly_s", "linear_solve_s", "contact_queries_s", "line_search_s", "bookkeeping_s"})
    phases += profile.at(phase).get<double>();
  for (const auto& s : j.at("per_step")) {
    assemblySum += s.at("assembly_time_s").get<double>();
    stepsWall += s.at("wall_time_s").get<double>();
  }
  EXPECT_NEAR(profile.at("assembly_s").get<double>(), assemblySum, 1e-9 + 1e-9 * assemblySum);
  EXPECT_NEAR(profile.at("steps_s").get<double>(), phases, 1e-9 + 1e-9 * phases);
  EXPECT_NEAR(phases, stepsWall, 1e-6 + 1e-6 * stepsWall);
  EXPECT_LE(stepsWall, j.at("wall_time_s").get<double>());
  // Hessian reuse (solver.newton.hessian_reuse_steps, default 4): some steps, never all (the first is fresh).
  EXPECT_GT(reused, 0);
  EXPECT_LT(reused, static_cast<int>(j.at("per_step").size()));
  EXPECT_NE(readWhole(obj).find("\nf "), std::string::npos);
}

// Which drape solves used the two-level PCG and the coupled groups: with both engaged from the first solve, every
// solve uses the coarse level and the stitched default t-shirt's solves find groups; with the groups off, none. The
// lagged coarse factor is factorised for fewer solves than use it.
TEST(CliSimulate, DrapeStatsCountTheSolvesWithEachPreconditionerLevel) {
  const auto obj = kScratch / "levels.obj";
  auto counts = [&](const std::string& groups) {
    const auto stats = kScratch / ("levels-" + groups + ".json");
    auto r = drape("--simulate " + asset("scenes/default.json") + " --solver drape --max-sim-time 0.03" +
                   " --set mesh.target_edge_length=0.05 --set solver.cg.coarse_from_iterations=0" +
                   " --set solver.cg.coupled_from_iterations=0 --set solver.cg.coupled_groups=" + groups + " -o " +
                   quote(obj.string()) + " --stats " + quote(stats.string()));
    // 0.03 s into the drape the t-shirt is not at rest (nor sewn onto the body): its quality verdict fails.
    EXPECT_EQ(r.exitCode, 4) << r.err << r.out;
    const auto j = nlohmann::json::parse(readWhole(stats));
    // Newton iterations (one solve each), coarse solves, coupled solves, coarse factorisations
    std::array<int, 4> n{};
    for (const auto& s : j.at("per_step")) {
      const int iterations = s.at("iterations"), coarse = s.at("coarse_solves"), coupled = s.at("coupled_solves");
      const int factorizations = s.at("coarse_factorizations");
      EXPECT_EQ(coarse, iterations);
      EXPECT_LE(coupled, iterations);
      EXPECT_LE(factorizations, coarse);
      n[0] += iterations, n[1] += coarse, n[2] += coupled, n[3] += factorizations;
    }
    return n;
  };
  const std::array<int, 4> on = counts("0.6"), off = counts("0");
  EXPECT_GT(on[2], on[0] / 2) << "coupled solves " << on[2] << " of " << on[0];
  EXPECT_EQ(off[2], 0);
  EXPECT_GT(off[1], 0);
  // The lagged coarse factor (solver.cg.coarse_lagged): factorised for some solves of this contact scene, not all.
  EXPECT_GT(on[3], 0);
  EXPECT_LT(on[3], on[1]) << "coarse factorisations " << on[3] << " of " << on[1] << " solves";
}

TEST(CliSimulate, StepLimitIsReportedAsSuch) {
  const auto obj = kScratch / "steps.obj", stats = kScratch / "steps.json";
  auto r = drape("--simulate " + asset("scenes/hanging_cloth.json") + " --set mesh.target_edge_length=0.1" +
                 " --set solver.max_steps=3 -o " + quote(obj.string()) + " --stats " + quote(stats.string()));
  // Stopped by the step limit, not at rest: the quality verdict fails on that (exit 4) and says why.
  ASSERT_EQ(r.exitCode, 4) << r.err << r.out;
  EXPECT_NE(r.out.find("warning: quality: at_rest: the run ended with MaxSteps"), std::string::npos) << r.out;
  const auto j = nlohmann::json::parse(readWhole(stats));
  EXPECT_EQ(j.at("status"), "MaxSteps");
  EXPECT_EQ(j.at("steps").get<int>(), 3);
  EXPECT_LT(j.at("sim_time_s").get<double>(), 0.01);  // far from the scene's time limit
}

// Progress lines: one every 0.1 s simulated, with the steps and the wall time so far, and once 5 % of
// solver.max_sim_time has passed, at most how long the rest takes at the rate so far.
TEST(CliSimulate, ProgressLinesSayTheWallTimeAndWhatIsLeft) {
  auto r =
      drape("--simulate " + asset("scenes/hanging_cloth.json") + " --set mesh.target_edge_length=0.1" +
            " --max-sim-time 0.25 --set quality.require_rest=false -o " + quote((kScratch / "progress.obj").string()) +
            " --stats " + quote((kScratch / "progress.json").string()));
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  const int totalSteps = nlohmann::json::parse(readWhole(kScratch / "progress.json")).at("steps").get<int>();
  int lines = 0, estimates = 0, lastStep = 0;
  std::istringstream text(r.out);
  for (std::string line; std::getline(text, line);) {
    if (line.rfind("  drape t=", 0) != 0) continue;
    ++lines;
    EXPECT_NE(line.find(" wall="), std::string::npos) << line;
    const double t = std::stod(line.substr(line.find("t=") + 2));
    ASSERT_NE(line.find(" step="), std::string::npos) << line;
    const int step = std::stoi(line.substr(line.find(" step=") + 6));
    EXPECT_GT(step, lastStep) << line;  // steps taken so far, counted from the first
    EXPECT_LE(step, totalSteps) << line;
    lastStep = step;
    const bool estimated = line.find("left<=") != std::string::npos;
    EXPECT_EQ(estimated, t >= 0.05 * 0.25) << line;
    estimates += estimated;
  }
  EXPECT_GE(lines, 3) << r.out;  // t = 0, 0.1, 0.2
  EXPECT_GE(estimates, 2) << r.out;
}

TEST(CliSimulate, ColliderSceneUsesContactAndFriction) {
  const auto stats = kScratch / "tablecloth.json";
  // The cloth starts 0.2 m above the sphere: after 0.4 s it lies on it (not at rest yet: the rest requirement of
  // the quality verdict is off).
  auto r = drape("--simulate " + asset("scenes/tablecloth.json") +
                 " --set mesh.target_edge_length=0.1 --set quality.require_rest=false --max-sim-time 0.4 -o " +
                 quote((kScratch / "tc.obj").string()) + " --stats " + quote(stats.string()));
  ASSERT_TRUE(r.exitCode == 0 || r.exitCode == 4) << r.err;
  const auto report = nlohmann::json::parse(readWhole(stats));
  // The coarse cloth is still landing on the sphere: whether its verdict passes (a few vertices may be inside) is
  // not this test's subject, but the exit status is the verdict's.
  EXPECT_EQ(r.exitCode, report.at("quality").at("passed").get<bool>() ? 0 : 4) << report.at("quality");
  EXPECT_EQ(report.at("per_step")[0].at("contacts"), 0);
  EXPECT_GT(report.at("final").at("contacts").get<int>(), 0);
  const auto terms = report.at("terms").get<std::vector<std::string>>();
  EXPECT_NE(std::find(terms.begin(), terms.end(), "avatar_contact"), terms.end());
  EXPECT_NE(std::find(terms.begin(), terms.end(), "friction"), terms.end());
  auto frictionless = drape("--simulate " + asset("scenes/tablecloth.json") +
                            " --set mesh.target_edge_length=0.1 --set contact.friction=false" +
                            " --set quality.require_rest=false --max-sim-time 0.005 -o " +
                            quote((kScratch / "tc2.obj").string()) + " --stats " + quote(stats.string()));
  ASSERT_EQ(frictionless.exitCode, 0) << frictionless.err;
  const auto terms2 = nlohmann::json::parse(readWhole(stats)).at("terms").get<std::vector<std::string>>();
  EXPECT_EQ(std::find(terms2.begin(), terms2.end(), "friction"), terms2.end());
}

TEST(CliSimulate, FullPipelineRunsThePreviewThenTheDrape) {
  const auto stats = kScratch / "full.json";
  auto r = drape("--simulate " + asset("scenes/tablecloth.json") + " --solver full --set mesh.target_edge_length=0.1" +
                 " --set solver.preview.max_time=0.05 --set quality.require_rest=false --max-sim-time 0.06 -o " +
                 quote((kScratch / "full.obj").string()) + " --stats " + quote(stats.string()));
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  const auto j = nlohmann::json::parse(readWhole(stats));
  bool sawPreview = false, sawDrape = false;
  for (const auto& s : j.at("per_step")) {
    const std::string stage = s.at("stage");
    if (stage == "preview") {
      EXPECT_FALSE(sawDrape) << "preview after the drape started";
      sawPreview = true;
      EXPECT_GE(s.at("domains").get<int>(), 1);
      EXPECT_TRUE(s.at("quasi_newton").get<bool>());  // the drape's model by L-BFGS
    }
    if (stage == "drape") sawDrape = true;
  }
  EXPECT_TRUE(sawPreview);
  EXPECT_TRUE(sawDrape);
  EXPECT_GE(j.at("sim_time_s").get<double>(), 0.06 - 1e-9);
  EXPECT_GE(j.at("domains").get<int>(), 1);
}

// The projective preview's settings went with it: a scene or command line that names one is told, in one line, what
// the preview is now and which settings it has.
TEST(CliSimulate, ProjectivePreviewSettingIsRefusedInOneLine) {
  auto r = drape("--simulate " + asset("scenes/tablecloth.json") + " --solver full" +
                 " --set solver.preview.courant_limit=5 -o " + quote((kScratch / "refused.obj").string()));
  EXPECT_NE(r.exitCode, 0);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("solver.preview.courant_limit"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("the preview solves the drape's own model"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(kScratch / "refused.obj"));
  // A renamed one says its new name.
  r = drape("--simulate " + asset("scenes/tablecloth.json") + " --set solver.preview.qn_iterations=3 -o " +
            quote((kScratch / "refused.obj").string()));
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.err.find("solver.preview.iterations"), std::string::npos) << r.err;
}

TEST(CliRender, WritesPngOfRequestedSize) {
  const auto png = kScratch / "default.png";
  std::filesystem::remove(png);
  auto r = drape("--render " + asset("scenes/tablecloth.json") + " -o " + quote(png.string()) + " --size 160x120");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const render::Image image = render::readPng(png);
  EXPECT_EQ(image.width, 160);
  EXPECT_EQ(image.height, 120);
  // Not a blank image: the garment and the sphere make many distinct colours.
  std::set<uint32_t> colours;
  for (size_t i = 0; i + 3 < image.pixels.size(); i += 4)
    colours.insert(image.pixels[i] << 16 | image.pixels[i + 1] << 8 | image.pixels[i + 2]);
  EXPECT_GT(colours.size(), 50u);
}

TEST(CliRender, ViewAllWritesAContactSheet) {
  const auto png = kScratch / "sheet.png";
  auto r = drape("--render " + asset("scenes/tablecloth.json") + " -o " + quote(png.string()) +
                 " --size 64x64 --view all --mode strain");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const render::Image image = render::readPng(png);
  EXPECT_EQ(image.width, 3 * 64);
  EXPECT_EQ(image.height, 2 * 64);
}

TEST(CliRender, BodyMeshRendersOnItsOwn) {
  const auto png = kScratch / "body.png";
  std::filesystem::remove(png);
  auto r =
      drape("--render " + asset("avatars/female.obj") + " -o " + quote(png.string()) + " --size 90x160 --view front");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const render::Image image = render::readPng(png);
  ASSERT_EQ(image.width, 90);
  // The background is a vertical gradient (constant along a row but for the floor grid). The body stands in the
  // middle: on the centre column many rows differ clearly from the same row's left-border pixel; on a column
  // near the border few do.
  auto bodyRows = [&](int x) {
    int n = 0;
    for (int y = 0; y < image.height; ++y) {
      const uint8_t* p = &image.pixels[4 * (y * image.width + x)];
      const uint8_t* edge = &image.pixels[4 * (y * image.width + 1)];
      if (std::abs(p[0] - edge[0]) + std::abs(p[1] - edge[1]) + std::abs(p[2] - edge[2]) > 30) ++n;
    }
    return n;
  };
  EXPECT_GT(bodyRows(45), 60) << "centre column";
  EXPECT_LT(bodyRows(4), 10) << "near the border";
  auto simulate = drape("--render " + asset("avatars/female.obj") + " -o " + quote(png.string()) + " --simulate drape");
  EXPECT_EQ(simulate.exitCode, 1);
  EXPECT_NE(simulate.err.find("a body mesh has nothing to simulate"), std::string::npos) << simulate.err;
}

TEST(CliRender, ErrorsAreOneLine) {
  auto notPng = drape("--render " + asset("scenes/tablecloth.json") + " -o " + quote((kScratch / "x.jpg").string()));
  EXPECT_EQ(notPng.exitCode, 1);
  EXPECT_NE(notPng.err.find("must be a .png"), std::string::npos) << notPng.err;
  auto missing = drape("--render /nonexistent.json -o " + quote((kScratch / "x.png").string()));
  EXPECT_EQ(missing.exitCode, 1);
  EXPECT_NE(missing.err.find("/nonexistent.json"), std::string::npos);
  auto badDir = drape("--render " + asset("scenes/tablecloth.json") + " -o /nonexistent-dir/x.png --size 32x32");
  EXPECT_EQ(badDir.exitCode, 1);
  EXPECT_NE(badDir.err.find("/nonexistent-dir/x.png"), std::string::npos) << badDir.err;
  auto badStage = drape("--render " + asset("scenes/tablecloth.json") + " -o x.png --simulate everything");
  EXPECT_EQ(badStage.exitCode, 1);
  EXPECT_NE(badStage.err.find("'everything' is not one of none|preview|drape|full"), std::string::npos) << badStage.err;
}

}  // namespace
}  // namespace drape::test

namespace drape::test {
namespace {

TEST(CliMakeAvatar, BadMeasurementsNameTheFile) {
  auto r = drape("--make-avatar " + asset("fabrics/denim.json") + " -o " + quote((kScratch / "x.obj").string()));
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("denim.json"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace drape::test

namespace drape::test {
namespace {

TEST(CliRender, ExplicitCameraFromSettingsChangesTheView) {
  const auto preset = kScratch / "cam_preset.png", explicitCam = kScratch / "cam_explicit.png";
  auto a = drape("--render " + asset("scenes/tablecloth.json") + " -o " + quote(preset.string()) + " --size 96x96");
  auto b = drape("--render " + asset("scenes/tablecloth.json") + " -o " + quote(explicitCam.string()) +
                 " --size 96x96 --set camera.eye=0,3,0.01 --set camera.target=0,0.8,0");
  ASSERT_EQ(a.exitCode, 0) << a.err;
  ASSERT_EQ(b.exitCode, 0) << b.err;
  const render::Image ia = render::readPng(preset), ib = render::readPng(explicitCam);
  ASSERT_EQ(ia.pixels.size(), ib.pixels.size());
  size_t differing = 0;
  for (size_t i = 0; i < ia.pixels.size(); i += 4) differing += std::abs(int(ia.pixels[i]) - int(ib.pixels[i])) > 8;
  EXPECT_GT(differing, ia.pixels.size() / 4 / 10);  // a top-down view differs from the three-quarter preset
  auto bad = drape("--render " + asset("scenes/tablecloth.json") + " -o " + quote(explicitCam.string()) +
                   " --size 32x32 --set camera.eye=0,1,0 --set camera.target=0,1,0");
  EXPECT_EQ(bad.exitCode, 1);
  EXPECT_NE(bad.err.find("camera.eye"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace drape::test
