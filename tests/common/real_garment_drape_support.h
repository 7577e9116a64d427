#pragma once
// What the real garments' drapes share (tests/unit/newton/real_garment_drape_test.cpp and the slow ones,
// tests/slow/real_garment_drape_test.cpp): a full Newton drape of a scene or of a pattern on an avatar, measured
// against an independent AvatarCollider on the loaded mesh, and the checks every garment hanging from the shoulders
// passes.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <utility>

#include "drape/avatar/body_measurements.h"
#include "drape/avatar/mannequin.h"
#include "drape/collision/avatar_collider.h"
#include "drape/collision/garment_facing.h"
#include "drape/scene/scene.h"
#include "drape/sim/simulation.h"
#include "shared_data.h"

namespace drape {

struct DrapeOutcome {
  int initiallyInside = 0;      // garment vertices inside the body as placed
  double maxPenetration = 0.0;  // metres, largest depth of a vertex inside the body after the drape (0: none)
  double contactThickness = 0.0;
  double maxStitchGap = 0.0;     // metres
  double topY = 0.0;             // metres, highest garment vertex
  double centroidY = 0.0;        // metres, mean vertex height
  double nearFraction = 0.0;     // vertices within 5 cm of the body surface (outside or on it)
  double onSkinFraction = 0.0;   // vertices within 1 mm of the body surface or inside it
  double outwardFraction = 0.0;  // faces within 1 cm of the body (garmentFacing) whose normal points away from it
  bool diverged = false;
  bool atRest = false;
  double simTime = 0.0;   // s
  double wallTime = 0.0;  // s
};

// Drapes the scene (a scene file, or a pattern with request.avatarFile) with the given mesh edge length (m) and
// simulated-time limit (s).
inline DrapeOutcome drape(SceneRequest request, double edge, double maxSimTime) {
  request.overrides.push_back({"mesh.target_edge_length", std::to_string(edge)});
  request.overrides.push_back({"solver.max_sim_time", std::to_string(maxSimTime)});
  Scene scene = loadScene(request);
  const std::filesystem::path pattern = scene.patternFile, avatar = scene.avatarFile;
  const collision::AvatarCollider body(scene.avatar);  // independent of the simulation's own collider
  Simulation sim(std::move(scene));
  DrapeOutcome out;
  out.contactThickness = sim.contactThickness();
  const Eigen::MatrixX3d placed = sim.positions();
  for (int v = 0; v < placed.rows(); ++v) out.initiallyInside += body.signedDistance(placed.row(v).transpose()) < 0.0;

  const auto start = std::chrono::steady_clock::now();
  while (!sim.finished()) {
    const StepReport r = sim.step();
    if (r.status == StepStatus::Diverged) {
      out.diverged = true;
      break;
    }
    out.atRest = r.atRest;
  }
  out.wallTime = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out.simTime = sim.time();

  const Eigen::MatrixX3d x = sim.positions();
  int near = 0, onSkin = 0;
  for (int v = 0; v < x.rows(); ++v) {
    const double d = body.signedDistance(x.row(v).transpose());
    out.maxPenetration = std::max(out.maxPenetration, -d);
    near += d < 0.05;
    onSkin += d < 1e-3;
  }
  out.nearFraction = static_cast<double>(near) / static_cast<double>(x.rows());
  out.onSkinFraction = static_cast<double>(onSkin) / static_cast<double>(x.rows());
  out.outwardFraction = collision::garmentFacing(x, sim.garment().triangles, body, 0.01).outwardFraction();
  for (auto [a, b] : sim.garment().stitchPairs)
    out.maxStitchGap = std::max(out.maxStitchGap, (x.row(a) - x.row(b)).norm());
  out.topY = x.col(1).maxCoeff();
  out.centroidY = x.col(1).mean();
  std::printf(
      "[real drape] %s on %s: %d vertices, %d inside as placed; after %.3f s simulated (%s, %.1f s wall): "
      "max penetration %.2f mm (thickness %.1f mm), max stitch gap %.2f mm, top y %.3f m, centroid y %.3f m, "
      "%.0f%% within 5 cm of the body, %.2f%% within 1 mm, %.1f%% of the faces on it outward\n",
      pattern.filename().string().c_str(), avatar.filename().string().c_str(), static_cast<int>(x.rows()),
      out.initiallyInside, out.simTime, out.diverged ? "diverged" : (out.atRest ? "at rest" : "time limit"),
      out.wallTime, 1e3 * out.maxPenetration, 1e3 * out.contactThickness, 1e3 * out.maxStitchGap, out.topY,
      out.centroidY, 100.0 * out.nearFraction, 100.0 * out.onSkinFraction, 100.0 * out.outwardFraction);
  return out;
}

// Drapes pattern on avatar (metres).
inline DrapeOutcome drape(const std::filesystem::path& pattern, const std::filesystem::path& avatar, double edge,
                          double maxSimTime) {
  SceneRequest request;
  request.input = pattern;
  request.avatarFile = avatar.string();
  return drape(request, edge, maxSimTime);
}

// The checks shared by every garment: levels from the body's measurement file (metres above the floor).
inline void expectHangsOnTorso(const DrapeOutcome& o, const MannequinLevels& levels) {
  EXPECT_FALSE(o.diverged);
  EXPECT_LE(o.maxPenetration, o.contactThickness) << "a garment vertex ended inside the body";
  EXPECT_LT(o.maxStitchGap, 0.01) << "a seam did not close";
  EXPECT_NEAR(o.topY, levels.neckBase, 0.06) << "the garment does not hang from the shoulders";
  EXPECT_LT(o.centroidY, levels.neckBase);
  EXPECT_GT(o.centroidY, levels.crotch);
  EXPECT_GT(o.nearFraction, 0.6);
}

inline MannequinLevels femaleLevels() {
  return mannequinLevels(loadBodyMeasurements(test::assetsDir() / "avatars/female.yaml"));
}

}  // namespace drape
