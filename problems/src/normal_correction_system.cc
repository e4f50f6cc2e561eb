#include "femup/problems/normal_correction_system.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>

#include "femup/core/errors.h"
#include "femup/core/linalg/sparse_cholesky.h"
#include "femup/core/parallel.h"

namespace femup {
namespace {

// Ranges of G's columns its products are split into, for the threads.
constexpr int kGramParts = 8;

double Since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The lower triangle of g += sum_j W_j' W_j for W_j (n x p, compressed) that
// share one pattern (HalfSolve's output for the modes of a state): row by row,
// each row's t entries for all modes at once, t (t + 1) / 2 products of
// m-vectors into G, with no sparse product and its sparse result. Returns the
// floating-point operations it made (a multiplication and an addition per
// product term). Runs on `threads` threads.
double AddGramLower(const std::vector<SparseMatrix>& w, int threads, Eigen::MatrixXd* g) {
  if (w.empty()) return 0;
  const SparseMatrix& first = w.front();
  const int n = static_cast<int>(first.rows());
  const int p = static_cast<int>(first.cols());
  const std::size_t m = w.size();
  const int* outer = first.outerIndexPtr();
  const int* inner = first.innerIndexPtr();
  const int nnz = outer[p];
  // Row-wise view of the pattern: per row, its columns in ascending order.
  std::vector<int> row_start(static_cast<std::size_t>(n) + 1, 0);
  for (int q = 0; q < nnz; ++q) ++row_start[static_cast<std::size_t>(inner[q]) + 1];
  for (int r = 0; r < n; ++r) row_start[r + 1] += row_start[r];
  std::vector<int> next(row_start.begin(), row_start.end() - 1);
  std::vector<int> column(static_cast<std::size_t>(nnz));
  // Values row-major by entry: the m modes of one entry side by side.
  std::vector<double> value(static_cast<std::size_t>(nnz) * m);
  for (int c = 0; c < p; ++c) {
    for (int q = outer[c]; q < outer[c + 1]; ++q) {
      const int slot = next[inner[q]]++;
      column[slot] = c;
      for (std::size_t j = 0; j < m; ++j) value[slot * m + j] = w[j].valuePtr()[q];
    }
  }
  double* gd = g->data();
  const Eigen::Index ld = g->rows();
  double flops = 0;
  // The products each column of G receives (its pairs a <= b in every row),
  // to split G's columns into kGramParts ranges of about equal work.
  std::vector<double> work(static_cast<std::size_t>(p), 0.0);
  for (int r = 0; r < n; ++r) {
    const double t = row_start[r + 1] - row_start[r];
    flops += t * (t + 1) * static_cast<double>(m);
    for (int a = row_start[r]; a < row_start[r + 1]; ++a)
      work[static_cast<std::size_t>(column[a])] += row_start[r + 1] - a;
  }
  std::vector<int> part_start(kGramParts + 1, p);
  part_start[0] = 0;
  {
    const double total = std::accumulate(work.begin(), work.end(), 0.0);
    double sum = 0;
    for (int c = 0, cut = 1; c < p && cut < kGramParts; ++c) {
      sum += work[static_cast<std::size_t>(c)];
      while (cut < kGramParts && sum >= total * cut / kGramParts)
        part_start[cut++] = c + 1;
    }
  }
  // Each part writes the columns of G in its range only, their terms added in
  // row order as one loop would: the bits do not depend on the threads. A
  // row's entries are in ascending column order, so a part's are contiguous.
  ParallelFor(kGramParts, threads, [&](int part) {
    const int lo = part_start[part], hi = part_start[part + 1];
    if (lo >= hi) return;
    for (int r = 0; r < n; ++r) {
      const int* first_col = column.data() + row_start[r];
      const int* last_col = column.data() + row_start[r + 1];
      const int begin =
          static_cast<int>(std::lower_bound(first_col, last_col, lo) - column.data());
      const int end =
          static_cast<int>(std::lower_bound(first_col, last_col, hi) - column.data());
      for (int a = begin; a < end; ++a) {
        const double* va = value.data() + static_cast<std::size_t>(a) * m;
        double* ga = gd + static_cast<Eigen::Index>(column[a]) * ld;  // column a of G
        for (int b = a; b < row_start[r + 1]; ++b) {
          const double* vb = value.data() + static_cast<std::size_t>(b) * m;
          double sum = 0;
          for (std::size_t j = 0; j < m; ++j) sum += va[j] * vb[j];
          ga[column[b]] += sum;  // G(column b, column a), column b >= column a
        }
      }
    }
  });
  return flops;
}

}  // namespace

LinearProblem BuildNormalCorrectionSystem(const ParametrisedModel& model,
                                          const std::vector<ModalData>& states,
                                          NormalCorrectionStats* stats,
                                          const NormalCorrectionOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  const int dofs = model.num_dofs();
  const int p = model.num_parameters();
  if (p == 0)
    throw InputError("parameters", "the model has no correction factor to identify");
  if (states.empty()) throw InputError("measurements", "no measured state is given");

  if (options.threads < 0) {
    throw InputError("threads", "must be >= 0 (0 = one per core), got " +
                                    std::to_string(options.threads));
  }
  SparseCholeskyOptions chol_options;
  chol_options.name = "model.mass";
  chol_options.threads = options.threads;
  chol_options.groups = model.DofNodes();  // nested dissection of the node graph
  const SparseCholesky chol(model.mass(), chol_options);

  Eigen::MatrixXd g = Eigen::MatrixXd::Zero(p, p);
  Eigen::VectorXd h = Eigen::VectorXd::Zero(p);
  double f2 = 0;
  int modes = 0;
  long long nnz_z = 0, nnz_w = 0;
  double seconds_half_solve = 0, seconds_gram = 0, flops_gram = 0;
  for (const ModalData& st : states) {
    const std::string where = "measurements." + st.state;
    st.Validate(dofs, where);
    const Eigen::MatrixXd shapes = st.FullShapes(dofs, where);
    const Eigen::VectorXd lambdas = st.Eigenvalues();
    const bool wet = st.immersion == Immersion::kWet;
    const int m = st.num_modes();
    // Added-mass factors enter wet states only (c_k = 0 in dry ones).
    const auto enters = [&](int k) {
      return model.parameter(k).kind != ParameterKind::kAddedMass || wet;
    };
    // B_k Phi on the support of each basis that enters the state, for all its
    // modes at once.
    std::vector<Eigen::MatrixXd> products(p);
    for (int k = 0; k < p; ++k) {
      if (enters(k)) products[k] = model.parameter(k).basis.RestrictedProduct(shapes);
    }
    // Z_j for every mode of the state, column k = c_k B_k phi_j on the support
    // of B_k: one sparsity pattern for all of them (the columns whose factor
    // enters the state), so that one sparse half solve serves them all.
    std::vector<int> outer(p + 1, 0);
    std::vector<int> inner;
    for (int k = 0; k < p; ++k) {
      if (enters(k)) {
        const std::vector<int>& touched = model.parameter(k).basis.dofs();
        inner.insert(inner.end(), touched.begin(), touched.end());
      }
      outer[k + 1] = static_cast<int>(inner.size());
    }
    std::vector<SparseMatrix> z(m, SparseMatrix(dofs, p));
    for (int j = 0; j < m; ++j) {
      const double lambda = lambdas[j];
      SparseMatrix& zj = z[j];
      zj.resizeNonZeros(static_cast<Eigen::Index>(inner.size()));
      std::copy(outer.begin(), outer.end(), zj.outerIndexPtr());
      std::copy(inner.begin(), inner.end(), zj.innerIndexPtr());
      for (int k = 0; k < p; ++k) {
        const double factor =
            model.parameter(k).kind == ParameterKind::kStiffness ? 1.0 : -lambda;
        for (int q = outer[k]; q < outer[k + 1]; ++q) {
          zj.valuePtr()[q] = factor * products[k](q - outer[k], j);
        }
      }
      nnz_z += zj.nonZeros();
    }
    // With P M P' = L L': Z' M^-1 Z = W' W for W = L^-1 P Z, whose columns are
    // sparse (only the elimination-tree ancestors of each basis's DOFs).
    auto t_phase = std::chrono::steady_clock::now();
    const std::vector<SparseMatrix> w = chol.HalfSolve(z);
    seconds_half_solve += Since(t_phase);
    // F_j = -(K phi_j - lambda_j M phi_j), all modes at once, and L^-1 P F.
    const Eigen::MatrixXd f =
        -(model.stiffness() * shapes - (model.mass() * shapes) * lambdas.asDiagonal());
    const Eigen::MatrixXd y = chol.HalfSolve(f);
    f2 += y.squaredNorm();
    for (int j = 0; j < m; ++j) {
      ++modes;
      nnz_w += w[j].nonZeros();
      h += w[j].transpose() * y.col(j);
    }
    t_phase = std::chrono::steady_clock::now();
    flops_gram += AddGramLower(w, options.threads, &g);
    seconds_gram += Since(t_phase);
  }
  // The upper triangle from the lower (a loop: no aliasing between the two).
  for (int c = 1; c < p; ++c) {
    for (int r = 0; r < c; ++r) g(r, c) = g(c, r);
  }
  const double assembly = Since(t0);

  // Column-scaled square root by pivoted LDL' (stable on a semidefinite G):
  // D G D = P' L S L' P, A = S^1/2 L' P D^-1, and b with A' b = h:
  // S^1/2 b = L^-1 P D h. Pivots at or below p eps max are dropped (zero rows).
  const auto t1 = std::chrono::steady_clock::now();
  Eigen::VectorXd d(p);
  for (int k = 0; k < p; ++k) d[k] = g(k, k) > 0 ? 1.0 / std::sqrt(g(k, k)) : 1.0;
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(d.asDiagonal() * g * d.asDiagonal());
  const Eigen::VectorXd& s = ldlt.vectorD();
  const double smax = s.size() > 0 ? std::max(s.maxCoeff(), 0.0) : 0.0;
  const double threshold = p * std::numeric_limits<double>::epsilon() * smax;
  LinearProblem problem;
  Eigen::MatrixXd pd = d.cwiseInverse().asDiagonal();
  pd = ldlt.transpositionsP() * pd;
  problem.A = ldlt.matrixU() * pd;
  Eigen::VectorXd y = ldlt.transpositionsP() * (d.asDiagonal() * h);
  ldlt.matrixL().solveInPlace(y);
  problem.b = Eigen::VectorXd::Zero(p);
  int dropped = 0;
  for (int i = 0; i < p; ++i) {
    if (!(s[i] > threshold)) {
      ++dropped;
      problem.A.row(i).setZero();
      continue;
    }
    const double root = std::sqrt(s[i]);
    problem.A.row(i) *= root;
    problem.b[i] = y[i] / root;
  }
  problem.source_rows = dofs * modes;
  problem.residual_offset = std::max(0.0, f2 - problem.b.squaredNorm());
  problem.names = model.ParameterNames();
  for (const Parameter& q : model.parameters())
    problem.groups.push_back(ToString(q.kind));
  if (stats != nullptr) {
    stats->dropped = dropped;
    stats->seconds_assembly = assembly;
    stats->seconds_factorise =
        chol.info().seconds_analyse + chol.info().seconds_factorise;
    stats->seconds_analyse = chol.info().seconds_analyse;
    stats->nnz_l = chol.info().nnz_l;
    stats->flops_factorise = chol.info().flops;
    stats->flops_gram = flops_gram;
    stats->seconds_half_solve = seconds_half_solve;
    stats->seconds_gram = seconds_gram;
    stats->nnz_z = nnz_z;
    stats->nnz_w = nnz_w;
    stats->seconds_compress = Since(t1);
  }
  return problem;
}

}  // namespace femup
