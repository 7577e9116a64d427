#pragma once
// A gradient kept from an energy's last gradient pass, keyed by the positions it was taken at (bit for bit).
// The Newton solver's relaxation steps start at x = x_n with zero velocities, and x_n is the positions of the
// last step's accepted line-search pass: the membrane and the bending record their elastic gradient there so
// that the next step's first iteration does not evaluate it again (energy.h, addRecordedStepStartGradient).
#include <Eigen/Core>
#include <cstring>

namespace drape::newton {

// True when a and b hold the same numbers bit for bit (and are not empty).
inline bool samePositions(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return a.size() == b.size() && a.size() > 0 && std::memcmp(a.data(), b.data(), sizeof(double) * a.size()) == 0;
}

struct RecordedGradient {
  bool enabled = false;
  Eigen::VectorXd gradient;  // at `at`, stiffness scale `scale`
  Eigen::VectorXd at;        // empty while a pass is recording, or when nothing is recorded
  double scale = 1.0;

  // Before a pass: clears the record (the pass accumulates into `gradient`).
  void begin(Eigen::Index size) {
    at.resize(0);
    gradient.setZero(size);
  }
  // After a complete pass at x with stiffness scale s.
  void finish(const Eigen::VectorXd& x, double s) {
    at = x;
    scale = s;
  }
  // g += the record rescaled to stiffness scale s, when it was taken at x; returns whether it was.
  bool addTo(const Eigen::VectorXd& x, double s, Eigen::VectorXd& g) const {
    if (!samePositions(at, x) || !(scale > 0.0)) return false;
    g += (s / scale) * gradient;
    return true;
  }
};

}  // namespace drape::newton
