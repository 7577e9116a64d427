#pragma once
// The quality verdict on a simulated garment, as a batch pipeline gives one for every drape (GarmentCode's
// simulation config counts body and self collisions and requires a static end state): a list of checks, each with
// its measured value, its threshold (settings quality.*), whether it passed and where it is worst (a garment vertex
// or triangle), so that a user can find the spot. The CLI prints a warning per failed check and exits 4; the GUI
// shows the checks in its Statistics dock.
#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

#include "drape/garment/garment.h"
#include "drape/scene/quality_settings.h"

namespace drape {

class Simulation;
namespace collision {
class AvatarCollider;
}


struct QualityCheck {
  // max_strain, inside_fraction, penetration_depth, near_skin_fraction, outward_faces, self_intersections, seam_gap,
  // at_rest
  std::string name;
  double value = 0.0;      // measured; at_rest: 1 at rest, 0 not
  double threshold = 0.0;  // the largest value that passes; at_rest, outward_faces: the smallest
  bool passed = true;
  int vertex = -1;         // the garment vertex where it is worst (penetration, near skin, seam gap), -1: none
  int triangle = -1;       // the garment triangle where it is worst (strain, the first crossing pair), -1: none
  int otherTriangle = -1;  // self_intersections: the triangle the first one crosses
  std::string where;       // the place in words: "triangle 12 of panel 'front' at (x, y, z) m"; empty: nowhere
  std::string message;     // one line: what was measured against what, and where
};

struct QualityReport {
  bool passed = true;  // every check passed
  std::vector<QualityCheck> checks;
  // The check of that name, nullptr when the report has none (no collider: no inside, depth or near-skin check).
  const QualityCheck* find(std::string_view name) const;
};

// The balance of forces at the run's end (the last step's StepReport): the RMS and the largest unbalanced force per
// vertex as a fraction of its weight, and the last step's largest vertex displacement, m. at_rest reports it;
// forceRms < 0: not measured (no step ran).
struct RestMeasures {
  double forceRms = -1.0;
  double forceMax = 0.0;
  double displacementMax = 0.0;
};

// Checks a simulated garment: `positions` (|V| x 3, metres) of `garment` (rest shape, triangles, stitch pairs),
// against `collider` (the avatar and generated colliders the simulation's contact uses; nullptr: none, and the
// collider checks are left out), with the contact thickness (metres; the depth threshold when
// settings.maxPenetrationDepth is 0) and the run's end status ("AtRest", "MaxSimTime", "MaxSteps", "Diverged",
// "Cancelled") and its balance of forces there. Thread-safe; the signed distances and the triangle pairs are computed
// in parallel.
QualityReport checkDrapeQuality(const Garment& garment, const Eigen::MatrixX3d& positions,
                                const collision::AvatarCollider* collider, double contactThickness,
                                const std::string& endStatus, const QualitySettings& settings,
                                const RestMeasures& rest = {});
// The same for a simulation's current state, with its scene's quality settings, collider and contact thickness.
QualityReport checkDrapeQuality(const Simulation& simulation, const std::string& endStatus);

}  // namespace drape
