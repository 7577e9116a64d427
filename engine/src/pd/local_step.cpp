#include "drape/pd/local_step.h"

#include <algorithm>
#include <random>
#include <tbb/parallel_for.h>
#include <unordered_map>

namespace drape::pd {

LocalStep::LocalStep(const PdSystem& system, const std::vector<int>& triangleDomain, int domains, int orders,
                     unsigned seed)
    : m_system(system), m_orders(std::max(orders, 1)) {
  const int nt = system.triangleCount();
  m_domains.resize(std::max(domains, 1));
  for (int t = 0; t < nt; ++t) m_domains[triangleDomain[t]].triangles.push_back(t);
  const auto& dofOf = system.dofOfVertex();
  const Eigen::SparseMatrix<double>& k = system.matrix();
  const auto& freeVertices = system.freeVertices();

  tbb::parallel_for(0, static_cast<int>(m_domains.size()), [&](int j) {
    Domain& dom = m_domains[j];
    for (int t : dom.triangles)
      for (int c = 0; c < 3; ++c) dom.vertices.push_back(system.triangles()(t, c));
    std::sort(dom.vertices.begin(), dom.vertices.end());
    dom.vertices.erase(std::unique(dom.vertices.begin(), dom.vertices.end()), dom.vertices.end());
    auto localOf = [&](int v) {
      const auto it = std::lower_bound(dom.vertices.begin(), dom.vertices.end(), v);
      return (it != dom.vertices.end() && *it == v) ? static_cast<int>(it - dom.vertices.begin()) : -1;
    };
    const int nl = static_cast<int>(dom.vertices.size());
    const int ntl = static_cast<int>(dom.triangles.size());
    dom.local.resize(ntl);
    for (int i = 0; i < ntl; ++i)
      for (int c = 0; c < 3; ++c) dom.local[i][c] = localOf(system.triangles()(dom.triangles[i], c));

    // K rows of the local free vertices.
    dom.freeDof.resize(nl);
    dom.rowOffsets.assign(nl + 1, 0);
    dom.diagonal.assign(nl, 1.0);
    std::unordered_map<int, int> ghostOf;  // global vertex -> local index of its ghost
    for (int l = 0; l < nl; ++l) {
      const int d = dofOf[dom.vertices[l]];
      dom.freeDof[l] = d;
      if (d >= 0)
        for (Eigen::SparseMatrix<double>::InnerIterator it(k, d); it; ++it) {
          const int u = freeVertices[it.row()];
          if (u == dom.vertices[l]) {
            dom.diagonal[l] = it.value();
            continue;
          }
          int lu = localOf(u);
          if (lu < 0) {
            const auto [g, added] = ghostOf.try_emplace(u, nl + static_cast<int>(dom.ghosts.size()));
            if (added) dom.ghosts.push_back(u);
            lu = g->second;
          }
          dom.rowNeighbour.push_back(lu);
          dom.rowValue.push_back(it.value());
        }
      dom.rowOffsets[l + 1] = static_cast<int>(dom.rowNeighbour.size());
    }

    // Constraint graph: local triangles sharing a vertex.
    std::vector<std::vector<int>> vertexTris(nl);
    for (int i = 0; i < ntl; ++i)
      for (int c = 0; c < 3; ++c) vertexTris[dom.local[i][c]].push_back(i);
    std::vector<int> starts;  // triangles with a pinned vertex first
    for (int i = 0; i < ntl; ++i)
      for (int c = 0; c < 3; ++c)
        if (dom.freeDof[dom.local[i][c]] < 0) {
          starts.push_back(i);
          break;
        }
    std::mt19937 rng(seed * 7919u + static_cast<unsigned>(j) * 104729u + 1u);
    dom.orders.resize(m_orders);
    for (int o = 0; o < m_orders; ++o) {
      std::vector<char> seen(ntl, 0);
      std::vector<int>& order = dom.orders[o];
      order.reserve(ntl);
      std::vector<int> roots = starts;
      std::shuffle(roots.begin(), roots.end(), rng);
      std::vector<int> rest(ntl);
      for (int i = 0; i < ntl; ++i) rest[i] = i;
      std::shuffle(rest.begin(), rest.end(), rng);
      roots.insert(roots.end(), rest.begin(), rest.end());
      std::vector<int> stack, neighbours;
      for (int root : roots) {
        if (seen[root]) continue;
        stack.push_back(root);
        while (!stack.empty()) {
          const int t = stack.back();
          stack.pop_back();
          if (seen[t]) continue;
          seen[t] = 1;
          order.push_back(t);  // DFS preorder of the random spanning (DFS) tree
          neighbours.clear();
          for (int c = 0; c < 3; ++c)
            for (int u : vertexTris[dom.local[t][c]])
              if (!seen[u]) neighbours.push_back(u);
          std::shuffle(neighbours.begin(), neighbours.end(), rng);
          stack.insert(stack.end(), neighbours.begin(), neighbours.end());
        }
      }
    }
  });
}

std::vector<int> LocalStep::order(int j, int o) const {
  std::vector<int> out;
  for (int i : m_domains[j].orders[o]) out.push_back(m_domains[j].triangles[i]);
  return out;
}

void LocalStep::jacobi(const Eigen::MatrixX3d& x, std::vector<StrainTarget>& targets) const {
  const int nt = m_system.triangleCount();
  targets.resize(nt);
  tbb::parallel_for(tbb::blocked_range<int>(0, nt, 2048), [&](const tbb::blocked_range<int>& r) {
    m_system.projectRange(x, r.begin(), r.end(), targets.data() + r.begin());
  });
}

void LocalStep::gaussSeidel(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& b, int iteration,
                            std::vector<StrainTarget>& targets) const {
  const auto& strains = m_system.strains();
  tbb::parallel_for(0, static_cast<int>(m_domains.size()), [&](int j) {
    const Domain& dom = m_domains[j];
    const int nl = static_cast<int>(dom.vertices.size());
    if (dom.triangles.empty()) return;
    thread_local Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> xl, bl;
    const int ng = static_cast<int>(dom.ghosts.size());
    xl.resize(nl + ng, 3);
    bl.resize(nl, 3);
    for (int l = 0; l < nl; ++l) {
      xl.row(l) = x.row(dom.vertices[l]);
      if (dom.freeDof[l] >= 0) bl.row(l) = b.row(dom.freeDof[l]);
    }
    for (int g = 0; g < ng; ++g) xl.row(nl + g) = x.row(dom.ghosts[g]);  // not moved by this sweep
    const std::vector<int>& order = dom.orders[iteration % m_orders];
    const int count = static_cast<int>(order.size());
    for (int pass = 0; pass < 2 * count; ++pass) {
      // Symmetric Gauss-Seidel: forward along the DFS order (away from the pins), then back along it.
      const int i = order[pass < count ? pass : 2 * count - 1 - pass];
      const int t = dom.triangles[i];
      const StrainConstraint& sc = strains[t];
      const auto& lv = dom.local[i];
      Eigen::Matrix3d xs;
      for (int c = 0; c < 3; ++c) xs.row(c) = xl.row(lv[c]);
      const StrainTarget target = m_system.target(t, xs.transpose() * sc.g);
      const StrainTarget delta = target - targets[t];
      targets[t] = target;
      for (int c = 0; c < 3; ++c) {
        const int l = lv[c];
        if (dom.freeDof[l] < 0) continue;
        bl.row(l) += (sc.columnWeight(0) * sc.g(c, 0) * delta.col(0) + sc.columnWeight(1) * sc.g(c, 1) * delta.col(1))
                         .transpose();
      }
      // Relax the triangle's free vertices: one Gauss-Seidel update of K x = b each (consistent: a fixed point
      // of the L-G iteration is left unchanged).
      for (int c = 0; c < 3; ++c) {
        const int l = lv[c];
        if (dom.freeDof[l] < 0) continue;
        Eigen::RowVector3d acc = bl.row(l);
        for (int e = dom.rowOffsets[l]; e < dom.rowOffsets[l + 1]; ++e)
          acc -= dom.rowValue[e] * xl.row(dom.rowNeighbour[e]);
        xl.row(l) = acc / dom.diagonal[l];
      }
    }
  });
}

}  // namespace drape::pd
