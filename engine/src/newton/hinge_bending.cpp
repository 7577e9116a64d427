#include "drape/newton/hinge_bending.h"

#include "drape/newton/strain_rate_damping.h"

#include <Eigen/Geometry>
#include <unsupported/Eigen/AutoDiff>

#include <cmath>
#include <map>

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

std::vector<Hinge> buildHinges(const ClothModel& model) {
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
        const TriangleFabric& f = model.fabric(tri);
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

HingeBending::HingeBending(const ClothModel& model) : m_hinges(buildHinges(model)) {
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

void HingeBending::addHessian(const Eigen::VectorXd& x, BlockMatrix& hm) const { assemble(x, nullptr, hm); }

void HingeBending::addGradientAndHessian(const Eigen::VectorXd& x, Eigen::VectorXd& g, BlockMatrix& hm) const {
  assemble(x, &g, hm);
}

void HingeBending::assemble(const Eigen::VectorXd& x, Eigen::VectorXd* g, BlockMatrix& hm) const {
  const bool cached = m_options.cachedBlockMap, closedForm = m_options.closedFormBending;
  const BendingDissipation* fold = m_options.foldDissipation ? m_dissipation : nullptr;
  if (cached) m_stencils.prepare(hm);
  m_stencils.forEach(m_options.parallel, [&](const int* ids, int count) {
    Grad12 gd;
    for (int i = 0; i < count; ++i) {
      const Hinge& h = m_hinges[ids[i]];
      const HingeCoords q = gatherHinge(h, x);
      double phi = 0.0;
      Grad12 grad = hingeBendGradient(h, q, closedForm, phi);
      Eigen::Matrix<double, 12, 12> he = grad * grad.transpose();
      if (m_exactHessian) he += phi * hingeBendHessian(h, x);
      he *= m_scale * h.stiffness;
      Grad12 ge = (m_scale * h.stiffness * phi) * grad;
      if (fold) {
        he += fold->stencilDerivatives(ids[i], q, h.stiffness, g ? &gd : nullptr);
        if (g) ge += gd;
      }
      m_stencils.addHessian(ids[i], he, hm, cached);
      if (g) m_stencils.addGradient(ids[i], ge, *g);
    }
  });
}

void HingeBending::addCouplings(std::vector<std::pair<int, int>>& pairs) const { m_stencils.addCouplings(pairs); }

}  // namespace drape::newton
