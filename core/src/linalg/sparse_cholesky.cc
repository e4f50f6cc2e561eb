#include "femup/core/linalg/sparse_cholesky.h"

#include <cholmod.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <mutex>
#include <numeric>

#include "femup/core/errors.h"
#include "femup/core/linalg/dense_kernels.h"
#include "femup/core/parallel.h"
#include "linalg/group_ordering.h"

namespace femup {
namespace {

// Blocks of columns a sparse half-solve is split into, for its threads.
constexpr int kHalfSolveBlocks = 32;
// L's dense tail is solved by blocks where it has at least this many columns.
constexpr int kDenseTailMin = 32;

double Since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// A CHOLMOD view (no copy) of the lower triangle held in `lower`.
cholmod_sparse ViewLower(SparseMatrix& lower) {
  return internal::CholmodLowerView(static_cast<int>(lower.rows()), lower.outerIndexPtr(),
                                    lower.innerIndexPtr(), lower.valuePtr());
}

// Forward substitution x <- L^-1 x on the reach (its `size` columns in
// topological order, L's diagonal entry first in each column) for `count`
// right-hand sides held row-major in x (the count values of a row together).
// kCount > 0 fixes the count at compile time, so that the compiler unrolls and
// vectorises the row updates; each value takes the same operations in the
// same order either way (the bits do not depend on it).
template <int kCount>
void SubstituteOnReachFixed(int dynamic_count, const int* reach, int size, const int* lp,
                            const int* li, const double* lx, double* x) {
  const std::size_t count = kCount > 0 ? static_cast<std::size_t>(kCount)
                                       : static_cast<std::size_t>(dynamic_count);
  for (int p = 0; p < size; ++p) {
    const int c = reach[p];
    double* xc = x + static_cast<std::size_t>(c) * count;
    const double diagonal = lx[lp[c]];
    for (std::size_t j = 0; j < count; ++j) xc[j] /= diagonal;
    for (int q = lp[c] + 1; q < lp[c + 1]; ++q) {
      double* xr = x + static_cast<std::size_t>(li[q]) * count;
      const double v = lx[q];
      for (std::size_t j = 0; j < count; ++j) xr[j] -= v * xc[j];
    }
  }
}

void SubstituteOnReach(int count, const int* reach, int size, const int* lp,
                       const int* li, const double* lx, double* x) {
  switch (count) {
    case 1:
      return SubstituteOnReachFixed<1>(count, reach, size, lp, li, lx, x);
    case 2:
      return SubstituteOnReachFixed<2>(count, reach, size, lp, li, lx, x);
    case 3:
      return SubstituteOnReachFixed<3>(count, reach, size, lp, li, lx, x);
    case 4:
      return SubstituteOnReachFixed<4>(count, reach, size, lp, li, lx, x);
    case 5:
      return SubstituteOnReachFixed<5>(count, reach, size, lp, li, lx, x);
    case 6:
      return SubstituteOnReachFixed<6>(count, reach, size, lp, li, lx, x);
    case 8:
      return SubstituteOnReachFixed<8>(count, reach, size, lp, li, lx, x);
    case 10:
      return SubstituteOnReachFixed<10>(count, reach, size, lp, li, lx, x);
    default:
      return SubstituteOnReachFixed<0>(count, reach, size, lp, li, lx, x);
  }
}

}  // namespace

struct SparseCholesky::Impl {
  cholmod_common common{};
  cholmod_factor* factor = nullptr;  // simplicial LL', packed, monotonic
  std::vector<int> perm;             // row i of P A P' is row perm[i] of A
  std::vector<int> inverse;          // inverse[perm[i]] = i
  SparseCholeskyInfo info;
  int threads = 0;  // of the sparse half-solve (0: one per core)
  // The elimination tree: the parent of column c is the first row below the
  // diagonal in L's column c (-1 at a root). A column's reach in L is the set
  // of the tree's ancestors of its right-hand side's rows (Gilbert), and
  // ascending order is a topological order of it (L is lower triangular), so
  // the half solve finds the reach by walking up the tree and substitutes in
  // the order it outputs.
  std::vector<int> parent;
  // L's dense tail: its last `tail` columns form a full lower triangle (the
  // top separator of the nested dissection, a chain in the elimination tree),
  // copied dense into tail_l (tail x tail, lower triangle); 0 when shorter
  // than kDenseTailMin. A column's reach holds a last part of it (from the
  // first tail column it reaches to the end), or none of it; no other column
  // of the reach depends on a tail column. The half solve runs the tail's
  // substitution for all the columns of a block at once, by the BLAS's
  // triangular solve (dtrsm): the same operations as column by column, in
  // blocked order.
  int tail = 0;
  Eigen::MatrixXd tail_l;

  ~Impl() {
    if (factor != nullptr) cholmod_free_factor(&factor, &common);
    cholmod_finish(&common);
  }

  int n() const { return static_cast<int>(info.n); }
  int* lp() const { return static_cast<int*>(factor->p); }
  int* li() const { return static_cast<int*>(factor->i); }
  double* lx() const { return static_cast<double*>(factor->x); }

  Eigen::Map<const SparseMatrix> L() const {
    return Eigen::Map<const SparseMatrix>(n(), n(), lp()[n()], lp(), li(), lx());
  }
};

SparseCholesky::SparseCholesky(const SparseMatrix& a,
                               const SparseCholeskyOptions& options)
    : impl_(std::make_unique<Impl>()) {
  const std::string& name = options.name;
  if (a.rows() != a.cols()) {
    throw InputError(name, "must be square, got " + std::to_string(a.rows()) + " x " +
                               std::to_string(a.cols()));
  }
  SparseMatrix lower = a.triangularView<Eigen::Lower>();
  lower.makeCompressed();
  for (Eigen::Index k = 0; k < lower.nonZeros(); ++k) {
    if (!std::isfinite(lower.valuePtr()[k])) {
      throw InputError(name, "holds a non-finite entry");
    }
  }
  if (options.threads < 0) {
    throw InputError(name, "threads must be >= 0 (0 = one per core), got " +
                               std::to_string(options.threads));
  }
  if (!options.groups.empty() &&
      (options.groups.size() != static_cast<std::size_t>(a.rows()) ||
       *std::min_element(options.groups.begin(), options.groups.end()) < 0)) {
    throw InputError(name, "groups must be empty or one index >= 0 per row (" +
                               std::to_string(a.rows()) + "), got " +
                               std::to_string(options.groups.size()) + " entries");
  }
  Impl& m = *impl_;
  m.threads = options.threads;
  m.info.n = a.rows();
  m.info.nnz_a = lower.nonZeros();
  cholmod_start(&m.common);
  m.common.print = 0;
  m.common.error_handler = nullptr;
  m.common.final_ll = 1;
  switch (options.ordering) {
    case SparseCholeskyOptions::Ordering::kAuto:
      break;
    case SparseCholeskyOptions::Ordering::kAmd:
      m.common.nmethods = 1;
      m.common.method[0].ordering = CHOLMOD_AMD;
      break;
    case SparseCholeskyOptions::Ordering::kNestedDissection:
      m.common.nmethods = 1;
      m.common.method[0].ordering = CHOLMOD_METIS;
      break;
  }
  if (a.rows() == 0) return;
  cholmod_sparse view = ViewLower(lower);
  auto t0 = std::chrono::steady_clock::now();
  std::vector<int> given;
  if (!options.groups.empty() &&
      options.ordering == SparseCholeskyOptions::Ordering::kNestedDissection) {
    given = internal::GroupOrdering(lower, options.groups, &m.common);
  }
  if (!given.empty()) {
    m.common.nmethods = 1;
    m.common.method[0].ordering = CHOLMOD_GIVEN;
    m.factor = cholmod_analyze_p(&view, given.data(), nullptr, 0, &m.common);
  } else {
    // CHOLMOD's own choice may be METIS, whose random generator is global
    // (internal::MetisMutex); minimum degree alone needs no lock.
    std::unique_lock<std::mutex> lock(internal::MetisMutex(), std::defer_lock);
    if (options.ordering != SparseCholeskyOptions::Ordering::kAmd) lock.lock();
    m.factor = cholmod_analyze(&view, &m.common);
  }
  if (m.factor == nullptr && m.common.status == CHOLMOD_NOT_INSTALLED) {
    // A CHOLMOD built without METIS: minimum degree instead.
    m.common.nmethods = 1;
    m.common.method[0].ordering = CHOLMOD_AMD;
    m.factor = cholmod_analyze(&view, &m.common);
  }
  if (m.factor == nullptr) {
    throw InputError(name, "the sparse Cholesky analysis failed (CHOLMOD status " +
                               std::to_string(m.common.status) + ")");
  }
  m.info.seconds_analyse = Since(t0);
  m.info.flops = m.common.method[m.common.selected].fl;
  t0 = std::chrono::steady_clock::now();
  cholmod_factorize(&view, m.factor, &m.common);
  const int* perm = static_cast<const int*>(m.factor->Perm);
  if (m.common.status == CHOLMOD_NOT_POSDEF || m.factor->minor < m.factor->n) {
    const std::size_t pivot = m.factor->minor;
    const int dof =
        perm != nullptr && pivot < m.factor->n ? perm[pivot] : static_cast<int>(pivot);
    throw InputError(name,
                     "is not positive definite (the Cholesky factorisation breaks "
                     "down at DOF index " +
                         std::to_string(dof) + ")");
  }
  if (m.common.status < CHOLMOD_OK) {
    throw InputError(name, "the sparse Cholesky factorisation failed (CHOLMOD status " +
                               std::to_string(m.common.status) + ")");
  }
  // Simplicial, packed, columns in order: L is a plain compressed-column matrix.
  if (!cholmod_change_factor(CHOLMOD_REAL, 1, 0, 1, 1, m.factor, &m.common)) {
    throw InputError(name, "could not convert the Cholesky factor (CHOLMOD status " +
                               std::to_string(m.common.status) + ")");
  }
  m.info.seconds_factorise = Since(t0);
  perm = static_cast<const int*>(m.factor->Perm);
  const int n = m.n();
  m.perm.resize(n);
  m.inverse.resize(n);
  for (int i = 0; i < n; ++i) {
    m.perm[i] = perm != nullptr ? perm[i] : i;
    m.inverse[m.perm[i]] = i;
  }
  m.info.nnz_l = m.lp()[n];
  const int* lp = m.lp();
  const int* li = m.li();
  const double* lx = m.lx();
  m.parent.assign(static_cast<std::size_t>(n), -1);
  for (int c = 0; c < n; ++c) {
    int& up = m.parent[static_cast<std::size_t>(c)];
    for (int q = lp[c]; q < lp[c + 1]; ++q) {
      if (li[q] > c && (up < 0 || li[q] < up)) up = li[q];
    }
  }
  while (m.tail < n && lp[n - m.tail] - lp[n - m.tail - 1] == m.tail + 1) ++m.tail;
  if (m.tail < kDenseTailMin) m.tail = 0;
  if (m.tail > 0) {
    const int start = n - m.tail;
    m.tail_l = Eigen::MatrixXd::Zero(m.tail, m.tail);
    for (int c = start; c < n; ++c) {
      for (int q = lp[c]; q < lp[c + 1]; ++q) m.tail_l(li[q] - start, c - start) = lx[q];
    }
  }
}

SparseCholesky::~SparseCholesky() = default;

Eigen::Index SparseCholesky::size() const { return impl_->info.n; }

const SparseCholeskyInfo& SparseCholesky::info() const { return impl_->info; }

Eigen::MatrixXd SparseCholesky::HalfSolve(const Eigen::MatrixXd& b) const {
  const Impl& m = *impl_;
  if (b.rows() != size()) {
    throw InputError("SparseCholesky::HalfSolve",
                     "the right-hand side has " + std::to_string(b.rows()) +
                         " rows, expected " + std::to_string(size()));
  }
  Eigen::MatrixXd y(b.rows(), b.cols());
  for (int i = 0; i < m.n(); ++i) y.row(i) = b.row(m.perm[i]);
  if (m.n() > 0) m.L().triangularView<Eigen::Lower>().solveInPlace(y);
  return y;
}

Eigen::MatrixXd SparseCholesky::Solve(const Eigen::MatrixXd& b) const {
  const Impl& m = *impl_;
  Eigen::MatrixXd y = HalfSolve(b);
  if (m.n() > 0) m.L().transpose().triangularView<Eigen::Upper>().solveInPlace(y);
  Eigen::MatrixXd x(b.rows(), b.cols());
  for (int i = 0; i < m.n(); ++i) x.row(m.perm[i]) = y.row(i);
  return x;
}

std::vector<SparseMatrix> SparseCholesky::HalfSolve(
    const std::vector<SparseMatrix>& b) const {
  const Impl& m = *impl_;
  const int n = m.n();
  const std::size_t count = b.size();
  if (count == 0) return {};
  const SparseMatrix& first = b.front();
  const auto same_pattern = [&first](const SparseMatrix& a) {
    return a.rows() == first.rows() && a.cols() == first.cols() && a.isCompressed() &&
           std::equal(a.outerIndexPtr(), a.outerIndexPtr() + a.cols() + 1,
                      first.outerIndexPtr()) &&
           std::equal(a.innerIndexPtr(), a.innerIndexPtr() + a.nonZeros(),
                      first.innerIndexPtr());
  };
  for (const SparseMatrix& a : b) {
    if (a.rows() != size() || !same_pattern(a)) {
      throw InputError("SparseCholesky::HalfSolve",
                       "the right-hand sides must be compressed, have " +
                           std::to_string(size()) + " rows and share one pattern");
    }
  }
  std::vector<SparseMatrix> out(count, SparseMatrix(n, first.cols()));
  if (n == 0 || first.cols() == 0) return out;
  // The common pattern, rows permuted (P B).
  std::vector<int> rows(first.innerIndexPtr(), first.innerIndexPtr() + first.nonZeros());
  for (int& r : rows) r = m.inverse[r];
  std::vector<int> outer(first.outerIndexPtr(), first.outerIndexPtr() + first.cols() + 1);
  const int columns = static_cast<int>(first.cols());

  // Blocks of consecutive columns of about equal right-hand-side entries, a
  // fixed number of them whatever the thread count (each column's arithmetic
  // is its own, so the bits do not depend on the split either way).
  const int blocks = std::min(columns, kHalfSolveBlocks);
  std::vector<int> block_start(static_cast<std::size_t>(blocks) + 1, columns);
  block_start[0] = 0;
  for (int k = 0, next = 1; k < columns && next < blocks; ++k) {
    if (static_cast<long long>(outer[k]) * blocks >=
        static_cast<long long>(outer[columns]) * next) {
      block_start[static_cast<std::size_t>(next++)] = k;
    }
  }
  for (int q = blocks - 1; q > 0; --q)  // monotonic, none empty beyond the end
    block_start[q] = std::min(block_start[q], block_start[q + 1]);

  // Per worker: the dense accumulator (n x count, row-major, so that the
  // count values of one row sit together; entries are zeroed over each reach
  // before use) and the marks of the reach's walk (the column index that last
  // reached a row).
  struct Workspace {
    std::vector<double> x;
    std::vector<int> mark;
  };
  const int workers = ParallelWorkers(blocks, m.threads);
  std::vector<Workspace> space(static_cast<std::size_t>(workers));
  struct Block {
    std::vector<int> inner, counts;  // counts: entries per column
    std::vector<std::vector<double>> values;
  };
  std::vector<Block> done(static_cast<std::size_t>(blocks));
  const int* li = m.li();
  const double* lx = m.lx();
  const int* lp = m.lp();
  const std::vector<int>& parent = m.parent;
  const int tail = m.tail;
  const int tail_start = n - tail;
  ParallelForWorkers(blocks, m.threads, [&](int block, int worker) {
    Workspace& w = space[static_cast<std::size_t>(worker)];
    if (w.mark.empty()) {
      w.x.assign(static_cast<std::size_t>(n) * count, 0.0);
      w.mark.assign(static_cast<std::size_t>(n), -1);
    }
    Block& out_block = done[static_cast<std::size_t>(block)];
    out_block.values.resize(count);
    std::vector<int> column;
    // The block's tail values: tail x (count per column reaching the tail),
    // and where each such column's tail entries go in the block's output.
    std::vector<double> tail_x;
    std::vector<std::size_t> tail_at;
    std::vector<int> tail_first;
    for (int k = block_start[block]; k < block_start[block + 1]; ++k) {
      // The reach without the tail (ascending), and the first tail row it
      // reaches (n: none; the tail is a chain, so the reach holds the rest).
      column.clear();
      int first_tail = n;
      for (int p = outer[k]; p < outer[k + 1]; ++p) {
        for (int r = rows[p]; r >= 0 && w.mark[static_cast<std::size_t>(r)] != k;
             r = parent[static_cast<std::size_t>(r)]) {
          if (r >= tail_start) {
            first_tail = std::min(first_tail, r);
            break;
          }
          w.mark[static_cast<std::size_t>(r)] = k;
          column.push_back(r);
        }
      }
      std::sort(column.begin(), column.end());
      for (int r : column) {
        std::fill_n(w.x.data() + static_cast<std::size_t>(r) * count, count, 0.0);
      }
      const bool reaches_tail = first_tail < n;
      if (reaches_tail) {  // all tail rows zero: those above the reach stay so in dtrsm
        std::fill_n(w.x.data() + static_cast<std::size_t>(tail_start) * count,
                    static_cast<std::size_t>(n - tail_start) * count, 0.0);
      }
      for (int p = outer[k]; p < outer[k + 1]; ++p) {
        double* row = w.x.data() + static_cast<std::size_t>(rows[p]) * count;
        for (std::size_t j = 0; j < count; ++j) row[j] = b[j].valuePtr()[p];
      }
      SubstituteOnReach(static_cast<int>(count), column.data(),
                        static_cast<int>(column.size()), lp, li, lx, w.x.data());
      for (int r : column) {
        out_block.inner.push_back(r);
        const double* xr = w.x.data() + static_cast<std::size_t>(r) * count;
        for (std::size_t j = 0; j < count; ++j) out_block.values[j].push_back(xr[j]);
      }
      if (reaches_tail) {  // the reached tail rows after the others, values later
        tail_at.push_back(out_block.inner.size());
        tail_first.push_back(first_tail);
        for (std::size_t j = 0; j < count; ++j) {
          for (int r = tail_start; r < n; ++r)
            tail_x.push_back(w.x[static_cast<std::size_t>(r) * count + j]);
          out_block.values[j].resize(out_block.values[j].size() + (n - first_tail));
        }
        for (int r = first_tail; r < n; ++r) out_block.inner.push_back(r);
      }
      out_block.counts.push_back(static_cast<int>(column.size()) + (n - first_tail));
    }
    if (tail_at.empty()) return;
    Eigen::Map<Eigen::MatrixXd> x(tail_x.data(), tail,
                                  static_cast<Eigen::Index>(tail_at.size() * count));
    SolveLowerInPlace(m.tail_l, x);
    for (std::size_t i = 0; i < tail_at.size(); ++i) {
      for (std::size_t j = 0; j < count; ++j) {
        const int skip = tail_first[i] - tail_start;  // rows above the reach
        std::copy_n(x.col(static_cast<Eigen::Index>(i * count + j)).data() + skip,
                    n - tail_first[i], out_block.values[j].data() + tail_at[i]);
      }
    }
  });
  // The blocks in column order.
  std::size_t total = 0;
  for (const Block& d : done) total += d.inner.size();
  for (std::size_t j = 0; j < count; ++j) {
    SparseMatrix& w = out[j];
    w.resizeNonZeros(static_cast<Eigen::Index>(total));
    int* out_outer = w.outerIndexPtr();
    out_outer[0] = 0;
    int k = 0;
    std::size_t at = 0;
    for (const Block& d : done) {
      for (int c : d.counts) {
        out_outer[k + 1] = out_outer[k] + c;
        ++k;
      }
      std::copy(d.inner.begin(), d.inner.end(), w.innerIndexPtr() + at);
      if (!d.values.empty())
        std::copy(d.values[j].begin(), d.values[j].end(), w.valuePtr() + at);
      at += d.inner.size();
    }
  }
  return out;
}

double SparseCholesky::HalfSolveFlops(const SparseMatrix& w, int right_hand_sides) const {
  if (w.rows() != size() || right_hand_sides < 1) {
    throw InputError("SparseCholesky::HalfSolveFlops",
                     "the pattern must have " + std::to_string(size()) +
                         " rows and the right-hand sides must be >= 1, got " +
                         std::to_string(w.rows()) + " rows and " +
                         std::to_string(right_hand_sides));
  }
  const int* lp = impl_->lp();
  double per_side = 0;
  for (Eigen::Index k = 0; k < w.outerSize(); ++k) {
    for (SparseMatrix::InnerIterator it(w, k); it; ++it) {
      const Eigen::Index c = it.row();
      per_side += 2.0 * (lp[c + 1] - lp[c]) - 1.0;
    }
  }
  return per_side * right_hand_sides;
}

SparseMatrix SparseCholesky::HalfSolve(const SparseMatrix& b) const {
  SparseMatrix compressed = b;
  compressed.makeCompressed();
  return HalfSolve(std::vector<SparseMatrix>{compressed}).front();
}

}  // namespace femup
