#include "drape/sim/extremes_grid.h"

#include <chrono>
#include <cstdio>

#include "drape/collision/avatar_collider.h"
#include "drape/core/input_error.h"
#include "drape/geometry/strain.h"
#include "drape/scene/settings.h"
#include "drape/sim/simulation.h"
#include "drape/sim/snapshot_builder.h"

namespace drape {
namespace {

std::string number(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

double rangeEnd(const std::string& key, bool max) {
  const SettingSpec* spec = Settings::find(key);
  return max ? spec->max : spec->min;
}

// The keys set to the same end of their ranges.
ExtremeCell atEnd(const std::string& name, const std::vector<std::string>& keys, bool max) {
  ExtremeCell cell{name + (max ? " max" : " min"), {}};
  for (const auto& k : keys) cell.settings.emplace_back(k, number(rangeEnd(k, max)));
  return cell;
}

const std::vector<std::string> kStretch = {"fabric.stretch_warp", "fabric.stretch_weft"};
const std::vector<std::string> kBending = {"fabric.bend_warp", "fabric.bend_weft"};
const std::vector<std::string> kTimeStep = {"solver.newton.h_max", "solver.preview.time_step"};
// The finest mesh the grid runs: the range's own minimum (0.1 mm) is refused for a garment (its triangle limit).
constexpr double kFinestEdge = 0.005;

}  // namespace

std::vector<ExtremeCell> extremeCells() {
  std::vector<ExtremeCell> cells;
  const std::vector<std::pair<std::string, std::vector<std::string>>> axes = {
      {"stretch", kStretch},
      {"shear", {"fabric.shear"}},
      {"bending", kBending},
      {"density", {"fabric.density"}},
      {"friction", {"fabric.friction"}},
      {"thickness", {"fabric.thickness"}},
      {"gravity", {"sim.gravity"}},
      {"damping", {"fabric.damping"}},
      {"mesh edge", {"mesh.target_edge_length"}},
      {"time step", kTimeStep},
      {"Newton tolerance", {"solver.newton.tolerance"}},
      {"CG tolerance", {"solver.cg.tolerance"}}};
  for (const auto& [name, keys] : axes) {
    for (bool max : {false, true}) {
      ExtremeCell cell = atEnd(name, keys, max);
      if (name == "mesh edge" && !max) cell.settings = {{"mesh.target_edge_length", number(kFinestEdge)}};
      cells.push_back(std::move(cell));
    }
  }
  ExtremeCell softest{"softest + finest + largest step + strongest gravity", {}};
  for (const auto& k : kStretch) softest.settings.emplace_back(k, number(rangeEnd(k, false)));
  softest.settings.emplace_back("fabric.shear", "0");
  for (const auto& k : kBending) softest.settings.emplace_back(k, "0");
  softest.settings.emplace_back("mesh.target_edge_length", number(kFinestEdge));
  for (const auto& k : kTimeStep) softest.settings.emplace_back(k, number(rangeEnd(k, true)));
  softest.settings.emplace_back("sim.gravity", number(rangeEnd("sim.gravity", false)));
  cells.push_back(std::move(softest));
  ExtremeCell stiffest{"stiffest + coarsest + largest step", {}};
  for (const auto& k : kStretch) stiffest.settings.emplace_back(k, number(rangeEnd(k, true)));
  stiffest.settings.emplace_back("fabric.shear", number(rangeEnd("fabric.shear", true)));
  for (const auto& k : kBending) stiffest.settings.emplace_back(k, number(rangeEnd(k, true)));
  stiffest.settings.emplace_back("mesh.target_edge_length", number(rangeEnd("mesh.target_edge_length", true)));
  for (const auto& k : kTimeStep) stiffest.settings.emplace_back(k, number(rangeEnd(k, true)));
  cells.push_back(std::move(stiffest));
  cells.push_back({"no friction + strongest gravity",
                   {{"fabric.friction", "0"}, {"sim.gravity", number(rangeEnd("sim.gravity", false))}}});
  return cells;
}

ExtremeOutcome runExtremeCell(const SceneRequest& base, const ExtremeCell& cell, const std::string& stage,
                              double maxSimTime, int maxSteps) {
  SceneRequest request = base;
  request.overrides.insert(request.overrides.end(), cell.settings.begin(), cell.settings.end());
  request.overrides.emplace_back("solver.stage", stage);
  request.overrides.emplace_back("solver.max_sim_time", number(maxSimTime));
  request.overrides.emplace_back("solver.max_steps", std::to_string(maxSteps));
  ExtremeOutcome out;
  out.cell = cell.name;
  out.stage = stage;
  const auto start = std::chrono::steady_clock::now();
  Scene scene;
  try {
    scene = loadScene(request);
  } catch (const InputError& e) {
    out.status = "Refused";
    out.refusal = e.what();
    return out;
  }
  Simulation sim(std::move(scene));
  StepReport last;
  while (!sim.finished()) {
    last = sim.step();
    if (last.status == StepStatus::Diverged) break;
  }
  out.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out.status = last.status == StepStatus::Diverged ? "Diverged" : sim.endReason();
  out.divergedReason = sim.divergedReason();
  out.simTime = sim.time();
  out.steps = sim.steps();
  const Eigen::MatrixX3d x = sim.positions();
  out.vertices = static_cast<int>(x.rows());
  out.finite = x.allFinite();
  const Eigen::VectorXd stretch = triangleStretch(sim.garment().rest, x, sim.garment().triangles);
  out.maxStrain = stretch.size() ? stretch.maxCoeff() : 0.0;
  if (sim.collider() && out.finite) {
    const double thickness = sim.contactThickness();
    for (int v = 0; v < x.rows(); ++v) {
      const double d = sim.collider()->signedDistance(x.row(v).transpose());
      if (d < 0.0) out.deepestMm = std::max(out.deepestMm, -1e3 * d);
      if (d < -thickness) ++out.insideVertices;
    }
  }
  char buffer[160];
  if (!out.finite) {
    out.failure = "positions not finite";
  } else if (out.status == "Diverged" && out.divergedReason.empty()) {
    std::snprintf(buffer, sizeof buffer, "diverged at t = %.4g s: no step converged", out.simTime);
    out.failure = buffer;
  } else if (out.insideVertices > 0) {
    std::snprintf(buffer, sizeof buffer, "%d vertices inside a collider beyond the contact thickness (deepest %.1f mm)",
                  out.insideVertices, out.deepestMm);
    out.failure = buffer;
  }
  return out;
}

}  // namespace drape
