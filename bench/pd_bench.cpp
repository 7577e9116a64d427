// Preview (PD-DD) benchmarks, run by hand: `drape_pd_bench [--quick] [global|local|iteration|contact]`,
// `drape_pd_bench solve [SIDE] [D] [REPS]` (the DD global solve alone on a SIDE x SIDE hanging cloth, 2 threads:
// minimum, median and 90th percentile of REPS solves; default 317 16 100, i.e. 100k vertices) and
// `drape_pd_bench interactive [SCENE] [--from DRAPED.obj] [--steps N] [--cap SECONDS] [--only VARIANT] [--verbose]`
// (--from: start from the vertex positions of an OBJ the garment was written to, e.g. by drape --simulate). Prints Markdown
// tables for docs/BENCHMARKS.md: global solve DD vs monolithic CHOLMOD (pd-dd Fig. 9), Gauss-Seidel vs Jacobi
// local step (Fig. 12/13), time per L-G iteration at 100k vertices, SD + PCG vs PCG for contact (Fig. 8), and the
// interactive preview speed of a real garment on the mannequin (issue 6: >= 30 steps/s at 10k vertices).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "drape/collision/avatar_collider.h"
#include "drape/geometry/primitives.h"
#include "drape/pd/dd_solver.h"
#include "drape/pd/domain_partition.h"
#include "drape/pd/grid_cloth.h"
#include "drape/pd/pd_system.h"
#include "drape/garment/garment_builder.h"
#include "drape/io/garment_state.h"
#include "drape/pd/preview_solver.h"
#include "drape/scene/pins.h"
#include "drape/scene/scene.h"
#include "drape/sim/simulation.h"
#include "drape/sim/snapshot_builder.h"
#include "sim/cloth_model_builder.h"

using namespace drape;
using namespace drape::pd;
using Clock = std::chrono::steady_clock;

namespace {

double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// Median-free mean over `reps` solves, seconds per solve.
double timeSolve(const GlobalSolver& s, const Eigen::MatrixX3d& b, int reps) {
  Eigen::MatrixX3d x;
  s.solve(b, x);  // warm-up
  const auto t = Clock::now();
  for (int i = 0; i < reps; ++i) s.solve(b, x);
  return since(t) / reps;
}

drape::model::ClothModel grid(int n) {
  GridClothOptions o;
  o.nx = n;
  o.ny = n;
  return makeGridCloth(o);
}

// A right-hand side of the global step (|free| x 3) with standard normal entries, the same for every run.
Eigen::MatrixX3d randomRightHandSide(const PdSystem& sys) {
  std::mt19937 rng(3);
  std::normal_distribution<double> normal;
  Eigen::MatrixX3d b(sys.freeCount(), 3);
  for (int i = 0; i < b.rows(); ++i)
    for (int c = 0; c < 3; ++c) b(i, c) = normal(rng);
  return b;
}

void globalSolveTable(bool quick) {
  std::printf("\n### Global solve: domain-decomposed vs monolithic CHOLMOD (pd-dd Fig. 9)\n\n");
  std::printf("Square hanging cloth, two pinned corners; DOF = 3 x vertices (the paper's count). Time per solve of\n"
              "K x = b for the three coordinates, mean of repeated solves; speed-up = monolithic / DD.\n\n");
  std::printf("| DOF | D | threads | N_C | N_B - N_C | max N_R | setup (s) | DD solve (ms) | monolithic (ms) | speed-up |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|\n");
  const std::vector<int> sizes = quick ? std::vector<int>{60} : std::vector<int>{142, 245};  // 60k, 180k DOF
  for (int n : sizes) {
    const drape::model::ClothModel model = grid(n);
    PdSystem sys(model, PreviewSettings{});
    const Eigen::MatrixX3d b = randomRightHandSide(sys);
    const int reps = n > 200 ? 10 : 20;
    std::map<int, double> mono;
    for (int threads : {1, 2}) {
      tbb::task_arena arena(threads);
      arena.execute([&] {
        MonolithicSolver m(sys.matrix());
        mono[threads] = timeSolve(m, b, reps);
        Eigen::MatrixX3d xm;
        m.solve(b, xm);
        for (int d : {2, 4, 8, 16, 32, 64}) {
          const auto t0 = Clock::now();
          const auto part = partitionTriangles(model.triangles, model.numVertices(), {}, d);
          DomainDecomposedSolver dd(splitSystem(sys, part, d), sys.freeCount());
          const double setup = since(t0);
          Eigen::MatrixX3d x;
          dd.solve(b, x);
          const double err = (x - xm).norm() / xm.norm();
          const double t = timeSolve(dd, b, reps);
          std::printf("| %dk | %d | %d | %d | %d | %d | %.2f | %.2f | %.2f | %.2fx%s |\n", 3 * sys.freeCount() / 1000, d,
                      threads, dd.cornerCount(), dd.duplicateCount(), dd.maxRemainder(), setup, 1e3 * t,
                      1e3 * mono[threads], mono[threads] / t, err > 1e-9 ? " (ERROR)" : "");
          std::fflush(stdout);
        }
      });
    }
  }
}

struct RunResult {
  int iterations = 0;
  double seconds = 0.0, local = 0.0, global = 0.0;
  int steps = 0;
};

RunResult run(const drape::model::ClothModel& model, const PreviewSettings& s, int steps,
              std::shared_ptr<const collision::AvatarCollider> collider = nullptr, int* pcg = nullptr,
              double* collisionTime = nullptr, int warmupSteps = 0) {
  PreviewSolver solver(model, s, collider);
  for (int i = 0; i < warmupSteps; ++i) solver.step();  // first touches of the solver's memory, not timed
  RunResult r;
  for (int i = 0; i < steps; ++i) {
    const PreviewReport rep = solver.step();
    r.iterations += rep.iterations;
    r.seconds += rep.wallTime;
    r.local += rep.localTime;
    r.global += rep.globalTime;
    if (pcg) *pcg += rep.pcgIterations;
    if (collisionTime) *collisionTime += rep.collisionTime;
  }
  r.steps = steps;
  return r;
}

void localStepTable(bool quick) {
  std::printf("\n### Local step: Gauss-Seidel vs Jacobi (pd-dd Fig. 12/13)\n\n");
  std::printf("Hanging cloth, two pinned corners, tolerance 1e-5, cap 200 L-G iterations, first 20 steps from rest,\n"
              "2 threads, D = 8, exact (DD) global solve in both.\n\n");
  std::printf("| vertices | h | GS iterations/step | Jacobi iterations/step | ratio J/GS | GS ms/step | Jacobi ms/step |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  const std::vector<int> sizes = quick ? std::vector<int>{30} : std::vector<int>{50, 100};
  for (int n : sizes)
    for (double h : {1.0 / 240.0, 1.0 / 120.0, 1.0 / 60.0}) {
      PreviewSettings s;
      s.threads = 2;
      s.domains = 8;
      s.timeStep = h;
      s.tolerance = 1e-5;
      s.maxIterations = 200;
      const drape::model::ClothModel model = grid(n);
      s.localStep = LocalStepKind::GaussSeidel;
      const RunResult gs = run(model, s, 20);
      s.localStep = LocalStepKind::Jacobi;
      const RunResult jc = run(model, s, 20);
      std::printf("| %d | 1/%d | %.1f | %.1f | %.2f | %.1f | %.1f |\n", n * n, static_cast<int>(std::lround(1.0 / h)),
                  gs.iterations / 20.0, jc.iterations / 20.0, static_cast<double>(jc.iterations) / gs.iterations,
                  1e3 * gs.seconds / 20, 1e3 * jc.seconds / 20);
      std::fflush(stdout);
    }
}

void perIterationTable(bool quick) {
  std::printf("\n### Time per L-G iteration, hanging cloth without contact (target <= 20 ms at 100k vertices)\n\n");
  std::printf("10 L-G iterations per step, 2 steps timed after 1 untimed, 2 threads.\n\n");
  std::printf("| vertices | threads | D | local step | ms/iteration (local + global) | local ms | global ms |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  const std::vector<int> sizes = quick ? std::vector<int>{100} : std::vector<int>{100, 317};  // 10k, 100k
  for (int n : sizes)
    for (int d : {16, 32})
      for (LocalStepKind kind : {LocalStepKind::GaussSeidel, LocalStepKind::Jacobi}) {
        PreviewSettings s;
        s.threads = 2;
        s.domains = d;
        s.localStep = kind;
        s.tolerance = 0.0;
        s.maxIterations = 10;
        const RunResult r = run(grid(n), s, 2, nullptr, nullptr, nullptr, 1);
        std::printf("| %d | 2 | %d | %s | %.1f | %.1f | %.1f |\n", n * n, d,
                    kind == LocalStepKind::GaussSeidel ? "GS" : "Jacobi", 1e3 * (r.local + r.global) / r.iterations,
                    1e3 * r.local / r.iterations, 1e3 * r.global / r.iterations);
        std::fflush(stdout);
      }
}


void contactTable(bool quick) {
  std::printf("\n### Collision-aware global solve: dual SD step + PCG vs PCG alone (pd-dd Fig. 8)\n\n");
  std::printf("Tablecloth dropped on a sphere (r = 0.3 m), 60 steps of 1/120 s, 2 threads, D = 8, PCG tolerance 1e-6.\n\n");
  std::printf("| vertices | solve | PCG iterations (total) | collision ms/step | ms/step | L-G iterations/step |\n");
  std::printf("|---|---|---|---|---|---|\n");
  const int n = quick ? 40 : 100;
  GridClothOptions o;
  o.nx = n;
  o.ny = n;
  o.horizontal = true;
  o.elevation = 0.33;
  o.pinTopCorners = false;
  const drape::model::ClothModel model = makeGridCloth(o);
  auto collider = std::make_shared<collision::AvatarCollider>(makeIcosphere(Eigen::Vector3d::Zero(), 0.3, 5));
  for (ContactSolveKind kind : {ContactSolveKind::DualThenPcg, ContactSolveKind::Pcg}) {
    PreviewSettings s;
    s.threads = 2;
    s.domains = 8;
    s.contactSolve = kind;
    int pcg = 0;
    double ct = 0.0;
    const int steps = 60;
    const RunResult r = run(model, s, steps, collider, &pcg, &ct);
    std::printf("| %d | %s | %d | %.1f | %.1f | %.1f |\n", n * n, kind == ContactSolveKind::DualThenPcg ? "SD + PCG" : "PCG",
                pcg, 1e3 * ct / steps, 1e3 * r.seconds / steps, static_cast<double>(r.iterations) / steps);
    std::fflush(stdout);
  }
}


// ---- interactive: a real garment on the mannequin --------------------------------------------------------------

// Signed distances (metres) of every vertex of positions (3|V|) to the collider.
std::vector<double> signedDistances(const collision::AvatarCollider& c, const Eigen::VectorXd& x) {
  std::vector<double> d(x.size() / 3);
  tbb::parallel_for(0, static_cast<int>(d.size()), [&](int v) { d[v] = c.signedDistance(x.segment<3>(3 * v)); });
  return d;
}

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  const size_t k = std::min(v.size() - 1, static_cast<size_t>(q * (v.size() - 1)));
  std::nth_element(v.begin(), v.begin() + k, v.end());
  return v[k];
}

struct Variant {
  std::string name;
  std::function<void(PreviewSettings&)> apply;
};

void interactiveTable(const std::string& sceneFile, const std::string& from, int steps, double cap,
                      const std::string& only, bool verbose) {
  SceneRequest request;
  request.input = sceneFile;
  const Scene scene = loadScene(request);
  const Garment garment = buildGarment(scene.pattern, meshingOptions(scene));
  const std::vector<int> pinned = resolvePins(scene, garment);
  drape::model::ClothModel model = buildClothModel(scene, garment, pinned);
  if (!from.empty()) {
    const Eigen::MatrixX3d x = readGarmentPositions(from, garment);
    for (int v = 0; v < model.numVertices(); ++v) model.positions.segment<3>(3 * v) = x.row(v).transpose();
  }
  const TriangleMesh colliderMesh = mergedColliders(scene);
  std::shared_ptr<const collision::AvatarCollider> collider;
  if (colliderMesh.triangleCount() > 0) collider = std::make_shared<const collision::AvatarCollider>(colliderMesh);
  // pd-dd's projective solver on the scene's garment and body: its own defaults at the step and quasi-static start
  // it ran garments with, the scene's contact thickness and friction.
  PreviewSettings base;
  base.timeStep = 1.0 / 480.0;
  base.relaxationTime = 0.05;
  base.contactThickness = contactThickness(scene);
  if (scene.settings.flag("contact.friction")) {
    base.friction = scene.fabric.friction;
    for (const auto& [panel, fabric] : scene.panelFabrics) base.friction = std::max(base.friction, fabric.friction);
  }
  const int nv = model.numVertices();

  std::printf("\n### Interactive preview: %s\n\n", sceneFile.c_str());
  std::printf("%d vertices, %d triangles, %d stitches, %d pinned; contact thickness %.1f mm, weight %.0e N/m, "
              "friction %.2f, h = 1/%.0f s, %d threads.\n", nv, static_cast<int>(model.triangles.rows()),
              static_cast<int>(model.stitches.size()), static_cast<int>(model.pinned.size()),
              1e3 * base.contactThickness, base.contactWeight, base.friction, 1.0 / base.timeStep,
              tbb::info::default_concurrency());
  if (collider) {
    const std::vector<double> d = signedDistances(*collider, model.positions);
    int inside = 0, withinThickness = 0;
    for (double v : d) {
      inside += v < 0.0;
      withinThickness += v < base.contactThickness;
    }
    std::printf("Placement: signed distance to the body min %.1f mm, 1%% %.1f mm, median %.1f mm; %d vertices inside the "
                "body, %d closer than the thickness.\n", 1e3 * quantile(d, 0.0), 1e3 * quantile(d, 0.01),
                1e3 * quantile(d, 0.5), inside, withinThickness);
  }
  std::printf("Up to %d steps or %.0f s per variant; times are per step (ms); iterations and contacts per step; churn: "
              "contact DOFs joining or leaving between L-G iterations; final: vertices deeper than the thickness "
              "inside the body, and the deepest (mm).\n\n", steps, cap);

  using K = ContactSolveKind;
  const std::vector<Variant> variants = {
      {"paper: SD + PCG (cap 20), cold", [](PreviewSettings& s) { s.contactSolve = K::DualThenPcg; s.contactWarmStart = false; }},
      {"SD + PCG, warm start", [](PreviewSettings& s) { s.contactSolve = K::DualThenPcg; }},
      {"dual CG (K_cc), cold", [](PreviewSettings& s) { s.contactSolve = K::DualCgThenPcg; s.contactWarmStart = false; }},
      {"dual CG, warm, fixed h", [](PreviewSettings& s) { s.contactSolve = K::DualCgThenPcg; s.maxHalvings = 0; }},
      {"dual CG, warm, halving", [](PreviewSettings& s) { s.contactSolve = K::DualCgThenPcg; }},
      {"factor, fixed h", [](PreviewSettings& s) { s.contactSolve = K::Factor; s.maxHalvings = 0; }},
      {"factor, halving (default)", [](PreviewSettings& s) { s.contactSolve = K::Factor; }},
      // No sewn regime: contact targets re-projected every iteration, friction bounded by the inertial load.
      {"sewn, Gauss-Seidel local", [](PreviewSettings& s) { s.sewnLocalStep = LocalStepKind::GaussSeidel; }},
      {"sewn_gap 0", [](PreviewSettings& s) { s.sewnGap = 0.0; }},
      {"sewn_gap 0, fixed h", [](PreviewSettings& s) { s.sewnGap = 0.0; s.maxHalvings = 0; }},
      // Fewer L-G iterations at the paper's fixed step: fast, but the t-shirt slides off the body (BENCHMARKS).
      {"fixed h, L-G cap 5", [](PreviewSettings& s) { s.maxIterations = 5; s.maxHalvings = 0; }},
      {"fixed h, L-G cap 2", [](PreviewSettings& s) { s.maxIterations = 2; s.maxHalvings = 0; }},
      {"dual CG, warm, relax 0.1 s", [](PreviewSettings& s) { s.contactSolve = K::DualCgThenPcg; s.relaxationTime = 0.1; }},
      {"dual CG, warm, relax, tol 1e-2", [](PreviewSettings& s) { s.contactSolve = K::DualCgThenPcg; s.relaxationTime = 0.1; s.pcgTolerance = 1e-2; }},
      {"dual CG, warm, relax, tol 1e-2, hold", [](PreviewSettings& s) { s.contactSolve = K::DualCgThenPcg; s.relaxationTime = 0.1; s.pcgTolerance = 1e-2; s.holdContactTargets = true; }},
      {"same, L-G cap 10", [](PreviewSettings& s) { s.contactSolve = K::DualCgThenPcg; s.relaxationTime = 0.1; s.pcgTolerance = 1e-2; s.holdContactTargets = true; s.maxIterations = 10; }},
      {"same, L-G cap 10, Jacobi local", [](PreviewSettings& s) { s.contactSolve = K::DualCgThenPcg; s.relaxationTime = 0.1; s.pcgTolerance = 1e-2; s.holdContactTargets = true; s.maxIterations = 10; s.localStep = LocalStepKind::Jacobi; }},
      {"default, fabric shear", [](PreviewSettings& s) { s.shearModel = ShearModelKind::Fabric; }},
      {"same, L-G cap 10, fabric shear", [](PreviewSettings& s) { s.contactSolve = K::DualCgThenPcg; s.relaxationTime = 0.1; s.pcgTolerance = 1e-2; s.holdContactTargets = true; s.maxIterations = 10; s.shearModel = ShearModelKind::Fabric; }},
  };

  std::printf("| variant | vertices | steps | steps/s | sim s/s | ms/step | collision | local | global | contact solve | L-G it | SD it "
              "| PCG it | contacts | churn | final inside | deepest mm | sewn at step | steps/s once sewn | L-G it once sewn "
              "| capped once sewn | mean move mm |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const Variant& variant : variants) {
    if (!only.empty() && variant.name.find(only) == std::string::npos) continue;
    PreviewSettings s = base;
    variant.apply(s);
    PreviewSolver solver(model, s, collider);
    double wall = 0, coll = 0, local = 0, global = 0, contactSolve = 0, simulated = 0;
    long lg = 0, sd = 0, pcg = 0, contacts = 0, churn = 0;
    int done = 0, sewnAt = -1, sewnSteps = 0, sewnCapped = 0;
    double sewnWall = 0.0;
    long sewnLg = 0;
    bool diverged = false;
    const auto t0 = Clock::now();
    Eigen::VectorXd previous = solver.positions();
    const Eigen::VectorXd initial = solver.positions();
    while (done < steps && since(t0) < cap) {
      const PreviewReport r = solver.step();
      ++done;
      wall += r.wallTime;
      simulated += r.timeStep;
      coll += r.collisionTime - r.contactSolveTime;
      contactSolve += r.contactSolveTime;
      local += r.localTime;
      global += r.globalTime;
      lg += r.iterations;
      sd += r.sdIterations;
      pcg += r.pcgIterations;
      contacts += r.contacts;
      churn += r.contactChurn;
      if (r.sewn && sewnAt < 0) sewnAt = done;
      if (r.sewn && done > sewnAt) {  // the steps after the one that found the garment sewn
        ++sewnSteps;
        sewnWall += r.wallTime;
        sewnLg += r.iterations;
        sewnCapped += r.status == PreviewStatus::MaxIterations;
      }
      if (verbose) {
        const Eigen::VectorXd& x = solver.positions();
        double maxMove = 0.0;
        for (int v = 0; v < nv; ++v) maxMove = std::max(maxMove, (x.segment<3>(3 * v) - previous.segment<3>(3 * v)).norm());
        previous = x;
        int inside = 0;
        double deepestNow = 0.0;
        if (collider)
          for (double d : signedDistances(*collider, x)) {
            inside += d < -s.contactThickness;
            deepestNow = std::min(deepestNow, d);
          }
        std::printf("  step %3d: %s, %.0f ms, L-G %d (res %.1e), SD %d, PCG %d, contacts %d (ccd %d, static %d), "
                    "churn %d, contact residual %.1e, max move %.1f mm, %d inside (deepest %.1f mm)\n", done,
                    toString(r.status), 1e3 * r.wallTime, r.iterations, r.residual, r.sdIterations, r.pcgIterations,
                    r.contacts, r.ccdContacts, r.staticFriction, r.contactChurn, r.contactResidual, 1e3 * maxMove,
                    inside, 1e3 * deepestNow);
      }
      if (r.status == PreviewStatus::Diverged) {
        diverged = true;
        break;
      }
    }
    int deep = 0;
    double deepest = 0.0;
    if (collider)
      for (double v : signedDistances(*collider, solver.positions())) {
        deep += v < -s.contactThickness;
        deepest = std::min(deepest, v);
      }
    const double n = std::max(done, 1);
    double meanMove = 0.0;
    for (int v = 0; v < nv; ++v) meanMove += (solver.positions().segment<3>(3 * v) - initial.segment<3>(3 * v)).norm();
    meanMove /= nv;
    char sewnColumns[160] = "- | - | - | -";
    if (sewnSteps > 0)
      std::snprintf(sewnColumns, sizeof sewnColumns, "%d | %.1f | %.2f | %d", sewnAt, sewnSteps / sewnWall,
                    static_cast<double>(sewnLg) / sewnSteps, sewnCapped);
    std::printf("| %s | %d | %d%s | %.2f | %.3f | %.0f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.0f | %.0f | %d | %.1f | %s | %.1f |\n",
                variant.name.c_str(), nv, done, diverged ? " (diverged)" : "", done / wall, simulated / wall, 1e3 * wall / n,
                1e3 * coll / n, 1e3 * local / n, 1e3 * global / n, 1e3 * contactSolve / n, lg / n, sd / n, pcg / n,
                contacts / n, churn / n, deep, 1e3 * deepest, sewnColumns, 1e3 * meanMove);
    std::fflush(stdout);
  }
}

// The DD global solve alone, repeated: its spread over many solves in one process is what tells a change to it
// from the VM's noise (compare the minima of builds run alternately).
void solveSpread(int side, int d, int reps) {
  const drape::model::ClothModel model = grid(side);
  PdSystem sys(model, PreviewSettings{});
  const Eigen::MatrixX3d b = randomRightHandSide(sys);
  tbb::task_arena arena(2);
  arena.execute([&] {
    const auto part = partitionTriangles(model.triangles, model.numVertices(), {}, d);
    DomainDecomposedSolver dd(splitSystem(sys, part, d), sys.freeCount());
    Eigen::MatrixX3d x;
    for (int i = 0; i < 5; ++i) dd.solve(b, x);  // first touches, not timed
    std::vector<double> t;
    for (int i = 0; i < reps; ++i) {
      const auto t0 = Clock::now();
      dd.solve(b, x);
      t.push_back(since(t0));
    }
    std::sort(t.begin(), t.end());
    std::printf("| %d | %d | 2 | %d | %.2f | %.2f | %.2f |\n", side * side, d, reps, 1e3 * t.front(),
                1e3 * t[t.size() / 2], 1e3 * t[t.size() * 9 / 10]);
  });
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false;
  std::string only;
  if (argc > 1 && std::strcmp(argv[1], "interactive") == 0) {
    std::string scene = "bench/scenes/tshirt_female.json", variant, from;
    int steps = 60;
    double cap = 300.0;
    bool verbose = false;
    for (int i = 2; i < argc; ++i) {
      const std::string a = argv[i];
      if (a == "--steps" && i + 1 < argc) steps = std::atoi(argv[++i]);
      else if (a == "--cap" && i + 1 < argc) cap = std::atof(argv[++i]);
      else if (a == "--only" && i + 1 < argc) variant = argv[++i];
      else if (a == "--verbose") verbose = true;
      else if (a == "--from" && i + 1 < argc) from = argv[++i];
      else scene = a;
    }
    try {
      interactiveTable(scene, from, steps, cap, variant, verbose);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "drape_pd_bench: %s\n", e.what());
      return 1;
    }
    return 0;
  }
  if (argc > 1 && std::strcmp(argv[1], "solve") == 0) {
    const int side = argc > 2 ? std::atoi(argv[2]) : 317, d = argc > 3 ? std::atoi(argv[3]) : 16;
    const int reps = argc > 4 ? std::atoi(argv[4]) : 100;
    if (side < 2 || d < 1 || reps < 1) {
      std::fprintf(stderr, "drape_pd_bench solve: SIDE >= 2, D >= 1 and REPS >= 1 expected\n");
      return 1;
    }
    std::printf("| vertices | D | threads | solves | min ms | median ms | p90 ms |\n|---|---|---|---|---|---|---|\n");
    solveSpread(side, d, reps);
    return 0;
  }
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--quick") == 0) quick = true;
    else only = argv[i];
  }
  if (only.empty() || only == "global") globalSolveTable(quick);
  if (only.empty() || only == "local") localStepTable(quick);
  if (only.empty() || only == "iteration") perIterationTable(quick);
  if (only.empty() || only == "contact") contactTable(quick);
  return 0;
}
