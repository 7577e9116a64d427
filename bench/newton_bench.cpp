// Newton drape benchmark: wall time per step of a 1 m x 1 m cloth hanging from its two top corners (the scene of
// the ARCSim comparison in issue 5), for several resolutions, time steps and speed-up switches measured side by
// side in one run, so that ratios are meaningful on a loaded machine.
//   drape_newton_bench [--n 21,51,101] [--h 0.005,0.001] [--steps 10] [--warmup 2] [--configs all|on,off,...]
// Configurations: "off" (every speed-up off), "on" (every speed-up on, the defaults), "on-X" (all on but X),
// "off+X" (all off but X), X in {bending, map, parallel}.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "drape/newton/newton_solver.h"

using namespace drape::newton;

namespace {

using Clock = std::chrono::steady_clock;

// n x n vertex square of side 1 m in the x-y plane, hanging from its two top corners (cotton-like fabric).
ClothModel hangingCloth(int n) {
  ClothModel m;
  TriangleFabric f;
  f.stretchWarp = f.stretchWeft = 5000.0;
  f.shear = 250.0;
  f.bendWarp = f.bendWeft = 5e-6;
  f.density = 0.12;
  m.fabrics = {f};
  const double d = 1.0 / (n - 1);
  m.restCoords.resize(n * n, 2);
  m.positions.resize(3 * n * n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      m.restCoords.row(i * n + j) << j * d, i * d;
      m.positions.segment<3>(3 * (i * n + j)) << j * d, i * d, 0.0;
    }
  m.triangles.resize(2 * (n - 1) * (n - 1), 3);
  int t = 0;
  for (int i = 0; i + 1 < n; ++i)
    for (int j = 0; j + 1 < n; ++j) {
      int a = i * n + j, b = a + 1, c = a + n, e = c + 1;
      if (2 * j < n - 1) {
        m.triangles.row(t++) << a, b, e;
        m.triangles.row(t++) << a, e, c;
      } else {
        m.triangles.row(t++) << a, b, c;
        m.triangles.row(t++) << b, e, c;
      }
    }
  m.pinned = {n * (n - 1), n * n - 1};
  return m;
}

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  for (std::string item; std::getline(ss, item, ',');) out.push_back(item);
  return out;
}

// Applies a configuration name to the settings; returns false for an unknown name.
bool configure(const std::string& name, NewtonSettings& s) {
  auto setAll = [&s](bool on) {
    s.closedFormBending = s.cachedBlockMap = s.parallelAssembly = on;
  };
  auto flag = [&s](const std::string& x) -> bool* {
    if (x == "bending") return &s.closedFormBending;
    if (x == "map") return &s.cachedBlockMap;
    if (x == "parallel") return &s.parallelAssembly;
    return nullptr;
  };
  if (name == "on" || name == "off") {
    setAll(name == "on");
    return true;
  }
  if (name.rfind("on-", 0) == 0 || name.rfind("off+", 0) == 0) {
    bool on = name[1] == 'n';
    setAll(on);
    bool* f = flag(name.substr(on ? 3 : 4));
    if (!f) return false;
    *f = !on;
    return true;
  }
  return false;
}

struct Result {
  double msPerStep = 0.0, assemblyMs = 0.0, gradientMs = 0.0, solveMs = 0.0;
  double newtonPerStep = 0.0, cgPerStep = 0.0, hMean = 0.0, bottomY = 0.0;
  int splits = 0;
};

Result run(int n, double h, int steps, int warmup, const std::string& config) {
  NewtonSettings s;
  s.relaxation = false;
  s.hMax = h;
  configure(config, s);
  NewtonSolver solver(hangingCloth(n), s);
  for (int k = 0; k < warmup; ++k) solver.step();
  Result r;
  const auto t0 = Clock::now();
  for (int k = 0; k < steps; ++k) {
    NewtonStepReport rep = solver.step();
    r.newtonPerStep += rep.newtonIterations;
    r.cgPerStep += rep.cgIterations;
    r.hMean += rep.h;
    r.splits += rep.splits;
    r.assemblyMs += 1e3 * rep.hessianSeconds;
    r.gradientMs += 1e3 * rep.gradientSeconds;
    r.solveMs += 1e3 * rep.linearSolveSeconds;
  }
  const double total = std::chrono::duration<double>(Clock::now() - t0).count();
  r.msPerStep = 1e3 * total / steps;
  r.newtonPerStep /= steps;
  r.cgPerStep /= steps;
  r.hMean /= steps;
  r.assemblyMs /= steps;
  r.gradientMs /= steps;
  r.solveMs /= steps;
  r.bottomY = solver.positions()(3 * (n / 2) + 1);
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> sizes{21, 51, 101};
  std::vector<double> steps{0.005, 0.001};
  int numSteps = 10, warmup = 2;
  std::vector<std::string> configs{"off", "on"};
  for (int i = 1; i + 1 < argc; i += 2) {
    std::string key = argv[i], value = argv[i + 1];
    if (key == "--n") {
      sizes.clear();
      for (auto& v : split(value)) sizes.push_back(std::atoi(v.c_str()));
    } else if (key == "--h") {
      steps.clear();
      for (auto& v : split(value)) steps.push_back(std::atof(v.c_str()));
    } else if (key == "--steps") {
      numSteps = std::atoi(value.c_str());
    } else if (key == "--warmup") {
      warmup = std::atoi(value.c_str());
    } else if (key == "--configs") {
      configs = value == "all" ? std::vector<std::string>{"off", "off+bending", "off+map", "off+parallel",
                                                          "on-bending", "on-map", "on-parallel", "on"}
                               : split(value);
    } else {
      std::fprintf(stderr, "unknown option %s\n", key.c_str());
      return 2;
    }
  }
  for (const auto& c : configs) {
    NewtonSettings probe;
    if (!configure(c, probe)) {
      std::fprintf(stderr, "unknown configuration '%s'\n", c.c_str());
      return 2;
    }
  }
  std::printf("| vertices | h (ms) | config | ms/step | hessian ms | gradient ms | solve ms | Newton it | CG it | "
              "splits | speed-up vs first | bottom y (m) |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (int n : sizes)
    for (double h : steps) {
      double first = 0.0;
      for (const auto& c : configs) {
        Result r = run(n, h, numSteps, warmup, c);
        if (first == 0.0) first = r.msPerStep;
        std::printf("| %d | %.1f | %s | %.2f | %.2f | %.2f | %.2f | %.2f | %.1f | %d | %.2fx | %.6f |\n", n * n,
                    1e3 * h, c.c_str(), r.msPerStep, r.assemblyMs, r.gradientMs, r.solveMs, r.newtonPerStep,
                    r.cgPerStep, r.splits, first / r.msPerStep, r.bottomY);
        std::fflush(stdout);
      }
    }
  return 0;
}
