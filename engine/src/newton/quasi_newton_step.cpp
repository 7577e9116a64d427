// The quasi-Newton inner solve of NewtonSolver (the preview): L-BFGS on the incremental potential
//   Phi(x) = 1 / (2 h^2) |x - x_n - h v_n|_M^2 + sum E(x),
// whose gradient is -b / h with b Newton's momentum residual (eq. 4), so that both solvers stop on the same test and
// rest at the same states. Two-loop recursion (Nocedal and Wright, Algorithm 7.4) with the model::StepPreconditioner as
// the initial inverse Hessian (Liu, Bouaziz and Kavan 2017), backtracking Armijo line search.
#include <Eigen/Eigenvalues>
#include <chrono>
#include <cmath>
#include <deque>

#include "drape/newton/newton_solver.h"

namespace drape::newton {
namespace {

// How many times QuasiNewtonSettings::maxIterations a step may take while a term is not satisfied.
constexpr int kUnsatisfiedIterations = 4;

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// The curvature pairs of a quasi-Newton solve (at most QuasiNewtonSettings::history).
struct QuasiNewtonHistory {
  std::deque<Eigen::VectorXd> s, y;  // x_{k+1} - x_k, gradient change
  std::deque<double> rho;            // 1 / (y . s)
  void clear() {
    s.clear();
    y.clear();
    rho.clear();
  }
};

}  // namespace

void NewtonSolver::freshVertexStiffness(const Eigen::VectorXd& x, Eigen::VectorXd& k) {
  const int n = m_model.numVertices();
  k = Eigen::VectorXd::Zero(n);
  if (m_energies.size() == m_elasticCount) return;
  // A diagonal-only pattern: the changing terms write their diagonal blocks there and the rest as dynamic blocks.
  if (m_freshHessian.numBlocks() != n) m_freshHessian.build(n, {});
  m_freshHessian.setZero();
  for (size_t e = m_elasticCount; e < m_energies.size(); ++e) m_energies[e]->addHessian(x, m_freshHessian);
  for (const auto& e : m_freshHessian.dynamicEntries())
    if (e.i == e.j) m_freshHessian.diagonalBlock(e.i) += e.block;
  for (int i = 0; i < n; ++i) {
    const Eigen::Matrix3d& b = m_freshHessian.diagonalBlock(i);
    if (b.isZero(0.0)) continue;
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
    eig.computeDirect(0.5 * (b + b.transpose()), Eigen::EigenvaluesOnly);
    k[i] = std::max(0.0, eig.eigenvalues().maxCoeff());
  }
}

NewtonStatus NewtonSolver::attemptQuasiNewton(double h, double scale, Eigen::VectorXd& x, Eigen::VectorXd& v,
                                              NewtonStepReport& report) {
  report.quasiNewton = true;
  StepContext ctx{&m_x, &m_v, h, m_time, scale, assemblyOptions()};
  const auto queries = Clock::now();
  for (auto& e : m_energies) e->beginStep(ctx);
  report.contactQuerySeconds += secondsSince(queries);
  const int n = m_model.numVertices();
  const Eigen::VectorXd prediction = m_x + h * m_v;
  // Starts at the prediction x_n + h v_n. (Newton's relaxation guess, the last step's motion again, overshoots closing
  // seams into the body here, where no Hessian brings it back within the step.)
  x = prediction;
  const double invH2 = 1.0 / (h * h);

  auto t0 = Clock::now();
  Eigen::VectorXd stiffness;
  freshVertexStiffness(x, stiffness);
  if (!m_quasiNewton->prepare(h, scale, stiffness)) return NewtonStatus::Diverged;
  report.hessianSeconds += secondsSince(t0);

  // Phi and its gradient at x.
  auto potential = [&](const Eigen::VectorXd& at) {
    double inertia = 0.0;
    for (int i = 0; i < n; ++i)
      inertia += m_mass(i) * (at.segment<3>(3 * i) - prediction.segment<3>(3 * i)).squaredNorm();
    return 0.5 * invH2 * inertia + totalEnergy(at);
  };
  auto gradient = [&](const Eigen::VectorXd& at, bool first, Eigen::VectorXd& g) {
    g = Eigen::VectorXd::Zero(at.size());
    for (const auto& e : m_energies) {
      if (first)
        e->addGuessGradient(at, g);
      else
        e->addGradient(at, g);
    }
    for (int i = 0; i < n; ++i)
      g.segment<3>(3 * i) += invH2 * m_mass(i) * (at.segment<3>(3 * i) - prediction.segment<3>(3 * i));
  };

  t0 = Clock::now();
  Eigen::VectorXd g;
  gradient(x, true, g);
  double phi = 0.0;  // Phi(x), computed when a line search needs it
  report.gradientSeconds += secondsSince(t0);
  if (!g.allFinite()) return NewtonStatus::Diverged;
  double rn = h * g.norm();  // |b|, Newton's residual
  report.residual = rn;
  report.residualHistory.assign(1, rn);

  // Curvature pairs of this step only: kept from the last step (same h) they made the first directions worse (lagged
  // contact and friction change the potential between steps).
  QuasiNewtonHistory pairs;
  std::vector<double> alpha;
  Eigen::VectorXd q, r, d, xt, gt;
  NewtonStatus status = NewtonStatus::MaxIterations;
  bool phiKnown = false;
  // Past maxIterations the solve goes on, up to kUnsatisfiedIterations times as many, only while a term's own bound is
  // violated (Energy::satisfied: a vertex pushed deep into the body by an under-converged step).
  auto satisfied = [&](const Eigen::VectorXd& at) {
    for (const auto& e : m_energies)
      if (!e->satisfied(at)) return false;
    return true;
  };
  const int cap = kUnsatisfiedIterations * m_qnSettings.maxIterations;
  for (int it = 0; it < cap; ++it) {
    if (it >= m_qnSettings.maxIterations && satisfied(x)) break;  // at the last evaluated point: cached
    if (m_cancel.load()) return NewtonStatus::Cancelled;
    // H_0 with the changing terms' stiffness where they act at this iterate (a vertex pushed into the body within the
    // step meets the body's stiffness there, which the step's first H_0 did not know).
    t0 = Clock::now();
    if (it > 0) {
      freshVertexStiffness(x, stiffness);
      if (!m_quasiNewton->stiffen(stiffness)) return NewtonStatus::Diverged;
    }
    report.hessianSeconds += secondsSince(t0);
    // Two-loop recursion: d = -H_k^-1 g, H_0^-1 the preconditioner.
    t0 = Clock::now();
    q = g;
    const int m = static_cast<int>(pairs.s.size());
    alpha.assign(m, 0.0);
    for (int k = m - 1; k >= 0; --k) {
      alpha[k] = pairs.rho[k] * pairs.s[k].dot(q);
      q.noalias() -= alpha[k] * pairs.y[k];
    }
    m_quasiNewton->apply(q, r);
    for (int k = 0; k < m; ++k) {
      const double beta = pairs.rho[k] * pairs.y[k].dot(r);
      r.noalias() += (alpha[k] - beta) * pairs.s[k];
    }
    d = -r;
    double slope = g.dot(d);
    if (!(slope < 0.0) && m > 0) {  // the pairs lost positive definiteness: restart from H_0
      pairs.clear();
      m_quasiNewton->apply(g, r);
      d = -r;
      slope = g.dot(d);
    }
    report.linearSolveSeconds += secondsSince(t0);
    if (!(slope < 0.0) || !d.allFinite()) {
      m_lastResidual = -h * g;
      return rn < m_settings.tauNewton ? NewtonStatus::Converged : NewtonStatus::Diverged;
    }
    // The full step first, judged by the gradient there (needed anyway): by the trapezoidal rule Phi(x + d) - Phi(x)
    // ~ (g + g_t) . d / 2, exact where Phi is quadratic along d, so Armijo's sufficient decrease holds when
    // g_t . d <= (1 - 2 c1) |g . d|. Otherwise a backtracking line search on Phi's values (Armijo).
    t0 = Clock::now();
    xt = x + d;
    gradient(xt, false, gt);
    ++report.lineSearchEvaluations;
    bool accepted = gt.allFinite() && gt.dot(d) <= -(1.0 - 2.0 * m_qnSettings.armijo) * slope;
    const bool fullGradient = gt.allFinite();
    double step = 1.0;
    if (!accepted) {
      if (!phiKnown) phi = potential(x);
      phiKnown = true;
      for (int k = 0; k < m_qnSettings.maxLineSearchIterations; ++k, step *= 0.5) {
        xt = x + step * d;
        const double phit = potential(xt);
        ++report.lineSearchEvaluations;
        if (std::isfinite(phit) && phit <= phi + m_qnSettings.armijo * step * slope) {
          accepted = true;
          phi = phit;
          break;
        }
      }
      if (accepted && !(step == 1.0 && fullGradient)) gradient(xt, false, gt);  // else gt is the full step's
    } else {
      phiKnown = false;
    }
    report.gradientSeconds += secondsSince(t0);
    ++report.newtonIterations;
    if (!accepted) {  // no decrease along d: the state is as good as this solve gets
      status = it > 0 || rn < m_settings.tauNewton ? NewtonStatus::MaxIterations : NewtonStatus::Diverged;
      break;
    }
    if (!gt.allFinite()) return NewtonStatus::Diverged;
    Eigen::VectorXd s = xt - x, y = gt - g;
    const double sy = s.dot(y);
    if (sy > 1e-12 * y.squaredNorm() && sy > 0.0) {
      if (m == m_qnSettings.history) {
        pairs.s.pop_front();
        pairs.y.pop_front();
        pairs.rho.pop_front();
      }
      pairs.s.push_back(std::move(s));
      pairs.y.push_back(std::move(y));
      pairs.rho.push_back(1.0 / sy);
    }
    x.swap(xt);
    g.swap(gt);
    rn = h * g.norm();
    report.residual = rn;
    report.residualHistory.push_back(rn);
    // Near rest, below tau_n is not enough (NewtonSettings::restAwareConvergence): the velocity error left must be
    // below the motion the early stop waits to die out, or the accepted errors keep the garment creeping.
    if (rn < m_settings.tauNewton && residualBelowRest(-h * g)) {
      status = NewtonStatus::Converged;
      break;
    }
  }
  v = (x - m_x) / h;
  m_lastResidual = -h * g;  // the potential's gradient is -b / h
  return status;
}

}  // namespace drape::newton
