#pragma once
// What the PD preview's contact target tests share (tests/unit/pd/pd_contact_target_test.cpp and the friction on the
// landing tablecloth, tests/slow/pd_contact_friction_test.cpp): the first version's settings (re-projected targets,
// friction bounded by the collision-free load) and a cloth settled on a collider for a number of steps.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <memory>

#include "drape/collision/avatar_collider.h"
#include "drape/pd/avatar_collision.h"
#include "drape/pd/preview_solver.h"

namespace drape::pd {

inline Eigen::MatrixX3d rowsOf(const Eigen::VectorXd& flat) {
  Eigen::MatrixX3d m(flat.size() / 3, 3);
  for (int v = 0; v < m.rows(); ++v) m.row(v) = flat.segment<3>(3 * v).transpose();
  return m;
}

inline PreviewSettings firstVersion(PreviewSettings s) {
  s.contactTargets = ContactTargetKind::Reproject;
  s.frictionLoad = FrictionLoadKind::CollisionFree;
  return s;
}

struct SettleResult {
  double lateIterations = 0.0;  // mean L-G iterations per step over the second half of the steps
  int lateCapped = 0;           // steps of the second half that hit the iteration cap
  double deepest = 0.0;         // most negative signed distance to the collider at the end, metres
  Eigen::MatrixX3d x;           // final positions
};

inline SettleResult settle(const drape::model::ClothModel& model, const PreviewSettings& s,
                           const std::shared_ptr<const collision::AvatarCollider>& collider, int steps) {
  PreviewSolver solver(model, s, collider);
  SettleResult out;
  long late = 0;
  for (int i = 0; i < steps; ++i) {
    const PreviewReport r = solver.step();
    EXPECT_NE(r.status, PreviewStatus::Diverged) << "step " << i;
    if (std::getenv("DRAPE_TEST_VERBOSE"))
      std::printf("  step %3d: L-G %2d residual %.1e contacts %d (ccd %d, static %d) churn %d\n", i, r.iterations,
                  r.residual, r.contacts, r.ccdContacts, r.staticFriction, r.contactChurn);
    if (i >= steps / 2) {
      late += r.iterations;
      out.lateCapped += r.iterations >= s.maxIterations;
    }
  }
  out.lateIterations = static_cast<double>(late) / (steps - steps / 2);
  out.x = rowsOf(solver.positions());
  for (int v = 0; v < out.x.rows(); ++v)
    out.deepest = std::min(out.deepest, collider->signedDistance(out.x.row(v).transpose()));
  return out;
}

}  // namespace drape::pd
