#include "femup/problems/normal_correction_system.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iterator>
#include <limits>
#include <numeric>
#include <sstream>

#include "femup/core/errors.h"
#include "femup/core/linalg/dense_kernels.h"
#include "femup/core/linalg/sparse_cholesky.h"
#include "femup/core/parallel.h"

namespace femup {
namespace {

// Ranges of G's columns its products are split into, for the threads.
constexpr int kGramParts = 8;

double Since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Rows of W grouped for the dense products: a block is a run of consecutive
// non-empty rows whose column patterns are joined into one (sorted) union, on
// which their values are laid out dense with zeros where a row lacks a column.
// Rows of one node, and nodes along a chain of the elimination tree, reach
// nearly the same factors, so little is padded.
struct GramBlock {
  int first_row = 0, last_row = 0;  // [first_row, last_row): some may be empty
  int columns_begin = 0;            // into the blocks' union of columns
  int columns = 0;
};

// A block takes a row while at least 1 - kGramPadding of its dense layout
// holds entries, and up to kGramBlockRows rows.
constexpr double kGramPadding = 0.25;
constexpr int kGramBlockRows = 48;
// The blocks' dense products made at once (then added into G), at most this
// many doubles of them (8 MB).
constexpr std::size_t kGramBatchDoubles = std::size_t{1} << 20;

// The lower triangle of g += sum_j W_j' W_j for W_j (n x p, compressed) that
// share one pattern (HalfSolve's output for the modes of a state). The rows
// are grouped into blocks (GramBlock); each block's values for all modes form
// a dense (rows m) x t matrix V on the union of its rows' t columns, and
// V' V (the BLAS's dsyrk) is added into G on those columns. Returns the
// floating-point operations the method needs, whatever the padding: t (t + 1)
// m per row of t entries (a multiplication and an addition per product term
// of its lower triangle). Runs on `threads` threads with the same bits for
// any number of them: each block's product does not depend on them, and each
// entry of G takes the blocks' terms in block order.
double AddGramLower(const std::vector<SparseMatrix>& w, int threads, Eigen::MatrixXd* g) {
  if (w.empty()) return 0;
  const SparseMatrix& first = w.front();
  const int n = static_cast<int>(first.rows());
  const int p = static_cast<int>(first.cols());
  const int m = static_cast<int>(w.size());
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
      for (int j = 0; j < m; ++j)
        value[static_cast<std::size_t>(slot) * m + j] = w[j].valuePtr()[q];
    }
  }
  double flops = 0;
  for (int r = 0; r < n; ++r) {
    const double t = row_start[r + 1] - row_start[r];
    flops += t * (t + 1) * m;
  }

  // The blocks, and their unions of columns one after another.
  std::vector<GramBlock> blocks;
  std::vector<int> unions;
  {
    std::vector<int> current, merged;
    GramBlock block;
    long long entries = 0;  // of the block's rows
    int rows = 0;
    const auto close = [&](int end_row) {
      if (rows == 0) return;
      block.last_row = end_row;
      block.columns_begin = static_cast<int>(unions.size());
      block.columns = static_cast<int>(current.size());
      unions.insert(unions.end(), current.begin(), current.end());
      blocks.push_back(block);
      rows = 0;
      entries = 0;
      current.clear();
    };
    for (int r = 0; r < n; ++r) {
      const int* lo = column.data() + row_start[r];
      const int* hi = column.data() + row_start[r + 1];
      if (lo == hi) continue;
      merged.clear();
      std::set_union(current.begin(), current.end(), lo, hi, std::back_inserter(merged));
      const double dense =
          static_cast<double>(rows + 1) * static_cast<double>(merged.size());
      const long long with_row = entries + (hi - lo);
      if (rows > 0 && (rows == kGramBlockRows ||
                       dense - static_cast<double>(with_row) > kGramPadding * dense)) {
        close(r);
        merged.assign(lo, hi);
      }
      if (rows == 0) block.first_row = r;
      current.swap(merged);
      entries += hi - lo;
      ++rows;
    }
    close(n);
  }

  // The products each column of G receives, to split G's columns into
  // kGramParts ranges of about equal work for the additions.
  std::vector<double> work(static_cast<std::size_t>(p), 0.0);
  for (const GramBlock& b : blocks) {
    for (int a = 0; a < b.columns; ++a)
      work[unions[b.columns_begin + a]] += b.columns - a;
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

  double* gd = g->data();
  const Eigen::Index ld = g->rows();
  std::vector<double> products;  // the batch's V' V, one after another
  std::vector<std::size_t> offset;
  std::vector<std::vector<double>> scratch;  // per worker: a block's V
  for (std::size_t b0 = 0; b0 < blocks.size();) {
    // A batch: blocks from b0 while their products fit (at least one).
    std::size_t b1 = b0, size = 0;
    offset.clear();
    while (b1 < blocks.size()) {
      const std::size_t t = static_cast<std::size_t>(blocks[b1].columns);
      if (b1 > b0 && size + t * t > kGramBatchDoubles) break;
      offset.push_back(size);
      size += t * t;
      ++b1;
    }
    products.resize(size);
    const int count = static_cast<int>(b1 - b0);
    scratch.resize(static_cast<std::size_t>(ParallelWorkers(count, threads)));
    ParallelForWorkers(count, threads, [&](int index, int worker) {
      const GramBlock& b = blocks[b0 + static_cast<std::size_t>(index)];
      const int* cols = unions.data() + b.columns_begin;
      const int k = (b.last_row - b.first_row) * m;
      std::vector<double>& buffer = scratch[static_cast<std::size_t>(worker)];
      buffer.assign(static_cast<std::size_t>(k) * b.columns, 0.0);
      Eigen::Map<Eigen::MatrixXd> v(buffer.data(), k, b.columns);
      for (int r = b.first_row; r < b.last_row; ++r) {
        int pos = 0;
        for (int e = row_start[r]; e < row_start[r + 1]; ++e) {
          while (cols[pos] != column[e]) ++pos;  // both ascending, row's within the union
          for (int j = 0; j < m; ++j) {
            v((r - b.first_row) * m + j, pos) =
                value[static_cast<std::size_t>(e) * m + j];
          }
        }
      }
      Eigen::Map<Eigen::MatrixXd> c(
          products.data() + offset[static_cast<std::size_t>(index)], b.columns,
          b.columns);
      RankUpdateLower(v, 1.0, 0.0, c);
    });
    // Each part adds into the columns of G in its range only, block by block.
    ParallelFor(kGramParts, threads, [&](int part) {
      const int lo = part_start[part], hi = part_start[part + 1];
      if (lo >= hi) return;
      for (std::size_t i = b0; i < b1; ++i) {
        const GramBlock& b = blocks[i];
        const int* cols = unions.data() + b.columns_begin;
        const int begin =
            static_cast<int>(std::lower_bound(cols, cols + b.columns, lo) - cols);
        const int end =
            static_cast<int>(std::lower_bound(cols, cols + b.columns, hi) - cols);
        const double* c = products.data() + offset[i - b0];
        for (int a = begin; a < end; ++a) {
          double* ga = gd + static_cast<Eigen::Index>(cols[a]) * ld;  // column a of G
          const double* ca = c + static_cast<std::size_t>(a) * b.columns;
          for (int bb = a; bb < b.columns; ++bb) ga[cols[bb]] += ca[bb];
        }
      }
    });
    b0 = b1;
  }
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
  double seconds_half_solve = 0, seconds_gram = 0, flops_gram = 0, flops_half_solve = 0;
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
    if (!w.empty()) flops_half_solve += chol.HalfSolveFlops(w.front(), m);
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
  const double assembly = Since(t0);

  // Column-scaled square root by Cholesky with complete pivoting (stable on a
  // semidefinite G; LAPACK's dpstrf): with D G D = P L L' P', A = L' P' D^-1
  // and b with A' b = h: L b = P' D h. The factorisation stops at pivots at
  // or below p eps times the largest (the scaled diagonal's 1): those rows of
  // A and b are zero (dropped).
  const auto t1 = std::chrono::steady_clock::now();
  Eigen::VectorXd d(p);
  for (int k = 0; k < p; ++k) d[k] = g(k, k) > 0 ? 1.0 / std::sqrt(g(k, k)) : 1.0;
  for (int c = 0; c < p; ++c) {  // D G D, lower triangle
    for (int r = c; r < p; ++r) g(r, c) *= d[r] * d[c];
  }
  double largest = 0;
  for (int k = 0; k < p; ++k) largest = std::max(largest, g(k, k));
  std::vector<int> pivots;
  const int rank = PivotedCholeskyLower(
      g, p * std::numeric_limits<double>::epsilon() * largest, &pivots);
  if (rank < 0) {
    throw InputError("measurements",
                     "the correction system's normal matrix is not finite: the measured "
                     "shapes or the model's matrices are too large to square in double "
                     "precision");
  }
  LinearProblem problem;
  problem.A = Eigen::MatrixXd::Zero(p, p);
  for (int i = 0; i < rank; ++i) {
    for (int j = i; j < p; ++j) {
      const int k = pivots[static_cast<std::size_t>(j)];
      problem.A(i, k) = g(j, i) / d[k];
    }
  }
  problem.b = Eigen::VectorXd::Zero(p);
  for (int j = 0; j < rank; ++j) {
    const int k = pivots[static_cast<std::size_t>(j)];
    problem.b[j] = d[k] * h[k];
  }
  g.topLeftCorner(rank, rank)
      .triangularView<Eigen::Lower>()
      .solveInPlace(problem.b.head(rank));
  const int dropped = p - rank;
  problem.source_rows = dofs * modes;
  // f2 - |b|^2 cancels: both sum source_rows squares, each to within about
  // source_rows eps f2. A difference below that is rounding and is taken as 0,
  // so that consistent (noise-free) data give no residual of rounding size
  // whose value would depend on the BLAS's kernels.
  const double difference = f2 - problem.b.squaredNorm();
  const double rounding = static_cast<double>(problem.source_rows) *
                          std::numeric_limits<double>::epsilon() * f2;
  problem.residual_offset = difference > rounding ? difference : 0.0;
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
    stats->flops_half_solve = flops_half_solve;
    stats->seconds_half_solve = seconds_half_solve;
    stats->seconds_gram = seconds_gram;
    stats->nnz_z = nnz_z;
    stats->nnz_w = nnz_w;
    stats->seconds_compress = Since(t1);
  }
  return problem;
}

}  // namespace femup
