#include "drape/newton/hinge_bending.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <unsupported/Eigen/AutoDiff>

#include "drape/newton/strain_rate_damping.h"

namespace drape::newton {
namespace {

// Dihedral angle from the 12 stacked coordinates, generic in the scalar type (for automatic differentiation).
template <typename S>
S angleOf(const Eigen::Matrix<S, 12, 1>& q) {
  using V3 = Eigen::Matrix<S, 3, 1>;
  V3 x0 = q.template segment<3>(0), x1 = q.template segment<3>(3);
  V3 x2 = q.template segment<3>(6), x3 = q.template segment<3>(9);
  V3 e = x1 - x0;
  V3 na = e.cross(x2 - x0);
  V3 nb = (x3 - x0).cross(e);
  S sine = na.cross(nb).dot(e) / e.norm();
  S cosine = na.dot(nb);
  using std::atan2;
  return atan2(sine, cosine);
}

using Grad12 = Eigen::Matrix<double, 12, 1>;
using Ad = Eigen::AutoDiffScalar<Grad12>;
using AdAd = Eigen::AutoDiffScalar<Eigen::Matrix<Ad, 12, 1>>;

double valueOf(double s) { return s; }
double valueOf(const AdAd& s) { return s.value().value(); }

// Fade c of a wing whose normal has length `length` (rest length `rest`, m^2; see hinge_bending.h); rest 0: 1.
template <typename S>
S wingFade(const S& length, double rest) {
  if (!(rest > 0.0) || valueOf(length) >= kHingeCollapseRatio * rest) return S(1.0);
  S t = length / (kHingeCollapseRatio * rest);
  return t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
}

// The fade and its derivative with respect to the normal length.
double wingFade(double length, double rest, double& derivative) {
  derivative = 0.0;
  if (!(rest > 0.0) || length >= kHingeCollapseRatio * rest) return 1.0;
  const double scale = kHingeCollapseRatio * rest, t = length / scale;
  derivative = 30.0 * t * t * (1.0 - t) * (1.0 - t) / scale;
  return t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
}

// Bending measure phi = theta c(|nA|) c(|nB|), generic in the scalar type (automatic differentiation).
template <typename S>
S measureOf(const Eigen::Matrix<S, 12, 1>& q, const std::array<double, 2>& rest) {
  using V3 = Eigen::Matrix<S, 3, 1>;
  V3 x0 = q.template segment<3>(0), x1 = q.template segment<3>(3);
  V3 x2 = q.template segment<3>(6), x3 = q.template segment<3>(9);
  V3 e = x1 - x0;
  S fade = wingFade<S>(e.cross(x2 - x0).norm(), rest[0]) * wingFade<S>((x3 - x0).cross(e).norm(), rest[1]);
  if (valueOf(fade) == 0.0) return S(0.0);
  return angleOf<S>(q) * fade;
}

// Symmetrised Hessian of f (a scalar of the 12 hinge coordinates, generic in AdAd) at q, by nested forward-mode
// automatic differentiation.
template <typename F>
Eigen::Matrix<double, 12, 12> autodiffHessian(const Grad12& q, F&& f) {
  Eigen::Matrix<AdAd, 12, 1> qa;
  for (int i = 0; i < 12; ++i) {
    Ad inner(q(i), 12, i);
    qa(i) = AdAd(inner);
    qa(i).derivatives() = Eigen::Matrix<Ad, 12, 1>::Zero();
    qa(i).derivatives()(i) = Ad(1.0, Grad12::Zero());
  }
  const AdAd value = f(qa);
  Eigen::Matrix<double, 12, 12> h;
  for (int i = 0; i < 12; ++i) h.row(i) = value.derivatives()(i).derivatives().transpose();
  return 0.5 * (h + h.transpose());
}

Grad12 autodiffGradient(const Grad12& q, double& theta) {
  Eigen::Matrix<Ad, 12, 1> qa;
  for (int i = 0; i < 12; ++i) qa(i) = Ad(q(i), 12, i);
  Ad t = angleOf<Ad>(qa);
  theta = t.value();
  return t.derivatives();
}

// Closed-form angle and gradient (Bridson et al. 2003; Tamstorf and Grinspun 2013): a wing vertex moves the angle
// by its displacement along the wing normal over its distance to the edge, d theta / d x2 = -|e| nA / |nA|^2,
// d theta / d x3 = -|e| nB / |nB|^2 (unnormalised normals, |n| = |e| * distance); the edge vertices take the
// opposite of these, split by where each wing vertex projects on the edge (translation and rotation invariance).
Grad12 closedFormGradient(const Grad12& q, double& theta) {
  const Eigen::Vector3d x0 = q.segment<3>(0), x1 = q.segment<3>(3), x2 = q.segment<3>(6), x3 = q.segment<3>(9);
  const Eigen::Vector3d e = x1 - x0, d2 = x2 - x0, d3 = x3 - x0;
  const Eigen::Vector3d na = e.cross(d2), nb = d3.cross(e);
  const double e2 = e.squaredNorm(), len = std::sqrt(e2);
  theta = std::atan2(na.cross(nb).dot(e) / len, na.dot(nb));
  const Eigen::Vector3d g2 = (-len / na.squaredNorm()) * na;
  const Eigen::Vector3d g3 = (-len / nb.squaredNorm()) * nb;
  const double a = d2.dot(e) / e2, b = d3.dot(e) / e2;  // projections of x2, x3 on the edge, from x0
  Grad12 g;
  g.segment<3>(0) = -(1.0 - a) * g2 - (1.0 - b) * g3;
  g.segment<3>(3) = -a * g2 - b * g3;
  g.segment<3>(6) = g2;
  g.segment<3>(9) = g3;
  return g;
}

}  // namespace

HingeCoords gatherHinge(const Hinge& hinge, const Eigen::VectorXd& x) {
  HingeCoords q;
  for (int k = 0; k < 4; ++k) q.segment<3>(3 * k) = x.segment<3>(3 * hinge.v[k]);
  return q;
}

std::vector<Hinge> buildHinges(const model::ClothModel& model) {
  std::map<std::pair<int, int>, std::pair<int, int>> edges;  // sorted edge -> (triangle, local index of opposite)
  std::vector<Hinge> out;
  for (int t = 0; t < model.triangles.rows(); ++t) {
    for (int k = 0; k < 3; ++k) {
      int a = model.triangles(t, k), b = model.triangles(t, (k + 1) % 3), opp = model.triangles(t, (k + 2) % 3);
      auto key = std::minmax(a, b);
      auto it = edges.find(key);
      if (it == edges.end()) {
        edges[key] = {t, opp};
        continue;
      }
      auto [t0, opp0] = it->second;
      // Triangle t0 traverses (a, b) in the opposite direction in a consistently oriented mesh: t0 = (b, a, opp0).
      Hinge h;
      h.v = {b, a, opp0, opp};
      Eigen::Vector2d ua = model.restCoords.row(a).transpose(), ub = model.restCoords.row(b).transpose();
      Eigen::Vector2d d = ub - ua;
      auto area = [&](int tri) {
        Eigen::Vector2d p0 = model.restCoords.row(model.triangles(tri, 0)).transpose();
        Eigen::Vector2d e1 = model.restCoords.row(model.triangles(tri, 1)).transpose() - p0;
        Eigen::Vector2d e2 = model.restCoords.row(model.triangles(tri, 2)).transpose() - p0;
        return 0.5 * std::abs(e1.x() * e2.y() - e1.y() * e2.x());
      };
      double len2 = d.squaredNorm();
      Eigen::Vector2d dir = d / std::sqrt(len2);
      auto kb = [&](int tri) {
        const model::TriangleFabric& f = model.fabric(tri);
        return f.bendWarp * dir.y() * dir.y() + f.bendWeft * dir.x() * dir.x();
      };
      h.stiffness = 0.5 * (kb(t0) + kb(t)) * 3.0 * len2 / (area(t0) + area(t));
      h.restNormalLength = {2.0 * area(t0), 2.0 * area(t)};
      if (h.stiffness > 0.0) out.push_back(h);
      edges.erase(it);  // a third triangle on the same edge (non-manifold) starts a new pair
    }
  }
  return out;
}

double hingeAngle(const Hinge& hinge, const Eigen::VectorXd& x) {
  return angleOf<double>(gatherHinge(hinge, x));
}

Grad12 hingeAngleGradient(const Hinge& hinge, const Eigen::VectorXd& x) {
  double theta = 0.0;
  return closedFormGradient(gatherHinge(hinge, x), theta);
}

Grad12 hingeAngleGradientAutodiff(const Hinge& hinge, const Eigen::VectorXd& x) {
  double theta = 0.0;
  return autodiffGradient(gatherHinge(hinge, x), theta);
}

Grad12 hingeAngleGradient(const Hinge& hinge, const Eigen::VectorXd& x, bool closedForm, double& theta) {
  Grad12 q = gatherHinge(hinge, x);
  return closedForm ? closedFormGradient(q, theta) : autodiffGradient(q, theta);
}

Eigen::Matrix<double, 12, 12> hingeAngleHessian(const Hinge& hinge, const Eigen::VectorXd& x) {
  return autodiffHessian(gatherHinge(hinge, x), [](const Eigen::Matrix<AdAd, 12, 1>& qa) { return angleOf<AdAd>(qa); });
}

Grad12 hingeBendGradient(const Hinge& hinge, const Eigen::VectorXd& x, bool closedForm, double& phi) {
  return hingeBendGradient(hinge, gatherHinge(hinge, x), closedForm, phi);
}

Grad12 hingeBendGradient(const Hinge& hinge, const HingeCoords& q, bool closedForm, double& phi) {
  const Eigen::Vector3d x0 = q.segment<3>(0), e = q.segment<3>(3) - x0;
  const Eigen::Vector3d d2 = q.segment<3>(6) - x0, d3 = q.segment<3>(9) - x0;
  const Eigen::Vector3d na = e.cross(d2), nb = d3.cross(e);
  const double la = na.norm(), lb = nb.norm();
  double dcA = 0.0, dcB = 0.0;
  const double cA = wingFade(la, hinge.restNormalLength[0], dcA), cB = wingFade(lb, hinge.restNormalLength[1], dcB);
  const double fade = cA * cB;
  if (fade == 0.0) {  // a zero-area wing: no bending (and grad theta undefined)
    phi = 0.0;
    return Grad12::Zero();
  }
  double theta = 0.0;
  Grad12 g = fade * (closedForm ? closedFormGradient(q, theta) : autodiffGradient(q, theta));
  phi = theta * fade;
  // + theta grad(fade); d|nA|/dx1 = d2 x nA^, d|nA|/dx2 = nA^ x e; d|nB|/dx3 = e x nB^, d|nB|/dx1 = nB^ x d3;
  // x0 takes minus the sum (translation invariance).
  // One wing's term: c times the gradients of its |n| at x1 and at its own vertex (slot 2 for A, 3 for B).
  auto addWing = [&](double c, const Eigen::Vector3d& at1, const Eigen::Vector3d& atOwn, int ownSlot) {
    g.segment<3>(0) -= c * (at1 + atOwn);
    g.segment<3>(3) += c * at1;
    g.segment<3>(3 * ownSlot) += c * atOwn;
  };
  if (dcA != 0.0) {
    const Eigen::Vector3d n = na / la;
    addWing(theta * cB * dcA, d2.cross(n), n.cross(e), 2);
  }
  if (dcB != 0.0) {
    const Eigen::Vector3d n = nb / lb;
    addWing(theta * cA * dcB, n.cross(d3), e.cross(n), 3);
  }
  return g;
}

double hingeBendMeasure(const Hinge& hinge, const Eigen::VectorXd& x) {
  return measureOf<double>(gatherHinge(hinge, x), hinge.restNormalLength);
}

Eigen::Matrix<double, 12, 12> hingeBendHessian(const Hinge& hinge, const Eigen::VectorXd& x) {
  return autodiffHessian(gatherHinge(hinge, x), [&](const Eigen::Matrix<AdAd, 12, 1>& qa) {
    return measureOf<AdAd>(qa, hinge.restNormalLength);
  });
}

HingeBending::HingeBending(const model::ClothModel& model) : m_hinges(buildHinges(model)) {
  std::vector<std::array<int, 4>> stencils;
  stencils.reserve(m_hinges.size());
  for (const auto& h : m_hinges) stencils.push_back(h.v);
  m_stencils = StencilSet<4>(std::move(stencils));
}

void HingeBending::beginStep(const StepContext& ctx) {
  m_scale = ctx.stiffnessScale;
  m_options = ctx.assembly;
}

double HingeBending::value(const Eigen::VectorXd& x) const {
  double sum = 0.0;
  for (const auto& h : m_hinges) {
    double phi = hingeBendMeasure(h, x);
    sum += 0.5 * h.stiffness * phi * phi;
  }
  return m_scale * sum;
}

double zeroSumOffset(const Hinge& hinge, const Eigen::VectorXd& x, Grad12& g) {
  return zeroSumOffset(gatherHinge(hinge, x), g);
}

double zeroSumOffset(const HingeCoords& q, Grad12& g) {
  g.segment<3>(0) = -(g.segment<3>(3) + g.segment<3>(6) + g.segment<3>(9));
  const Eigen::Vector3d x0 = q.segment<3>(0);
  double sum = 0.0;
  for (int k = 1; k < 4; ++k) sum += g.segment<3>(3 * k).dot(q.segment<3>(3 * k) - x0);
  return sum;
}

bool HingeBending::hasRecordedGradientsAt(const Eigen::VectorXd& x, bool closedForm) const {
  return m_recordedClosedForm == closedForm && samePositions(m_recordedAt, x) && m_recorded.size() == m_hinges.size();
}

bool HingeBending::takeRecordedGradients(const Eigen::VectorXd& x, bool closedForm, std::vector<Grad12>& gradients,
                                         std::vector<double>& offsets) const {
  if (!hasRecordedGradientsAt(x, closedForm)) return false;
  gradients.swap(m_recorded);
  offsets.swap(m_recordedOffsets);
  m_recordedAt.resize(0);
  return true;
}

void HingeBending::addGradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const { gradientPass(x, g, true); }

void HingeBending::gradientPass(const Eigen::VectorXd& x, Eigen::VectorXd& g, bool record) const {
  const bool closedForm = m_options.closedFormBending;
  const BendingDissipation* fold = m_options.foldDissipation ? m_dissipation : nullptr;
  const bool recordAngles = record && m_record;
  if (recordAngles) {
    m_recorded.resize(m_hinges.size());
    m_recordedOffsets.resize(m_hinges.size());
    m_recordedAt.resize(0);  // invalid until the pass is complete
  }
  const bool recordGradient = record && m_recordedGradient.enabled;
  if (recordGradient) m_recordedGradient.begin(x.size());
  m_stencils.forEach(m_options.parallel, [&](const int* ids, int count) {
    if (closedForm && m_options.batchedGradients) {
      batchGradients(x, ids, count, recordAngles, recordGradient ? &m_recordedGradient.gradient : nullptr, fold, g);
      return;
    }
    for (int i = 0; i < count; ++i) {
      const Hinge& h = m_hinges[ids[i]];
      const HingeCoords q = gatherHinge(h, x);
      double phi = 0.0;
      const Grad12 grad = hingeBendGradient(h, q, closedForm, phi);
      if (recordAngles) {
        Grad12& r = m_recorded[ids[i]];
        r = grad;
        m_recordedOffsets[ids[i]] = zeroSumOffset(q, r);
      }
      Grad12 ge = (m_scale * h.stiffness * phi) * grad;
      if (recordGradient) m_stencils.addGradient(ids[i], ge, m_recordedGradient.gradient);
      if (fold) ge += fold->stencilGradient(ids[i], q, h.stiffness);
      m_stencils.addGradient(ids[i], ge, g);
    }
  });
  if (recordGradient) m_recordedGradient.finish(x, m_scale);
  if (recordAngles) {
    m_recordedAt = x;
    m_recordedClosedForm = closedForm;
  }
}

// The closed-form hingeBendGradient of kLanes hinges at a time: every quantity an array over the lanes, so that the
// arithmetic vectorises across hinges (the gathers, atan2 and the scatters stay scalar). A lane whose fade is 0
// (a collapsed wing) contributes nothing, as in hingeBendGradient.
void HingeBending::batchGradients(const Eigen::VectorXd& x, const int* ids, int count, bool recordAngles,
                                  Eigen::VectorXd* recordedGradient, const BendingDissipation* fold,
                                  Eigen::VectorXd& g) const {
  constexpr int kLanes = 8;
  const double foldFactor = fold ? fold->factor() : 0.0;
  for (int i0 = 0; i0 < count; i0 += kLanes) {
    const int lanes = std::min(kLanes, count - i0);
    // The next batch's hinges and folded start gradients, requested ahead: on a reordered matrix the stencils are
    // visited by storage row, not by index, so these reads do not stream.
    for (int l = 0; l < kLanes && i0 + kLanes + l < count; ++l) {
      const int s = ids[i0 + kLanes + l];
      prefetchRange(&m_hinges[s], sizeof(Hinge));
      if (fold) {
        prefetchRange(fold->startGradient(s).data(), sizeof(Grad12));
        __builtin_prefetch(&fold->startOffset(s));
      }
    }
    alignas(64) double q[12][kLanes], gr[12][kLanes], gd[12][kLanes], ge[12][kLanes];
    // The wing fades' 1 / (ratio rest), and 1 where a wing has no rest length (no fade: t = 1).
    alignas(64) double invScale[2][kLanes], noFade[2][kLanes];
    alignas(64) double k[kLanes], sine[kLanes], cosine[kLanes], theta[kLanes], edgeLength[kLanes];
    alignas(64) double offset[kLanes], recordedOffset[kLanes], coef[kLanes], live[kLanes];
    for (int l = 0; l < kLanes; ++l) {
      const int s = ids[i0 + (l < lanes ? l : 0)];
      const Hinge& h = m_hinges[s];
      for (int v = 0; v < 4; ++v) {
        const double* xv = x.data() + 3 * h.v[v];
        for (int d = 0; d < 3; ++d) q[3 * v + d][l] = xv[d];
      }
      k[l] = h.stiffness;
      live[l] = l < lanes ? 1.0 : 0.0;
      for (int w = 0; w < 2; ++w) {
        const bool fades = h.restNormalLength[w] > 0.0;
        invScale[w][l] = fades ? 1.0 / (kHingeCollapseRatio * h.restNormalLength[w]) : 0.0;
        noFade[w][l] = fades ? 0.0 : 1.0;
      }
      if (fold) {
        const Grad12& gs = fold->startGradient(s);
        for (int j = 0; j < 12; ++j) gd[j][l] = gs(j);
        offset[l] = fold->startOffset(s);
      }
    }
    // Relative coordinates and the wing normals; atan2's arguments.
    alignas(64) double e[3][kLanes], d2[3][kLanes], d3[3][kLanes], na[3][kLanes], nb[3][kLanes];
    for (int l = 0; l < kLanes; ++l) {
      for (int d = 0; d < 3; ++d) {
        e[d][l] = q[3 + d][l] - q[d][l];
        d2[d][l] = q[6 + d][l] - q[d][l];
        d3[d][l] = q[9 + d][l] - q[d][l];
      }
      for (int d = 0; d < 3; ++d) {
        const int d1 = (d + 1) % 3, dd = (d + 2) % 3;
        na[d][l] = e[d1][l] * d2[dd][l] - e[dd][l] * d2[d1][l];
        nb[d][l] = d3[d1][l] * e[dd][l] - d3[dd][l] * e[d1][l];
      }
      double m[3];
      for (int d = 0; d < 3; ++d) {
        const int d1 = (d + 1) % 3, dd = (d + 2) % 3;
        m[d] = na[d1][l] * nb[dd][l] - na[dd][l] * nb[d1][l];
      }
      const double len = std::sqrt(e[0][l] * e[0][l] + e[1][l] * e[1][l] + e[2][l] * e[2][l]);
      edgeLength[l] = len;
      sine[l] = (m[0] * e[0][l] + m[1] * e[1][l] + m[2] * e[2][l]) / len;
      cosine[l] = na[0][l] * nb[0][l] + na[1][l] * nb[1][l] + na[2][l] * nb[2][l];
    }
    for (int l = 0; l < kLanes; ++l) theta[l] = std::atan2(sine[l], cosine[l]);
    for (int l = 0; l < kLanes; ++l) {
      const double e2 = e[0][l] * e[0][l] + e[1][l] * e[1][l] + e[2][l] * e[2][l], len = edgeLength[l];
      const double na2 = na[0][l] * na[0][l] + na[1][l] * na[1][l] + na[2][l] * na[2][l];
      const double nb2 = nb[0][l] * nb[0][l] + nb[1][l] * nb[1][l] + nb[2][l] * nb[2][l];
      // Wing fades (wingFade): t = |n| / (ratio rest), capped at 1 where the fade is 1 (or no rest length).
      const double normA = std::sqrt(na2), normB = std::sqrt(nb2);
      const double uA = normA * invScale[0][l] + noFade[0][l];
      const double uB = normB * invScale[1][l] + noFade[1][l];
      // Capped at the lane's live flag (1; 0 on the padding lanes past count, whose fade is then 0): a run-time
      // value, so that the compiler does not split the loop on the constant cap's branch and then not vectorise.
      const double tA = uA < live[l] ? uA : live[l], tB = uB < live[l] ? uB : live[l];
      const double cA = tA * tA * tA * (tA * (tA * 6.0 - 15.0) + 10.0);
      const double cB = tB * tB * tB * (tB * (tB * 6.0 - 15.0) + 10.0);
      const double dcA = 30.0 * tA * tA * (1.0 - tA) * (1.0 - tA) * invScale[0][l];
      const double dcB = 30.0 * tB * tB * (1.0 - tB) * (1.0 - tB) * invScale[1][l];
      const double fade = cA * cB, th = theta[l];
      // Where the fade is 0 (a collapsed wing, |n| = 0, or a padding lane) the normals' lengths are taken 1 larger,
      // so that nothing divides by 0, and every term below is then 0 (dc = 0 at t = 0).
      const double dead = fade == 0.0 ? 1.0 : 0.0;
      const double la2 = na2 + dead, lb2 = nb2 + dead, la = normA + dead, lb = normB + dead;
      // grad theta (closedFormGradient) times the fade.
      const double ca = -len / la2 * fade, cb = -len / lb2 * fade;
      const double pa = (d2[0][l] * e[0][l] + d2[1][l] * e[1][l] + d2[2][l] * e[2][l]) / e2;
      const double pb = (d3[0][l] * e[0][l] + d3[1][l] * e[1][l] + d3[2][l] * e[2][l]) / e2;
      // + theta grad(fade): the wings' normal-length gradients (hingeBendGradient).
      const double wa = th * cB * dcA / la, wb = th * cA * dcB / lb;
      for (int d = 0; d < 3; ++d) {
        const int d1 = (d + 1) % 3, dd = (d + 2) % 3;
        const double g2 = ca * na[d][l], g3 = cb * nb[d][l];
        // d2 x nA, nA x e; nB x d3, e x nB (unnormalised; wa, wb carry 1 / |n|).
        const double a1 = wa * (d2[d1][l] * na[dd][l] - d2[dd][l] * na[d1][l]);
        const double aOwn = wa * (na[d1][l] * e[dd][l] - na[dd][l] * e[d1][l]);
        const double b1 = wb * (nb[d1][l] * d3[dd][l] - nb[dd][l] * d3[d1][l]);
        const double bOwn = wb * (e[d1][l] * nb[dd][l] - e[dd][l] * nb[d1][l]);
        gr[d][l] = -(1.0 - pa) * g2 - (1.0 - pb) * g3 - (a1 + aOwn) - (b1 + bOwn);
        gr[3 + d][l] = -pa * g2 - pb * g3 + a1 + b1;
        gr[6 + d][l] = g2 + aOwn;
        gr[9 + d][l] = g3 + bOwn;
      }
      coef[l] = m_scale * k[l] * th * fade;  // k_e phi
    }
    for (int j = 0; j < 12; ++j)
      for (int l = 0; l < kLanes; ++l) ge[j][l] = coef[l] * gr[j][l];
    if (recordAngles) {
      // zeroSumOffset: g_0 = -(g_1 + g_2 + g_3), offset sum_k>0 g_k . (x_k - x_0).
      for (int l = 0; l < kLanes; ++l) {
        double o = 0.0;
        for (int d = 0; d < 3; ++d) {
          gr[d][l] = -(gr[3 + d][l] + gr[6 + d][l] + gr[9 + d][l]);
          o += gr[3 + d][l] * (q[3 + d][l] - q[d][l]) + gr[6 + d][l] * (q[6 + d][l] - q[d][l]) +
               gr[9 + d][l] * (q[9 + d][l] - q[d][l]);
        }
        recordedOffset[l] = o;
      }
      for (int l = 0; l < lanes; ++l) {
        const int s = ids[i0 + l];
        double* r = m_recorded[s].data();
        for (int j = 0; j < 12; ++j) r[j] = gr[j][l];
        m_recordedOffsets[s] = recordedOffset[l];
      }
    }
    if (recordedGradient)
      for (int l = 0; l < lanes; ++l) {
        const Hinge& h = m_hinges[ids[i0 + l]];
        for (int v = 0; v < 4; ++v)
          for (int d = 0; d < 3; ++d) (*recordedGradient)[3 * h.v[v] + d] += ge[3 * v + d][l];
      }
    if (fold) {
      // BendingDissipation::stencilGradient: (c k (g . d)) g, g . d = sum_k>0 g_k . (x_k - x_0) - o.
      for (int l = 0; l < kLanes; ++l) {
        double change = -offset[l];
        for (int d = 0; d < 3; ++d)
          change += gd[3 + d][l] * (q[3 + d][l] - q[d][l]) + gd[6 + d][l] * (q[6 + d][l] - q[d][l]) +
                    gd[9 + d][l] * (q[9 + d][l] - q[d][l]);
        coef[l] = foldFactor * k[l] * change;
      }
      for (int j = 0; j < 12; ++j)
        for (int l = 0; l < kLanes; ++l) ge[j][l] += coef[l] * gd[j][l];
    }
    for (int l = 0; l < lanes; ++l) {
      const Hinge& h = m_hinges[ids[i0 + l]];
      for (int v = 0; v < 4; ++v) {
        double* gv = g.data() + 3 * h.v[v];
        for (int d = 0; d < 3; ++d) gv[d] += ge[3 * v + d][l];
      }
    }
  }
}

void HingeBending::addHessian(const Eigen::VectorXd& x, BlockMatrix& hm) const { assemble(x, nullptr, hm); }

void HingeBending::addGradientAndHessian(const Eigen::VectorXd& x, Eigen::VectorXd& g, BlockMatrix& hm) const {
  assemble(x, &g, hm);
}

void HingeBending::assemble(const Eigen::VectorXd& x, Eigen::VectorXd* g, BlockMatrix& hm) const {
  const bool cached = m_options.cachedBlockMap, closedForm = m_options.closedFormBending;
  const BendingDissipation* fold = m_options.foldDissipation ? m_dissipation : nullptr;
  if (cached) m_stencils.prepare(hm);
  m_stencils.forEach(m_options.parallel, [&](const int* ids, int count) {
    for (int i = 0; i < count; ++i) {
      const int s = ids[i];
      if (i + kPrefetchAhead < count) {
        const int next = ids[i + kPrefetchAhead];
        m_stencils.prefetch(next);
        prefetchRange(&m_hinges[next], sizeof(Hinge));
        if (fold) prefetchRange(fold->startGradient(next).data(), sizeof(Grad12));
      }
      const Hinge& h = m_hinges[s];
      const HingeCoords q = gatherHinge(h, x);
      double phi = 0.0;
      const Grad12 grad = hingeBendGradient(h, q, closedForm, phi);
      const double k = m_scale * h.stiffness;
      Grad12 ge = (k * phi) * grad;
      if (fold && g) ge += fold->stencilGradient(s, q, h.stiffness);
      if (g) m_stencils.addGradient(s, ge, *g);
      // Gauss-Newton k grad grad^T, and the folded dissipation's (c k_e) g_n g_n^T (stencilDerivatives).
      const double foldWeight = fold ? fold->factor() * h.stiffness : 0.0;
      const Grad12& gn = fold ? fold->startGradient(s) : grad;
      if (!m_exactHessian) {
        m_stencils.addOuterProducts(s, k, grad, foldWeight, gn, hm, cached);
        continue;
      }
      Eigen::Matrix<double, 12, 12> he = k * (grad * grad.transpose() + phi * hingeBendHessian(h, x));
      if (fold) he += foldWeight * (gn * gn.transpose());
      m_stencils.addHessian(s, he, hm, cached);
    }
  });
}

void HingeBending::addCouplings(std::vector<std::pair<int, int>>& pairs) const { m_stencils.addCouplings(pairs); }

}  // namespace drape::newton
