#include "drape/newton/linear_solve.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_reduce.h>

#include <Eigen/CholmodSupport>
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/LU>
#include <cmath>
#include <type_traits>
#include <utility>
#include <vector>

#include "drape/newton/coarse_space.h"
#include "drape/newton/coupled_groups.h"

namespace drape::newton {
namespace {

// ---------------------------------------------------------------------------------------------------------------
// Plain PCG on Eigen vectors (the reference path, and the only one for incomplete Cholesky).

// The factor a warm start's guess g is taken with, from xb = g.b and xax = g.Ag. g's best multiple, the one closest
// to the solution of A x = b in the A-norm, is g.b / g.Ag; it is never further from the solution than 0. The guess
// is taken as it is unless that multiple is below 1/8 (g points against the solution, or is far too long); then it
// is taken with it (0, a cold start, when g.Ag is not positive and finite). Where the garment chatters, the velocity
// change flips from step to step, and the last step's change, the Newton solver's guess, is about minus this step's;
// started from it, the PCG first has to undo it. A guess somewhat too long but right in its smooth part is kept: for
// the block-Jacobi PCG it is a better start than its scaled copy (docs/BENCHMARKS.md, "Findings worth keeping").
double guessScale(double xb, double xax) {
  if (!(xax > 0.0) || !std::isfinite(xax) || !std::isfinite(xb)) return 0.0;
  const double best = xb / xax;
  return best < 0.125 ? best : 1.0;
}

// Preconditioned conjugate gradients from x (warm, scaled by guessScale) or 0; applyA(p, out), applyP(r, out).
// Returns the iterations.
template <typename Vec, typename ApplyA, typename ApplyP>
int pcg(const ApplyA& applyA, const ApplyP& applyP, const Vec& b, Vec& x, double tol, int maxIt, bool warm) {
  using S = typename Vec::Scalar;
  Vec r = b, z(b.size()), ap(b.size());
  if (warm) {
    applyA(x, ap);
    const S scale = static_cast<S>(guessScale(static_cast<double>(x.dot(b)), static_cast<double>(x.dot(ap))));
    x *= scale;
    r -= scale * ap;
  } else {
    x.setZero(b.size());
  }
  double bNorm = static_cast<double>(b.norm());
  if (bNorm == 0.0) {
    x.setZero(b.size());
    return 0;
  }
  if (static_cast<double>(r.norm()) <= tol * bNorm) return 0;
  applyP(r, z);
  Vec p = z;
  S rz = r.dot(z);
  int it = 0;
  while (it < maxIt) {
    applyA(p, ap);
    S pap = p.dot(ap);
    if (!(std::abs(static_cast<double>(pap)) > 0.0)) break;
    S alpha = rz / pap;
    x += alpha * p;
    r -= alpha * ap;
    ++it;
    if (static_cast<double>(r.norm()) <= tol * bNorm) break;
    applyP(r, z);
    S rzNew = r.dot(z);
    p = z + (rzNew / rz) * p;
    rz = rzNew;
  }
  return it;
}

// Inverse 3x3 diagonal blocks (blocks = true) or inverse scalar diagonal of A including dynamic (i, i) entries,
// indexed by storage row (storage = true) or by vertex.
template <typename S>
std::vector<Eigen::Matrix<S, 3, 3>> inverseDiagonal(const BlockMatrix& a, bool blocks, bool storage) {
  const int n = a.numBlocks();
  std::vector<Eigen::Matrix3d> diag(n);
  for (int i = 0; i < n; ++i) diag[i] = a.diagonalBlock(i);
  for (const auto& e : a.dynamicEntries())
    if (e.i == e.j) diag[e.i] += e.block;
  std::vector<Eigen::Matrix<S, 3, 3>> inv(n);
  for (int i = 0; i < n; ++i) {
    Eigen::Matrix3d d = diag[i];
    if (!blocks) d = Eigen::Matrix3d(d.diagonal().asDiagonal());
    Eigen::Matrix3d di = d.inverse();
    if (!di.allFinite()) di = Eigen::Matrix3d::Identity();
    inv[storage ? a.internalIndex(i) : i] = di.cast<S>();
  }
  return inv;
}

template <typename S>
struct BlockPreconditioner {
  std::vector<Eigen::Matrix<S, 3, 3>> inv;
  BlockPreconditioner(const BlockMatrix& a, bool blocks) : inv(inverseDiagonal<S>(a, blocks, false)) {}
  template <typename Vec>
  void operator()(const Vec& r, Vec& z) const {
    for (size_t i = 0; i < inv.size(); ++i) z.template segment<3>(3 * i) = inv[i] * r.template segment<3>(3 * i);
  }
};

// ---------------------------------------------------------------------------------------------------------------
// Fused block PCG in storage order.

constexpr int kRowGrain = 512;  // block rows per TBB chunk (smaller systems run serially)

// Sum over block rows [0, n) of f(begin, end) (a double, or an Eigen::Vector2d for two sums at once), in fixed
// chunks with a deterministic reduction tree so that results do not depend on thread timing.
template <typename T = double, typename F>
T reduceRows(int n, const F& f) {
  if (n <= kRowGrain) return f(0, n);
  T zero;
  if constexpr (std::is_same_v<T, double>)
    zero = 0.0;
  else
    zero = T::Zero();
  return tbb::parallel_deterministic_reduce(
      tbb::blocked_range<int>(0, n, kRowGrain), zero,
      [&f](const tbb::blocked_range<int>& r, T acc) -> T { return acc + f(r.begin(), r.end()); },
      [](const T& u, const T& v) -> T { return u + v; });
}

template <typename F>
void forRows(int n, const F& f) {
  if (n <= kRowGrain) return f(0, n);
  tbb::parallel_for(tbb::blocked_range<int>(0, n, kRowGrain),
                    [&f](const tbb::blocked_range<int>& r) { f(r.begin(), r.end()); });
}

// A static block as the SpMV reads it: the double 3x3 block in place; a float block padded to 4 x 3, so that each
// column is one SIMD packet and y += B x is three packet multiply-adds.
template <typename S>
using StoredBlock = std::conditional_t<std::is_same_v<S, float>, Eigen::Matrix<float, 4, 3>, Eigen::Matrix<S, 3, 3>>;

// B v for a padded float block, v given by its three entries: three packet multiply-adds; row 3 stays 0. Forced
// inline, as applyBlock: GCC otherwise calls these from the PCG's row loops.
[[gnu::always_inline]] inline Eigen::Vector4f paddedProduct(const Eigen::Matrix<float, 4, 3>& b, const float* v) {
  return b.col(0) * v[0] + b.col(1) * v[1] + b.col(2) * v[2];
}

// B v for a stored block.
template <typename S>
[[gnu::always_inline]] inline Eigen::Matrix<S, 3, 1> applyBlock(const StoredBlock<S>& b,
                                                                const Eigen::Matrix<S, 3, 1>& v) {
  if constexpr (std::is_same_v<S, float>)
    return paddedProduct(b, v.data()).template head<3>();
  else
    return b * v;
}

// Copies a 3x3 block into its stored form.
template <typename S>
void storeBlock(const Eigen::Matrix<S, 3, 3>& src, StoredBlock<S>& dst) {
  dst.template topRows<3>() = src;
  if constexpr (std::is_same_v<S, float>) dst.row(3).setZero();
}

// The matrix in storage order with scalar S: static blocks (double ones used in place, float ones copied and
// padded) and the dynamic entries renumbered to storage rows.
template <typename S>
struct StorageMatrix {
  using Mat3 = Eigen::Matrix<S, 3, 3>;
  using Block = StoredBlock<S>;
  using Vec = Eigen::Matrix<S, Eigen::Dynamic, 1>;
  struct Entry {
    int i, j;
    Mat3 block;
  };
  const Block* blocks = nullptr;
  std::vector<Block> copy;  // float blocks when S != double
  const int* rowStart = nullptr;
  const int* cols = nullptr;
  int n = 0;
  std::vector<Entry> dynamic;

  // floatBlocks: where the float copy of the static blocks is kept (filled when fill), nullptr for a local one.
  explicit StorageMatrix(const BlockMatrix& a, std::vector<Block>* floatBlocks = nullptr, bool fill = true)
      : rowStart(a.rowStarts()), cols(a.colIndices()), n(a.numBlocks()) {
    if constexpr (std::is_same_v<S, double>) {
      blocks = a.blocks().data();
    } else {
      std::vector<Block>& dst = floatBlocks ? *floatBlocks : copy;
      if (fill) {
        dst.resize(a.blocks().size());
        const auto& src = a.blocks();
        forRows(n, [&](int r0, int r1) {
          for (int k = rowStart[r0]; k < rowStart[r1]; ++k) storeBlock<S>(src[k].template cast<S>(), dst[k]);
        });
      }
      blocks = dst.data();
    }
    for (const auto& e : a.dynamicEntries())
      dynamic.push_back({a.internalIndex(e.i), a.internalIndex(e.j), e.block.template cast<S>()});
  }

  // y = A x; returns x . y (accumulated in double).
  double multiplyDot(const Vec& x, Vec& y) const {
    double dot = reduceRows<double>(n, [&](int r0, int r1) {
      double acc = 0.0;
      for (int r = r0; r < r1; ++r) {
        Eigen::Matrix<S, 3, 1> s;
        if constexpr (std::is_same_v<S, float>) {
          Eigen::Vector4f s4 = Eigen::Vector4f::Zero();
          for (int k = rowStart[r]; k < rowStart[r + 1]; ++k) s4 += paddedProduct(blocks[k], x.data() + 3 * cols[k]);
          s = s4.head<3>();
        } else {
          s.setZero();
          for (int k = rowStart[r]; k < rowStart[r + 1]; ++k)
            s.noalias() += blocks[k] * x.template segment<3>(3 * cols[k]);
        }
        y.template segment<3>(3 * r) = s;
        acc += static_cast<double>(x.template segment<3>(3 * r).dot(s));
      }
      return acc;
    });
    for (const auto& e : dynamic) {
      const Eigen::Matrix<S, 3, 1> bij = e.block * x.template segment<3>(3 * e.j);
      y.template segment<3>(3 * e.i) += bij;
      dot += static_cast<double>(x.template segment<3>(3 * e.i).dot(bij));
      if (e.i != e.j) {
        const Eigen::Matrix<S, 3, 1> bji = e.block.transpose() * x.template segment<3>(3 * e.i);
        y.template segment<3>(3 * e.j) += bji;
        dot += static_cast<double>(x.template segment<3>(3 * e.j).dot(bji));
      }
    }
    return dot;
  }
};

// The coarse correction of the two-level preconditioner on storage-ordered vectors: e = P (P^T A P)^-1 P^T r,
// kept per aggregate (3m) and added to the block-Jacobi z where z is used.
template <typename S>
struct CoarseCorrection {
  const CoarseSpace* space = nullptr;
  Eigen::VectorXd rc, ec;
  Eigen::Matrix<S, Eigen::Dynamic, 1> e;  // ec in S

  explicit CoarseCorrection(const CoarseSpace* coarse) : space(coarse && coarse->ready() ? coarse : nullptr) {}
  // Computes the correction for residual r (storage order); returns r . P ec (the correction's share of r . z).
  double update(const Eigen::Matrix<S, Eigen::Dynamic, 1>& r, int n) {
    rc.setZero(3 * space->numAggregates());
    restrictAdd(r, 1.0, n);
    return solve();
  }
  // The same for r - alpha q, with r the residual of the last update or advance: rc follows r's recurrence, so this
  // needs only q, and can run while r itself is being updated.
  double advance(const Eigen::Matrix<S, Eigen::Dynamic, 1>& q, double alpha, int n) {
    restrictAdd(q, -alpha, n);
    return solve();
  }
  Eigen::Matrix<S, 3, 1> at(int row) const { return e.template segment<3>(3 * space->aggregateOfRow()[row]); }

 private:
  void restrictAdd(const Eigen::Matrix<S, Eigen::Dynamic, 1>& v, double c, int n) {
    const std::vector<int>& agg = space->aggregateOfRow();
    for (int i = 0; i < n; ++i) rc.segment<3>(3 * agg[i]) += c * v.template segment<3>(3 * i).template cast<double>();
  }
  double solve() {
    space->solve(rc, ec);
    e = ec.cast<S>();
    return rc.dot(ec);
  }
};

// PCG on storage-ordered vectors; x in/out (initial guess when warm). Returns the iteration count. coarse: the
// two-level correction added to z = inv r (nullptr or not ready: one level); groups: rows whose z comes from their
// group's inverse instead of inv (nullptr: none).
template <typename S>
int fusedPcg(const StorageMatrix<S>& a, const std::vector<StoredBlock<S>>& inv,
             const Eigen::Matrix<S, Eigen::Dynamic, 1>& b, Eigen::Matrix<S, Eigen::Dynamic, 1>& x, double tol,
             int maxIt, bool warm, const CoarseSpace* coarse, const CoupledGroups* groups) {
  using Vec = Eigen::Matrix<S, Eigen::Dynamic, 1>;
  const int n = a.n;
  CoarseCorrection<S> cc(coarse);
  Vec r(b.size()), z(b.size()), p(b.size()), ap(b.size());
  const double bNorm2 = reduceRows<double>(
      n, [&](int r0, int r1) { return static_cast<double>(b.segment(3 * r0, 3 * (r1 - r0)).squaredNorm()); });
  if (bNorm2 == 0.0 || !warm) x.setZero(b.size());
  if (bNorm2 == 0.0) return 0;
  const double stop2 = tol * tol * bNorm2;
  // The guess as it is, or its best multiple when that is below 1/8 (guessScale).
  S scale = 0;
  if (warm) {
    const double xax = a.multiplyDot(x, ap);
    const double xb = reduceRows<double>(n, [&](int r0, int r1) {
      return static_cast<double>(x.segment(3 * r0, 3 * (r1 - r0)).dot(b.segment(3 * r0, 3 * (r1 - r0))));
    });
    scale = static_cast<S>(guessScale(xb, xax));
  }
  // x = scale x, r = b - A x, z = P r, p = z; (r.z, r.r).
  Eigen::Vector2d sums = reduceRows<Eigen::Vector2d>(n, [&](int r0, int r1) {
    Eigen::Vector2d acc = Eigen::Vector2d::Zero();
    for (int i = r0; i < r1; ++i) {
      Eigen::Matrix<S, 3, 1> ri = b.template segment<3>(3 * i);
      if (warm) {
        x.template segment<3>(3 * i) *= scale;
        ri -= scale * ap.template segment<3>(3 * i);
      }
      const Eigen::Matrix<S, 3, 1> zi = applyBlock<S>(inv[i], ri);
      r.template segment<3>(3 * i) = ri;
      z.template segment<3>(3 * i) = zi;
      p.template segment<3>(3 * i) = zi;
      acc += Eigen::Vector2d(static_cast<double>(ri.dot(zi)), static_cast<double>(ri.squaredNorm()));
    }
    return acc;
  });
  double rz = sums(0);
  if (sums(1) <= stop2) return 0;
  if (groups) {
    rz += groups->apply<S>(r, z);
    p = z;
  }
  if (cc.space) {
    rz += cc.update(r, n);
    forRows(n, [&](int r0, int r1) {
      for (int i = r0; i < r1; ++i) p.template segment<3>(3 * i) += cc.at(i);
    });
  }
  int it = 0;
  while (it < maxIt) {
    const double pap = a.multiplyDot(p, ap);
    if (!(std::abs(pap) > 0.0) || !std::isfinite(pap)) break;
    const S alpha = static_cast<S>(rz / pap);
    // x += alpha p, r -= alpha Ap, z = P r; (r.z, r.r) in the same pass. The coarse solve (one thread) runs at the
    // same time on the restriction of Ap.
    double coarseDot = 0.0;
    auto pass = [&] {
      sums = reduceRows<Eigen::Vector2d>(n, [&](int r0, int r1) {
        Eigen::Vector2d acc = Eigen::Vector2d::Zero();
        for (int i = r0; i < r1; ++i) {
          x.template segment<3>(3 * i) += alpha * p.template segment<3>(3 * i);
          const Eigen::Matrix<S, 3, 1> ri = r.template segment<3>(3 * i) - alpha * ap.template segment<3>(3 * i);
          const Eigen::Matrix<S, 3, 1> zi = applyBlock<S>(inv[i], ri);
          r.template segment<3>(3 * i) = ri;
          z.template segment<3>(3 * i) = zi;
          acc += Eigen::Vector2d(static_cast<double>(ri.dot(zi)), static_cast<double>(ri.squaredNorm()));
        }
        return acc;
      });
    };
    if (cc.space)
      tbb::parallel_invoke([&] { coarseDot = cc.advance(ap, static_cast<double>(alpha), n); }, pass);
    else
      pass();
    double rzNew = sums(0);
    if (groups) rzNew += groups->apply<S>(r, z);
    ++it;
    if (sums(1) <= stop2) break;
    if (cc.space) {
      rzNew += coarseDot;
      const S beta = static_cast<S>(rzNew / rz);
      forRows(n, [&](int r0, int r1) {
        for (int i = r0; i < r1; ++i)
          p.template segment<3>(3 * i) = z.template segment<3>(3 * i) + cc.at(i) + beta * p.template segment<3>(3 * i);
      });
    } else {
      const S beta = static_cast<S>(rzNew / rz);
      forRows(n, [&](int r0, int r1) {
        for (int i = 3 * r0; i < 3 * r1; ++i) p[i] = z[i] + beta * p[i];
      });
    }
    rz = rzNew;
  }
  return it;
}

template <typename S>
LinearSolveResult fusedSolve(const BlockMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                             const LinearSolveOptions& options, bool warm) {
  using Vec = Eigen::Matrix<S, Eigen::Dynamic, 1>;
  using Mat3 = Eigen::Matrix<S, 3, 3>;
  constexpr bool isFloat = std::is_same_v<S, float>;
  LinearSolveResult result;
  // The preparation (inverse diagonal blocks, float copy) comes from the cache while the matrix is unchanged.
  PcgCache* cache = a.dynamicEntries().empty() ? options.cache : nullptr;
  std::vector<StoredBlock<S>> local;
  std::vector<StoredBlock<S>>* invStore = &local;
  std::vector<StoredBlock<S>>* floatBlocks = nullptr;
  if (cache) {
    if constexpr (isFloat) {
      invStore = &cache->inverseFloat;
      floatBlocks = &cache->blocksFloat;
    } else {
      invStore = &cache->inverse;
    }
  }
  const bool cached = cache && cache->valid && cache->preconditioner == options.preconditioner &&
                      cache->mixed == isFloat && invStore->size() == size_t(a.numBlocks());
  if (!cached) {
    std::vector<Mat3> inverse;
    if (options.preconditioner == Preconditioner::None)
      inverse.assign(a.numBlocks(), Mat3::Identity());
    else
      inverse = inverseDiagonal<S>(a, options.preconditioner == Preconditioner::BlockJacobi, true);
    if constexpr (isFloat) {
      invStore->resize(inverse.size());
      for (size_t i = 0; i < inverse.size(); ++i) storeBlock<S>(inverse[i], (*invStore)[i]);
    } else {
      *invStore = std::move(inverse);  // the stored double block is the 3x3 block itself
    }
  }
  Eigen::VectorXd bi, xi;
  a.toInternal(b, bi);
  if (warm) a.toInternal(x, xi);
  StorageMatrix<S> m(a, floatBlocks, !cached);
  if (cache) {
    cache->valid = true;
    cache->preconditioner = options.preconditioner;
    cache->mixed = isFloat;
  }
  const std::vector<StoredBlock<S>>& inv = *invStore;
  Vec bs = bi.cast<S>(), xs;
  if (warm) xs = xi.cast<S>();
  const CoupledGroups* coupled = options.preconditioner == Preconditioner::BlockJacobi ? options.coupled : nullptr;
  result.iterations = fusedPcg<S>(m, inv, bs, xs, options.tolerance, options.maxIterations, warm, options.coarse,
                                  coupled && !coupled->empty() ? coupled : nullptr);
  xi = xs.template cast<double>();
  if (!xi.allFinite()) return result;
  if (options.trueResidual) {
    // True residual in double precision.
    StorageMatrix<double> md(a);
    Eigen::VectorXd axi(xi.size());
    md.multiplyDot(xi, axi);
    const double bNorm = bi.norm();
    result.relativeResidual = bNorm > 0.0 ? (axi - bi).norm() / bNorm : 0.0;
  } else {
    result.relativeResidual = -1.0;
  }
  a.toOriginal(xi, x);
  result.ok = true;
  return result;
}

LinearSolveResult plainSolve(const BlockMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                             const LinearSolveOptions& options, bool warm) {
  LinearSolveResult result;
  const double tol = options.tolerance;
  const int maxIt = options.maxIterations;
  if (options.mixedPrecision) {
    Eigen::SparseMatrix<float, Eigen::RowMajor> s = a.toSparse().cast<float>();
    Eigen::VectorXf bf = b.cast<float>(), xf;
    if (warm) xf = x.cast<float>();
    auto applyA = [&s](const Eigen::VectorXf& p, Eigen::VectorXf& out) { out.noalias() = s * p; };
    if (options.preconditioner == Preconditioner::IncompleteCholesky) {
      Eigen::SparseMatrix<float> sc = s;
      Eigen::IncompleteCholesky<float> ic(sc);
      auto applyP = [&ic](const Eigen::VectorXf& r, Eigen::VectorXf& z) { z = ic.solve(r); };
      result.iterations = pcg(applyA, applyP, bf, xf, tol, maxIt, warm);
    } else if (options.preconditioner == Preconditioner::None) {
      auto identity = [](const Eigen::VectorXf& r, Eigen::VectorXf& z) { z = r; };
      result.iterations = pcg(applyA, identity, bf, xf, tol, maxIt, warm);
    } else {
      BlockPreconditioner<float> pre(a, options.preconditioner == Preconditioner::BlockJacobi);
      result.iterations = pcg(applyA, pre, bf, xf, tol, maxIt, warm);
    }
    x = xf.cast<double>();
  } else {
    auto applyA = [&a](const Eigen::VectorXd& p, Eigen::VectorXd& out) { a.multiply(p, out); };
    if (options.preconditioner != Preconditioner::IncompleteCholesky && a.reordered()) {
      // Storage (RCM) order: permute once, SpMV over contiguous block rows.
      StorageMatrix<double> m(a);
      auto applyStorage = [&m](const Eigen::VectorXd& p, Eigen::VectorXd& out) {
        out.resize(p.size());
        m.multiplyDot(p, out);
      };
      Eigen::VectorXd bi, xi;
      a.toInternal(b, bi);
      if (warm) a.toInternal(x, xi);
      if (options.preconditioner == Preconditioner::None) {
        auto identity = [](const Eigen::VectorXd& r, Eigen::VectorXd& z) { z = r; };
        result.iterations = pcg(applyStorage, identity, bi, xi, tol, maxIt, warm);
      } else {
        BlockPreconditioner<double> pre(a, options.preconditioner == Preconditioner::BlockJacobi);
        pre.inv = inverseDiagonal<double>(a, options.preconditioner == Preconditioner::BlockJacobi, true);
        result.iterations = pcg(applyStorage, pre, bi, xi, tol, maxIt, warm);
      }
      a.toOriginal(xi, x);
    } else if (options.preconditioner == Preconditioner::IncompleteCholesky) {
      Eigen::SparseMatrix<double> s = a.toSparse();
      Eigen::IncompleteCholesky<double> ic(s);
      auto applyP = [&ic](const Eigen::VectorXd& r, Eigen::VectorXd& z) { z = ic.solve(r); };
      result.iterations = pcg(applyA, applyP, b, x, tol, maxIt, warm);
    } else if (options.preconditioner == Preconditioner::None) {
      auto identity = [](const Eigen::VectorXd& r, Eigen::VectorXd& z) { z = r; };
      result.iterations = pcg(applyA, identity, b, x, tol, maxIt, warm);
    } else {
      BlockPreconditioner<double> pre(a, options.preconditioner == Preconditioner::BlockJacobi);
      result.iterations = pcg(applyA, pre, b, x, tol, maxIt, warm);
    }
  }
  if (!x.allFinite()) return result;
  double bNorm = b.norm();
  result.relativeResidual = bNorm > 0.0 ? (a * x - b).norm() / bNorm : 0.0;
  result.ok = true;
  return result;
}

}  // namespace

LinearSolveResult solveLinear(const BlockMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                              const LinearSolveOptions& options) {
  const bool warm = options.warmStart && x.size() == b.size() && x.allFinite();
  if (options.kind == LinearSolverKind::Cholmod) {
    LinearSolveResult result;
    Eigen::SparseMatrix<double> s = a.toSparse();
    Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>> chol(s);
    if (chol.info() != Eigen::Success) return result;
    x = chol.solve(b);
    if (!x.allFinite()) return result;
    const double bNorm = b.norm();
    result.relativeResidual = bNorm > 0.0 ? (a * x - b).norm() / bNorm : 0.0;
    result.ok = true;
    return result;
  }
  if (!options.fusedKernels || options.preconditioner == Preconditioner::IncompleteCholesky)
    return plainSolve(a, b, x, options, warm);
  return options.mixedPrecision ? fusedSolve<float>(a, b, x, options, warm)
                                : fusedSolve<double>(a, b, x, options, warm);
}

}  // namespace drape::newton
