#include "drape/pd/domain_partition.h"

#include <algorithm>
#include <map>
#include <metis.h>

#include "drape/pd/pd_system.h"

namespace drape::pd {

std::vector<int> partitionTriangles(const Eigen::MatrixX3i& triangles, int vertexCount,
                                    const std::vector<std::pair<int, int>>& stitches, int domains,
                                    unsigned seed) {
  return partitionTriangles(triangles, vertexCount, stitches, {}, domains, seed);
}

std::vector<int> partitionTriangles(const Eigen::MatrixX3i& triangles, int vertexCount,
                                    const std::vector<std::pair<int, int>>& stitches,
                                    const std::vector<model::EdgeStitch>& edgeStitches, int domains,
                                    unsigned seed) {
  const int nt = static_cast<int>(triangles.rows());
  std::vector<int> part(nt, 0);
  domains = std::clamp(domains, 1, std::max(nt, 1));
  if (domains <= 1 || nt == 0) return part;

  // Adjacency: triangles sharing an edge, and triangles touching the two ends of a stitch.
  std::vector<std::vector<int>> adj(nt);
  auto link = [&adj](int s, int t) {
    if (s >= 0 && t >= 0 && s != t) {
      adj[s].push_back(t);
      adj[t].push_back(s);
    }
  };
  std::map<std::pair<int, int>, int> firstOnEdge;
  std::map<std::pair<int, int>, int> secondOnEdge;  // only filled when edge stitches need it
  for (int t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = triangles(t, k), b = triangles(t, (k + 1) % 3);
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      const auto [it, inserted] = firstOnEdge.emplace(key, t);
      if (!inserted && it->second != t) {
        link(t, it->second);
        if (!edgeStitches.empty()) secondOnEdge.emplace(key, t);
      }
    }
  if (!stitches.empty() || !edgeStitches.empty()) {
    std::vector<int> someTriangle(vertexCount, -1);
    for (int t = 0; t < nt; ++t)
      for (int k = 0; k < 3; ++k) someTriangle[triangles(t, k)] = t;
    for (const auto& [a, b] : stitches) link(someTriangle[a], someTriangle[b]);
    for (const model::EdgeStitch& e : edgeStitches) {
      const int tv = someTriangle[e.vertex];
      const auto key = std::make_pair(std::min(e.a, e.b), std::max(e.a, e.b));
      const auto first = firstOnEdge.find(key);
      if (first == firstOnEdge.end()) {
        link(tv, someTriangle[e.a]);
        link(tv, someTriangle[e.b]);
        continue;
      }
      link(tv, first->second);
      const auto second = secondOnEdge.find(key);
      if (second != secondOnEdge.end()) link(tv, second->second);
    }
  }
  std::vector<idx_t> xadj(nt + 1, 0), adjncy;
  for (int t = 0; t < nt; ++t) {
    std::sort(adj[t].begin(), adj[t].end());
    adj[t].erase(std::unique(adj[t].begin(), adj[t].end()), adj[t].end());
    for (int u : adj[t]) adjncy.push_back(u);
    xadj[t + 1] = static_cast<idx_t>(adjncy.size());
  }
  if (adjncy.empty()) {  // no edges at all: round robin
    for (int t = 0; t < nt; ++t) part[t] = t % domains;
    return part;
  }
  idx_t nvtxs = nt, ncon = 1, nparts = domains, objval = 0;
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_SEED] = static_cast<idx_t>(seed);
  options[METIS_OPTION_NUMBERING] = 0;
  std::vector<idx_t> metisPart(nt, 0);
  const int status = METIS_PartGraphKway(&nvtxs, &ncon, xadj.data(), adjncy.data(), nullptr, nullptr, nullptr,
                                         &nparts, nullptr, nullptr, options, &objval, metisPart.data());
  if (status != METIS_OK) {
    // Fallback: contiguous blocks in index order (still a valid, if worse, decomposition).
    for (int t = 0; t < nt; ++t) part[t] = static_cast<int>(static_cast<long long>(t) * domains / nt);
    return part;
  }
  for (int t = 0; t < nt; ++t) part[t] = static_cast<int>(metisPart[t]);
  return part;
}

std::vector<DomainMatrix> splitSystem(const PdSystem& system, const std::vector<int>& triangleDomain,
                                      int domains) {
  const auto& dofOf = system.dofOfVertex();
  const int nf = system.freeCount();
  // Which domains hold each free DOF.
  std::vector<std::vector<int>> holders(nf);
  auto hold = [&](int dof, int j) {
    auto& h = holders[dof];
    if (std::find(h.begin(), h.end(), j) == h.end()) h.push_back(j);
  };
  for (const Stencil& st : system.stencils()) {
    const int j = triangleDomain[st.ownerTriangle];
    for (int i = 0; i < st.size; ++i)
      if (dofOf[st.vertices[i]] >= 0) hold(dofOf[st.vertices[i]], j);
  }
  for (int d = 0; d < nf; ++d)
    if (holders[d].empty()) holders[d].push_back(0);

  std::vector<DomainMatrix> out(domains);
  // localIndex[d][k]: local index of DOF d in domain holders[d][k].
  std::vector<std::vector<int>> localIndex(nf);
  for (int d = 0; d < nf; ++d)
    for (int j : holders[d]) {
      localIndex[d].push_back(static_cast<int>(out[j].dofs.size()));
      out[j].dofs.push_back(d);  // increasing d
    }
  auto localOf = [&](int d, int j) {
    const auto& h = holders[d];
    return localIndex[d][std::find(h.begin(), h.end(), j) - h.begin()];
  };
  std::vector<std::vector<Eigen::Triplet<double>>> trip(domains);
  const double invH2 = 1.0 / (system.timeStep() * system.timeStep());
  for (int d = 0; d < nf; ++d) {
    const double m = system.masses()[system.freeVertices()[d]] * invH2 / static_cast<double>(holders[d].size());
    for (size_t k = 0; k < holders[d].size(); ++k)
      trip[holders[d][k]].emplace_back(localIndex[d][k], localIndex[d][k], m);
  }
  for (const Stencil& st : system.stencils()) {
    const int j = triangleDomain[st.ownerTriangle];
    for (int a = 0; a < st.size; ++a) {
      const int da = dofOf[st.vertices[a]];
      if (da < 0) continue;
      const int la = localOf(da, j);
      for (int b = 0; b < st.size; ++b) {
        const int db = dofOf[st.vertices[b]];
        if (db >= 0) trip[j].emplace_back(la, localOf(db, j), st.q(a, b));
      }
    }
  }
  for (int j = 0; j < domains; ++j) {
    const int n = static_cast<int>(out[j].dofs.size());
    out[j].k.resize(n, n);
    out[j].k.setFromTriplets(trip[j].begin(), trip[j].end());
  }
  return out;
}

}  // namespace drape::pd
