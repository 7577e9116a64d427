#include "drape/pd/pd_system.h"

#include <Eigen/LU>
#include <algorithm>
#include <map>
#include <stdexcept>
#include <string>
#include <tbb/parallel_for.h>

#include "drape/core/input_error.h"

namespace drape::pd {
namespace {

double cotangent(const Eigen::Vector2d& u, const Eigen::Vector2d& v) {
  const double cross = std::abs(u.x() * v.y() - u.y() * v.x());
  return u.dot(v) / std::max(cross, 1e-300);
}

double restArea(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  const Eigen::Vector2d e1 = b - a, e2 = c - a;
  return 0.5 * (e1.x() * e2.y() - e1.y() * e2.x());
}

}  // namespace

Eigen::Vector4d hingeVector(const Eigen::Vector2d& r0, const Eigen::Vector2d& r1, const Eigen::Vector2d& r2,
                            const Eigen::Vector2d& r3) {
  const Eigen::Vector2d e0 = r1 - r0, e1 = r2 - r0, e2 = r3 - r0, e3 = r2 - r1, e4 = r3 - r1;
  const double c01 = cotangent(e0, e1), c02 = cotangent(e0, e2);
  const double c03 = cotangent(-e0, e3), c04 = cotangent(-e0, e4);
  return Eigen::Vector4d(c03 + c04, c01 + c02, -c01 - c03, -c02 - c04);
}

PdSystem::PdSystem(const model::ClothModel& model, const PreviewSettings& settings)
    : m_h(settings.timeStep), m_triangles(model.triangles), m_gravity(model.gravity), m_warp(settings.warpLimits),
      m_weft(settings.weftLimits), m_shearLimit(settings.shearLimit),
      m_stretchHoldsShear(settings.shearModel == ShearModelKind::Stretch) {
  const int nv = model.numVertices();
  const int nt = static_cast<int>(model.triangles.rows());
  m_vertexCount = nv;
  if (!(settings.timeStep > 0.0)) throw InputError("preview settings: time step must be positive");
  if (model.positions.size() != 3 * nv)
    throw InputError("cloth model: positions have " + std::to_string(model.positions.size()) +
                     " values, expected 3 x " + std::to_string(nv));
  if (model.fabrics.size() != 1 && static_cast<int>(model.fabrics.size()) != nt)
    throw InputError("cloth model: " + std::to_string(model.fabrics.size()) + " fabrics for " +
                     std::to_string(nt) + " triangles (expected 1 or one per triangle)");
  for (int t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k)
      if (model.triangles(t, k) < 0 || model.triangles(t, k) >= nv)
        throw InputError("cloth model: triangle " + std::to_string(t) + ": vertex " +
                         std::to_string(model.triangles(t, k)) + " out of range (" + std::to_string(nv) +
                         " vertices)");
  model::validateStitches(model);
  if (!model.pinTargets.empty() && model.pinTargets.size() != model.pinned.size())
    throw InputError("cloth model: " + std::to_string(model.pinTargets.size()) + " pin targets for " +
                     std::to_string(model.pinned.size()) + " pins");

  // Pins: eliminated from the unknowns.
  m_dofOfVertex.assign(nv, 0);
  for (size_t p = 0; p < model.pinned.size(); ++p) {
    const int v = model.pinned[p];
    if (v < 0 || v >= nv)
      throw InputError("cloth model: pin " + std::to_string(p) + ": vertex " + std::to_string(v) +
                       " out of range (" + std::to_string(nv) + " vertices)");
    if (m_dofOfVertex[v] < 0) continue;  // pinned twice
    m_dofOfVertex[v] = -1;
    m_pinned.push_back(v);
  }
  m_pinTargets.resize(static_cast<int>(m_pinned.size()), 3);
  for (size_t p = 0, k = 0; p < model.pinned.size(); ++p) {
    const int v = model.pinned[p];
    if (k < m_pinned.size() && m_pinned[k] == v) {
      const Eigen::Vector3d target =
          model.pinTargets.empty() ? Eigen::Vector3d(model.positions.segment<3>(3 * v)) : model.pinTargets[p];
      m_pinTargets.row(static_cast<int>(k)) = target.transpose();
      ++k;
    }
  }
  for (int v = 0; v < nv; ++v)
    if (m_dofOfVertex[v] >= 0) {
      m_dofOfVertex[v] = static_cast<int>(m_freeVertices.size());
      m_freeVertices.push_back(v);
    }

  // Masses and strain constraints.
  m_mass = Eigen::VectorXd::Zero(nv);
  double maxStretch = 0.0;
  m_strains.reserve(nt);
  for (int t = 0; t < nt; ++t) {
    const auto& fab = model.fabric(t);
    const Eigen::Vector3i tri = model.triangles.row(t);
    const Eigen::Vector2d r0 = model.restCoords.row(tri[0]), r1 = model.restCoords.row(tri[1]),
                          r2 = model.restCoords.row(tri[2]);
    const double area = std::abs(restArea(r0, r1, r2));
    StrainConstraint sc;
    sc.vertices = {tri[0], tri[1], tri[2]};
    if (area > 1e-14) {
      Eigen::Matrix2d dm;
      dm.col(0) = r1 - r0;
      dm.col(1) = r2 - r0;
      const Eigen::Matrix2d inv = dm.inverse();
      sc.g.row(1) = inv.row(0);
      sc.g.row(2) = inv.row(1);
      sc.g.row(0) = -(inv.row(0) + inv.row(1));
      sc.weightWarp = fab.stretchWarp * area;
      sc.weightWeft = fab.stretchWeft * area;
      sc.weightShear = m_stretchHoldsShear ? 0.0 : fab.shear * area;
      for (int k = 0; k < 3; ++k) m_mass[tri[k]] += fab.density * area / 3.0;
    }
    maxStretch = std::max({maxStretch, fab.stretchWarp, fab.stretchWeft});
    Stencil st;
    st.size = 3;
    st.ownerTriangle = t;
    for (int k = 0; k < 3; ++k) st.vertices[k] = tri[k];
    st.q.topLeftCorner<3, 3>() = sc.columnWeight(0) * sc.g.col(0) * sc.g.col(0).transpose() +
                                 sc.columnWeight(1) * sc.g.col(1) * sc.g.col(1).transpose();
    m_stencils.push_back(st);
    m_strains.push_back(sc);
  }
  // Vertices without mass (in no triangle, or only in degenerate ones) get a small one so K stays definite.
  const double meanMass = nv > 0 ? std::max(m_mass.sum() / nv, 1e-9) : 1.0;
  for (int v = 0; v < nv; ++v)
    if (!(m_mass[v] > 0.0)) m_mass[v] = 1e-3 * meanMass;

  // Bending hinges on interior edges (edges shared by exactly two triangles).
  std::map<std::pair<int, int>, std::vector<std::pair<int, int>>> edgeTriangles;  // edge -> (triangle, opposite)
  for (int t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = model.triangles(t, k), b = model.triangles(t, (k + 1) % 3), c = model.triangles(t, (k + 2) % 3);
      edgeTriangles[{std::min(a, b), std::max(a, b)}].push_back({t, c});
    }
  for (const auto& [edge, tris] : edgeTriangles) {
    if (tris.size() != 2) continue;
    const auto [t0, v2] = tris[0];
    const auto [t1, v3] = tris[1];
    const Eigen::Vector2d r0 = model.restCoords.row(edge.first), r1 = model.restCoords.row(edge.second);
    const Eigen::Vector2d r2 = model.restCoords.row(v2), r3 = model.restCoords.row(v3);
    const double a0 = std::abs(restArea(r0, r1, r2)), a1 = std::abs(restArea(r0, r1, r3));
    if (a0 + a1 < 1e-14 || a0 < 1e-16 || a1 < 1e-16) continue;
    const auto& f0 = model.fabric(t0);
    const auto& f1 = model.fabric(t1);
    const double kb = 0.25 * (f0.bendWarp + f0.bendWeft + f1.bendWarp + f1.bendWeft) * settings.bendingScale;
    if (!(kb > 0.0)) continue;
    const Eigen::Vector4d hv = hingeVector(r0, r1, r2, r3);
    Stencil st;
    st.size = 4;
    st.ownerTriangle = t0;
    st.vertices = {edge.first, edge.second, v2, v3};
    st.q = kb * 3.0 / (a0 + a1) * hv * hv.transpose();
    m_stencils.push_back(st);
  }

  // Stitches: zero-length springs, owned by a triangle touching their first vertex.
  std::vector<int> someTriangle(nv, 0);
  for (int t = nt - 1; t >= 0; --t)
    for (int k = 0; k < 3; ++k) someTriangle[model.triangles(t, k)] = t;
  m_largestStretch = maxStretch;
  const double stitchWeight = settings.stitchWeight > 0.0 ? settings.stitchWeight : 10.0 * maxStretch;
  for (const auto& [a, b] : model.stitches) {
    if (a == b) continue;  // a dart tip sewn to itself: no term
    Stencil st;
    st.size = 2;
    st.ownerTriangle = someTriangle[a];
    st.vertices = {a, b, 0, 0};
    st.q.topLeftCorner<2, 2>() << stitchWeight, -stitchWeight, -stitchWeight, stitchWeight;
    m_stencils.push_back(st);
  }
  // Edge stitches (pd-dd section 4.4): constraint A = [1, -(1 - t), -t] on (v, a, b), q = w A^T A. Owned by a
  // triangle of the edge, so that only v is shared with another domain when the seam crosses domains.
  for (const model::EdgeStitch& e : model.edgeStitches) {
    Stencil st;
    st.size = 3;
    const auto it = edgeTriangles.find({std::min(e.a, e.b), std::max(e.a, e.b)});
    st.ownerTriangle = it != edgeTriangles.end() ? it->second.front().first : someTriangle[e.a];
    st.vertices = {e.vertex, e.a, e.b, 0};
    const Eigen::Vector3d a(1.0, -(1.0 - e.t), -e.t);
    st.q.topLeftCorner<3, 3>() = stitchWeight * a * a.transpose();
    m_stencils.push_back(st);
  }

  // K over the free DOFs and its coupling to the pins.
  std::vector<int> pinIndex(nv, -1);
  for (size_t p = 0; p < m_pinned.size(); ++p) pinIndex[m_pinned[p]] = static_cast<int>(p);
  std::vector<Eigen::Triplet<double>> kt, pt;
  const double invH2 = 1.0 / (m_h * m_h);
  for (int v : m_freeVertices) kt.emplace_back(m_dofOfVertex[v], m_dofOfVertex[v], m_mass[v] * invH2);
  for (const Stencil& st : m_stencils)
    for (int i = 0; i < st.size; ++i) {
      const int di = m_dofOfVertex[st.vertices[i]];
      if (di < 0) continue;
      for (int j = 0; j < st.size; ++j) {
        const int dj = m_dofOfVertex[st.vertices[j]];
        if (dj >= 0)
          kt.emplace_back(di, dj, st.q(i, j));
        else
          pt.emplace_back(di, pinIndex[st.vertices[j]], st.q(i, j));
      }
    }
  m_k.resize(freeCount(), freeCount());
  m_k.setFromTriplets(kt.begin(), kt.end());
  m_kfp.resize(freeCount(), static_cast<int>(m_pinned.size()));
  m_kfp.setFromTriplets(pt.begin(), pt.end());

  // Vertex -> incident triangles.
  m_incOffsets.assign(nv + 1, 0);
  for (int t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) ++m_incOffsets[model.triangles(t, k) + 1];
  for (int v = 0; v < nv; ++v) m_incOffsets[v + 1] += m_incOffsets[v];
  m_incTriangles.assign(m_incOffsets[nv], 0);
  m_incWeights.assign(m_incOffsets[nv], Eigen::Vector2d::Zero());
  std::vector<int> fill(m_incOffsets.begin(), m_incOffsets.end() - 1);
  for (int t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) {
      const int slot = fill[model.triangles(t, k)]++;
      const StrainConstraint& sc = m_strains[t];
      m_incTriangles[slot] = t;
      m_incWeights[slot] = Eigen::Vector2d(sc.columnWeight(0) * sc.g(k, 0), sc.columnWeight(1) * sc.g(k, 1));
    }
}

Eigen::Matrix<double, 3, 2> PdSystem::deformationGradient(int i, const Eigen::MatrixX3d& x) const {
  const StrainConstraint& sc = m_strains[i];
  Eigen::Matrix3d xs;
  for (int k = 0; k < 3; ++k) xs.row(k) = x.row(sc.vertices[k]);
  return xs.transpose() * sc.g;
}

Eigen::Matrix<double, 3, 2> PdSystem::project(int i, const Eigen::MatrixX3d& x) const {
  return target(i, deformationGradient(i, x));
}

Eigen::Matrix<double, 3, 2> PdSystem::target(int i, const Eigen::Matrix<double, 3, 2>& f) const {
  return strainTarget(m_strains[i], f, m_warp, m_weft, m_shearLimit, m_stretchHoldsShear);
}

void PdSystem::projectRange(const Eigen::MatrixX3d& x, int begin, int end, Eigen::Matrix<double, 3, 2>* out) const {
  strainTargets(m_strains, x, begin, end, m_warp, m_weft, m_shearLimit, m_stretchHoldsShear, out);
}

double PdSystem::strainEnergy(const Eigen::MatrixX3d& x) const {
  double sum = 0.0;
  for (int i = 0; i < triangleCount(); ++i)
    sum += pd::strainEnergy(m_strains[i], deformationGradient(i, x), m_warp, m_weft, m_shearLimit,
                            m_stretchHoldsShear);
  return sum;
}

Eigen::MatrixX3d PdSystem::rhs(const Eigen::MatrixX3d& z,
                               const std::vector<Eigen::Matrix<double, 3, 2>>& targets) const {
  const int nf = freeCount();
  Eigen::MatrixX3d b(nf, 3);
  const double invH2 = 1.0 / (m_h * m_h);
  tbb::parallel_for(tbb::blocked_range<int>(0, nf, 1024), [&](const tbb::blocked_range<int>& range) {
    for (int d = range.begin(); d < range.end(); ++d) {
      const int v = m_freeVertices[d];
      Eigen::Vector3d acc = m_mass[v] * invH2 * z.row(v).transpose();
      for (int k = m_incOffsets[v]; k < m_incOffsets[v + 1]; ++k) {
        const Eigen::Matrix<double, 3, 2>& target = targets[m_incTriangles[k]];
        acc += m_incWeights[k].x() * target.col(0) + m_incWeights[k].y() * target.col(1);
      }
      b.row(d) = acc.transpose();
    }
  });
  if (m_kfp.cols() > 0) b -= m_kfp * m_pinTargets;
  return b;
}

void PdSystem::setPinTargets(const Eigen::MatrixX3d& targets) {
  if (targets.rows() != m_pinTargets.rows())
    throw std::invalid_argument("pd system: " + std::to_string(targets.rows()) + " pin targets for " +
                                std::to_string(m_pinTargets.rows()) + " pins");
  m_pinTargets = targets;
}

}  // namespace drape::pd
