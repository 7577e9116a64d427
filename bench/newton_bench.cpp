// Newton drape benchmark (docs/BENCHMARKS.md, "Newton drape"). Speed-up switches are measured side by side in one
// process so that ratios stay meaningful on a loaded machine.
//
// Cloth mode (default): wall time per step of a 1 m x 1 m cloth hanging from its two top corners (the scene of
// the ARCSim comparison in issue 5), for several resolutions and time steps:
//   drape_newton_bench [--n 21,51,101] [--h 0.005,0.001] [--steps 10] [--warmup 2] [--configs all|table7|on,off,...]
// Scene mode: a scene file through drape::loadScene + drape::Simulation (the whole engine path of --simulate):
//   drape_newton_bench --scene FILE [--sim-time 0.2] [--motion-start S] [--set KEY=VALUE]... [--configs ...]
//                      [--repeat R] [--memory]
// --motion-start moves the start (and end, keeping the rate) of every moving pin to S seconds, so that a short
// window shows the twist; --repeat R runs the whole list of configurations R times, interleaved, and keeps the
// fastest run of each (the loaded-machine noise only ever adds time); --memory prints the peak resident memory (VmHWM)
// per 100k DOFs, run it alone.
// --reuse-steps N: the Hessian reuse limit of feature "reuse" (default 4); --coarse-aggregate N: the vertices per
// aggregate of feature "coarse" (two-level PCG, default 16). (solver.cg.forcing trades accuracy, so
// it is no feature here: measure it with --set.)
// Configurations: a base "on" (every speed-up on) or "off" (all off) followed by "+X" / "-X" modifiers, e.g.
// "off+bending+map", "on-reorder". X in {bending, map, parallel, fold, reorder, fused, warm, mixed, reuse, coarse,
// coupled, guess, majorizer, batch, lag}. "all" = off, on and every on-X; "table7" = the cumulative sequence off,
// off+bending, ..., on (newton-drape-pizana Table 7; the features after "coarse" are not in the paper either).
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "drape/newton/newton_solver.h"
#include "drape/scene/scene.h"
#include "drape/sim/simulation.h"

using namespace drape::newton;

namespace {

using Clock = std::chrono::steady_clock;

// Steps an elastic Hessian may be reused with feature "reuse" on (solver.newton.hessian_reuse_steps; --reuse-steps).
int g_reuseSteps = 4;
// Vertices per coarse aggregate with feature "coarse" on (solver.cg.coarse_aggregate; --coarse-aggregate).
int g_coarseAggregate = 16;

// The speed-up switches: name, setting key (scene mode; nullptr for an implementation switch, set on
// Scene::implementation), NewtonSettings setter (cloth mode); a switch that is not boolean gives its scene value
// on / off.
struct Feature {
  const char* name;
  const char* key;
  void (*set)(NewtonSettings&, bool on);
  std::string (*sceneValue)(bool on) = [](bool on) { return std::string(on ? "true" : "false"); };
  void (*setImplementation)(drape::Implementation&, bool on) = nullptr;
};
// An implementation switch: the same field in NewtonSettings (cloth mode) and in drape::Implementation (scene mode).
#define DRAPE_IMPLEMENTATION_SWITCH(name, newtonField, implementationField)                         \
  Feature {                                                                                         \
    name, nullptr, [](NewtonSettings& s, bool on) { s.newtonField = on; }, nullptr,                 \
        [](drape::Implementation& i, bool on) { i.implementationField = on; }                       \
  }
const std::vector<Feature>& features() {
  static const std::vector<Feature> list = {
      DRAPE_IMPLEMENTATION_SWITCH("bending", closedFormBending, closedFormBending),
      DRAPE_IMPLEMENTATION_SWITCH("map", cachedBlockMap, blockMap),
      DRAPE_IMPLEMENTATION_SWITCH("parallel", parallelAssembly, parallelAssembly),
      DRAPE_IMPLEMENTATION_SWITCH("fold", foldDissipation, foldDissipation),
      DRAPE_IMPLEMENTATION_SWITCH("reorder", reorderDofs, reorderDofs),
      DRAPE_IMPLEMENTATION_SWITCH("fused", linear.fusedKernels, fusedKernels),
      {"warm", "solver.cg.warm_start", [](NewtonSettings& s, bool on) { s.linear.warmStart = on; }},
      {"mixed", "solver.cg.mixed_precision", [](NewtonSettings& s, bool on) { s.linear.mixedPrecision = on; }},
      {"reuse", "solver.newton.hessian_reuse_steps",
       [](NewtonSettings& s, bool on) { s.hessianReuseSteps = on ? g_reuseSteps : 0; },
       [](bool on) { return std::to_string(on ? g_reuseSteps : 0); }},
      {"coarse", "solver.cg.coarse_aggregate",
       [](NewtonSettings& s, bool on) { s.coarseAggregate = on ? g_coarseAggregate : 0; },
       [](bool on) { return std::to_string(on ? g_coarseAggregate : 0); }},
      {"coupled", "solver.cg.coupled_groups", [](NewtonSettings& s, bool on) { s.coupledThreshold = on ? 0.6 : 0.0; },
       [](bool on) { return std::string(on ? "0.6" : "0"); }},
      {"guess", "solver.newton.relaxation_guess", [](NewtonSettings& s, bool on) { s.relaxationGuess = on; }},
      // Friction is a contact term: the cloth mode (no contact) has none to switch.
      {"majorizer", "contact.friction_majorizer", [](NewtonSettings&, bool) {}},
      DRAPE_IMPLEMENTATION_SWITCH("batch", batchedGradients, batchedGradients),
      {"lag", "solver.cg.coarse_lagged", [](NewtonSettings& s, bool on) { s.coarseLagged = on; }},
  };
  return list;
}

std::vector<std::string> split(const std::string& s, char sep = ',') {
  std::vector<std::string> out;
  std::stringstream ss(s);
  for (std::string item; std::getline(ss, item, sep);) out.push_back(item);
  return out;
}

// Configuration name -> on/off per feature (order of features()); false for an unknown name.
bool parseConfig(const std::string& name, std::vector<bool>& on) {
  size_t pos = name.find_first_of("+-");
  const std::string base = name.substr(0, pos);
  if (base != "on" && base != "off") return false;
  on.assign(features().size(), base == "on");
  while (pos != std::string::npos) {
    const bool value = name[pos] == '+';
    size_t next = name.find_first_of("+-", pos + 1);
    const std::string x = name.substr(pos + 1, next == std::string::npos ? std::string::npos : next - pos - 1);
    size_t k = 0;
    while (k < features().size() && x != features()[k].name) ++k;
    if (k == features().size()) return false;
    on[k] = value;
    pos = next;
  }
  return true;
}

std::vector<std::string> expandConfigs(const std::string& value) {
  std::vector<std::string> out;
  if (value == "all") {
    out = {"off", "on"};
    for (const auto& f : features()) out.push_back(std::string("on-") + f.name);
  } else if (value == "table7") {
    std::string name = "off";
    out.push_back(name);
    for (const auto& f : features()) out.push_back(name += std::string("+") + f.name);
    out.back() = "on";
  } else {
    out = split(value);
  }
  return out;
}

double cpuSeconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_utime.tv_sec + u.ru_stime.tv_sec + 1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

// Peak resident set size of this process so far (VmHWM), megabytes.
double peakResidentMb() {
  std::ifstream in("/proc/self/status");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("VmHWM:", 0) == 0) return std::atof(line.c_str() + 6) / 1024.0;
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024.0;
}

struct Result {
  int steps = 0;
  double simTime = 0.0, wall = 0.0, cpu = 0.0;
  double assemblyMs = 0.0, gradientMs = 0.0, solveMs = 0.0;  // per step
  double newtonPerStep = 0.0, cgPerStep = 0.0;
  int splits = 0;
  Eigen::VectorXd x;  // final positions, flat
  double probe = 0.0;  // one coordinate for the table
};

void finish(Result& r) {
  const double n = std::max(1, r.steps);
  r.assemblyMs *= 1e3 / n;
  r.gradientMs *= 1e3 / n;
  r.solveMs *= 1e3 / n;
  r.newtonPerStep /= n;
  r.cgPerStep /= n;
}

// ---------------------------------------------------------------------------------------------------------------
// Cloth mode.

// n x n vertex square of side 1 m in the x-y plane, hanging from its two top corners (cotton-like fabric).
drape::model::ClothModel hangingCloth(int n) {
  drape::model::ClothModel m;
  drape::model::TriangleFabric f;
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

Result runCloth(int n, double h, int steps, int warmup, const std::vector<bool>& on) {
  NewtonSettings s;
  s.relaxation = false;
  s.hMax = h;
  for (size_t k = 0; k < on.size(); ++k) features()[k].set(s, on[k]);
  NewtonSolver solver(hangingCloth(n), s);
  for (int k = 0; k < warmup; ++k) solver.step();
  Result r;
  const auto t0 = Clock::now();
  const double c0 = cpuSeconds();
  for (int k = 0; k < steps; ++k) {
    NewtonStepReport rep = solver.step();
    r.newtonPerStep += rep.newtonIterations;
    r.cgPerStep += rep.cgIterations;
    r.splits += rep.splits;
    r.assemblyMs += rep.hessianSeconds;
    r.gradientMs += rep.gradientSeconds;
    r.solveMs += rep.linearSolveSeconds;
  }
  r.wall = std::chrono::duration<double>(Clock::now() - t0).count();
  r.cpu = cpuSeconds() - c0;
  r.steps = steps;
  finish(r);
  r.x = solver.positions();
  r.probe = solver.positions()(3 * (n / 2) + 1);
  return r;
}

// ---------------------------------------------------------------------------------------------------------------
// Scene mode.

struct SceneOptions {
  std::string file;
  double simTime = 0.2;
  double motionStart = -1.0;  // < 0: as in the scene
  std::vector<std::pair<std::string, std::string>> overrides;
};

drape::Scene loadBenchScene(const SceneOptions& o, const std::vector<bool>& on) {
  drape::SceneRequest request;
  request.input = o.file;
  request.overrides = o.overrides;
  for (size_t k = 0; k < on.size(); ++k)
    if (features()[k].key) request.overrides.emplace_back(features()[k].key, features()[k].sceneValue(on[k]));
  request.overrides.emplace_back("solver.max_sim_time", std::to_string(o.simTime));
  drape::Scene scene = drape::loadScene(request);
  for (size_t k = 0; k < on.size(); ++k)
    if (features()[k].setImplementation) features()[k].setImplementation(scene.implementation, on[k]);
  if (o.motionStart >= 0.0)
    for (auto& pin : scene.pins)
      if (pin.moving) {
        pin.motion.end += o.motionStart - pin.motion.start;
        pin.motion.start = o.motionStart;
      }
  return scene;
}

Result runScene(const SceneOptions& o, const std::vector<bool>& on) {
  drape::Simulation sim(loadBenchScene(o, on));
  Result r;
  const auto t0 = Clock::now();
  const double c0 = cpuSeconds();
  while (!sim.finished()) {
    const drape::StepReport rep = sim.step();
    ++r.steps;
    r.newtonPerStep += rep.iterations;
    r.cgPerStep += rep.cgIterations;
    r.splits += rep.splits;
    r.assemblyMs += rep.assemblyTime;
    r.gradientMs += rep.gradientTime;
    r.solveMs += rep.linearSolveTime;
    if (rep.status == drape::StepStatus::Diverged) break;
  }
  r.wall = std::chrono::duration<double>(Clock::now() - t0).count();
  r.cpu = cpuSeconds() - c0;
  r.simTime = sim.time();
  finish(r);
  const Eigen::MatrixX3d p = sim.positions();
  r.x.resize(3 * p.rows());
  for (Eigen::Index i = 0; i < p.rows(); ++i) r.x.segment<3>(3 * i) = p.row(i).transpose();
  r.probe = p.col(1).minCoeff();
  return r;
}

void printHeader(bool scene) {
  std::printf("| %s | config | steps | wall s | cpu s | ms/step | assembly ms | gradient ms | solve ms | Newton it | "
              "CG it | splits | speed-up vs first | vs previous | %s | max dx vs first (m) |\n",
              scene ? "scene" : "vertices | h (ms)", scene ? "lowest y (m)" : "bottom y (m)");
  std::printf("|---|%s---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n", scene ? "" : "---|");
}

// previousMs: ms per step of the row above (0 for the first row).
void printRow(const std::string& what, const std::string& config, const Result& r, const Result& first,
              double previousMs) {
  const double msPerStep = 1e3 * r.wall / std::max(1, r.steps);
  const double firstMs = 1e3 * first.wall / std::max(1, first.steps);
  double dx = 0.0;
  if (r.x.size() == first.x.size())
    for (Eigen::Index i = 0; i < r.x.size(); i += 3) dx = std::max(dx, (r.x.segment<3>(i) - first.x.segment<3>(i)).norm());
  std::printf("| %s | %s | %d | %.1f | %.1f | %.2f | %.2f | %.2f | %.2f | %.2f | %.1f | %d | %.2fx | %.2fx | %.6f | "
              "%.1e |\n",
              what.c_str(), config.c_str(), r.steps, r.wall, r.cpu, msPerStep, r.assemblyMs, r.gradientMs, r.solveMs,
              r.newtonPerStep, r.cgPerStep, r.splits, firstMs / msPerStep,
              previousMs > 0.0 ? previousMs / msPerStep : 1.0,
              r.probe, dx);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) try {
  std::vector<int> sizes{21, 51, 101};
  std::vector<double> steps{0.005, 0.001};
  int numSteps = 10, warmup = 2;
  std::vector<std::string> configs{"off", "on"};
  SceneOptions scene;
  bool memory = false;
  int repeat = 1;
  for (int i = 1; i < argc; ++i) {
    std::string key = argv[i];
    if (key == "--memory") {
      memory = true;
      continue;
    }
    if (i + 1 >= argc) {
      std::fprintf(stderr, "option %s needs a value\n", key.c_str());
      return 2;
    }
    std::string value = argv[++i];
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
      configs = expandConfigs(value);
    } else if (key == "--reuse-steps") {
      g_reuseSteps = std::max(1, std::atoi(value.c_str()));
    } else if (key == "--coarse-aggregate") {
      g_coarseAggregate = std::max(2, std::atoi(value.c_str()));
    } else if (key == "--repeat") {
      repeat = std::max(1, std::atoi(value.c_str()));
    } else if (key == "--scene") {
      scene.file = value;
    } else if (key == "--sim-time") {
      scene.simTime = std::atof(value.c_str());
    } else if (key == "--motion-start") {
      scene.motionStart = std::atof(value.c_str());
    } else if (key == "--set") {
      const size_t eq = value.find('=');
      if (eq == std::string::npos) {
        std::fprintf(stderr, "--set needs KEY=VALUE\n");
        return 2;
      }
      scene.overrides.emplace_back(value.substr(0, eq), value.substr(eq + 1));
    } else {
      std::fprintf(stderr, "unknown option %s\n", key.c_str());
      return 2;
    }
  }
  std::vector<std::vector<bool>> switches;
  for (const auto& c : configs) {
    switches.emplace_back();
    if (!parseConfig(c, switches.back())) {
      std::fprintf(stderr, "unknown configuration '%s'\n", c.c_str());
      return 2;
    }
  }

  if (!scene.file.empty() && memory) {
    // Peak memory: the process before the simulation (engine + scene + avatar loaded once, then released) and
    // after a few steps of the first configuration.
    const double before = peakResidentMb();
    drape::Simulation sim(loadBenchScene(scene, switches.front()));
    const double built = peakResidentMb();
    const int dofs = 3 * sim.garment().vertexCount();
    int n = 0;
    while (!sim.finished() && n < numSteps) {
      sim.step();
      ++n;
    }
    const double after = peakResidentMb();
    std::printf("| scene | config | DOFs | steps | VmHWM before (MB) | after build (MB) | after steps (MB) | "
                "simulation MB | MB per 100k DOFs |\n|---|---|---|---|---|---|---|---|---|\n");
    std::printf("| %s | %s | %d | %d | %.1f | %.1f | %.1f | %.1f | %.1f |\n", scene.file.c_str(), configs.front().c_str(),
                dofs, n, before, built, after, after - before, (after - before) / (dofs / 1e5));
    return 0;
  }

  if (!scene.file.empty()) {
    std::vector<Result> best(configs.size());
    for (int k = 0; k < repeat; ++k)
      for (size_t c = 0; c < configs.size(); ++c) {
        Result r = runScene(scene, switches[c]);
        if (k == 0 || r.wall < best[c].wall) best[c] = r;
        std::fprintf(stderr, "run %d %s: %.1f s\n", k, configs[c].c_str(), r.wall);
      }
    printHeader(true);
    Result first;
    double previous = 0.0;
    for (size_t c = 0; c < configs.size(); ++c) {
      const Result& r = best[c];
      if (c == 0) first = r;
      printRow(scene.file, configs[c], r, first, previous);
      previous = 1e3 * r.wall / std::max(1, r.steps);
    }
    return 0;
  }

  printHeader(false);
  for (int n : sizes)
    for (double h : steps) {
      std::vector<Result> best(configs.size());
      for (int k = 0; k < repeat; ++k)
        for (size_t c = 0; c < configs.size(); ++c) {
          Result r = runCloth(n, h, numSteps, warmup, switches[c]);
          if (k == 0 || r.wall < best[c].wall) best[c] = r;
        }
      Result first;
      double previous = 0.0;
      for (size_t c = 0; c < configs.size(); ++c) {
        const Result& r = best[c];
        if (c == 0) first = r;
        char what[64];
        std::snprintf(what, sizeof what, "%d | %.1f", n * n, 1e3 * h);
        printRow(what, configs[c], r, first, previous);
        previous = 1e3 * r.wall / std::max(1, r.steps);
      }
    }
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "drape_newton_bench: %s\n", e.what());
  return 1;
}
