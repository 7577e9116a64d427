#pragma once
// Anderson acceleration (type II, windowed) of a fixed-point iteration x <- G(x) on the preview's free positions
// (Walker and Ni 2011; Peng et al. 2018 apply it to Projective Dynamics). From the last m differences of the
// iterates and of their residuals f = G(x) - x it extrapolates x_next = G(x) - dG gamma, gamma minimising
// |f - dF gamma|. Safeguarded: when a residual grows against the previous one, the history is dropped and the plain
// step G(x) taken, so the accelerated loop is never worse than a restart of the plain one.
#include <Eigen/Core>

namespace drape::pd {

class AndersonMixer {
 public:
  explicit AndersonMixer(int window = 5) : m_window(window) {}
  void reset() { m_count = m_head = 0; m_have = false; }
  // x: the current iterate, g: G(x) (same shape, rows = free DOFs). Returns the next iterate.
  Eigen::MatrixX3d next(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& g);
  int window() const { return m_window; }
  int restarts() const { return m_restarts; }

 private:
  int m_window;
  int m_count = 0;       // differences stored (<= window), in columns [0, count) until the window is full
  int m_head = 0;        // slot of the next difference (== count until the window is full)
  bool m_have = false;   // a previous (x, g) pair exists
  int m_restarts = 0;
  double m_lastNorm = 0.0;
  Eigen::VectorXd m_fPrev, m_gPrev;
  Eigen::MatrixXd m_dF, m_dG;  // columns: differences of residuals and of G values
};

}  // namespace drape::pd
