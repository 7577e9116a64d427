#pragma once
// One run of the speed/accuracy trade (`drape --bench`): a stage of the simulation with some settings over the
// scene's own, run to its end, with what it cost (wall time, steps) and what it gave (the final garment, its
// strain, vertices inside a collider, the energy terms it used). The reference drape, the tightest setting, is such
// a run; it can be kept in a file so that a sweep extended later is measured against the same reference.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "drape/geometry/triangle_mesh.h"
#include "drape/scene/scene.h"
#include "drape/sim/simulation.h"

namespace drape::trade {

using SettingList = std::vector<std::pair<std::string, std::string>>;

struct TradeConfig {
  std::string label;     // "reference", "solver.newton.h_max=2e-3", "level Fast"
  std::string level;     // the speed/accuracy level this run measures (assets/trade/level_candidates.json), or empty
  std::string stage;     // "preview", "drape" or "full" (solver.stage)
  SettingList settings;  // applied over the scene's settings and --set, before the stage
};

struct TradeOutcome {
  TradeConfig config;
  std::string status;  // Simulation::endReason ("AtRest", "MaxSimTime", "MaxSteps"), or "Diverged"
  double wallSeconds = 0.0;
  double simTime = 0.0;  // s simulated
  int steps = 0;
  TriangleMesh garment;  // the final garment: positions (metres) and triangles
  double maxStrain = 0.0;
  int insideVertices = 0;          // deeper inside a collider than the contact thickness
  std::vector<std::string> terms;  // the energy (drape) and constraint (preview) terms of every stage it ran
  PhaseProfile profile;            // where its steps' wall time went
  bool atRest() const { return status == "AtRest"; }
};

// The reference: the Newton drape with an 8x smaller step limit and 10-100x tighter tolerances than the defaults
// (h_max 2.5e-4 s, tau_n 1e-5, tau_cg 1e-4) on the scene's own mesh (drape --bench puts it on the finest mesh of its
// runs, so that it resolves what they resolve).
TradeConfig referenceConfig();

// Runs config on the scene `base` to its end. Throws InputError when the settings are refused at load.
TradeOutcome runTrade(const SceneRequest& base, const TradeConfig& config);

// The identity of a reference: the scene request and the reference's settings, so that a kept reference is never
// compared with another scene or with other settings.
std::string referenceKey(const SceneRequest& base, const TradeConfig& reference);

// Writes a reference run atomically as JSON (its key, status, costs, vertices and triangles).
void writeReference(const std::filesystem::path& file, const TradeOutcome& reference, const std::string& key);
// Reads a reference written by writeReference. Throws InputError naming the file when it is not one, or when it was
// made for another key (another scene, avatar, fabric, --set or reference settings).
TradeOutcome readReference(const std::filesystem::path& file, const std::string& key);

struct Distances {
  // From every reference vertex to the run's surface: comparable across meshes (a coarser mesh is judged by where
  // its surface is, not by where its vertices are).
  double meanMm = 0.0;
  double p95Mm = 0.0;
  double maxMm = 0.0;
  // Vertex to vertex, when the run has the reference's mesh (else negative): also counts a vertex sliding along the
  // surface, which the surface distance ignores; never below meanMm.
  double vertexMeanMm = -1.0;
};

// The distance of a run's final garment to the reference's.
Distances distanceToReference(const TriangleMesh& run, const TriangleMesh& reference);

}  // namespace drape::trade
