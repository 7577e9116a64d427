// Preview (PD-DD) benchmarks, run by hand: `drape_pd_bench [--quick]`. Prints Markdown tables for
// docs/BENCHMARKS.md: global solve DD vs monolithic CHOLMOD (pd-dd Fig. 9), Gauss-Seidel vs Jacobi local step
// (Fig. 12/13), time per L-G iteration at 100k vertices, SD + PCG vs PCG for contact (Fig. 8).
#include <chrono>
#include <cstdio>
#include <cstring>
#include <map>
#include <memory>
#include <random>
#include <tbb/task_arena.h>

#include "drape/collision/avatar_collider.h"
#include "drape/geometry/primitives.h"
#include "drape/pd/dd_solver.h"
#include "drape/pd/domain_partition.h"
#include "drape/pd/grid_cloth.h"
#include "drape/pd/pd_system.h"
#include "drape/pd/preview_solver.h"

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

newton::ClothModel grid(int n) {
  GridClothOptions o;
  o.nx = n;
  o.ny = n;
  return makeGridCloth(o);
}

void globalSolveTable(bool quick) {
  std::printf("\n### Global solve: domain-decomposed vs monolithic CHOLMOD (pd-dd Fig. 9)\n\n");
  std::printf("Square hanging cloth, two pinned corners; DOF = 3 x vertices (the paper's count). Time per solve of\n"
              "K x = b for the three coordinates, mean of repeated solves; speed-up = monolithic / DD.\n\n");
  std::printf("| DOF | D | threads | N_C | N_B - N_C | max N_R | setup (s) | DD solve (ms) | monolithic (ms) | speed-up |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|\n");
  const std::vector<int> sizes = quick ? std::vector<int>{60} : std::vector<int>{142, 245};  // 60k, 180k DOF
  for (int n : sizes) {
    const newton::ClothModel model = grid(n);
    PdSystem sys(model, PreviewSettings{});
    std::mt19937 rng(3);
    std::normal_distribution<double> normal;
    Eigen::MatrixX3d b(sys.freeCount(), 3);
    for (int i = 0; i < b.rows(); ++i)
      for (int c = 0; c < 3; ++c) b(i, c) = normal(rng);
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

RunResult run(const newton::ClothModel& model, const PreviewSettings& s, int steps,
              std::shared_ptr<const collision::AvatarCollider> collider = nullptr, int* pcg = nullptr,
              double* collisionTime = nullptr) {
  PreviewSolver solver(model, s, collider);
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
      const newton::ClothModel model = grid(n);
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
        const RunResult r = run(grid(n), s, 2);
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
  const newton::ClothModel model = makeGridCloth(o);
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

}  // namespace

int main(int argc, char** argv) {
  bool quick = false;
  std::string only;
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
