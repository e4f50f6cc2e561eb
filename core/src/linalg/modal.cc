#include "femup/core/linalg/modal.h"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "femup/core/errors.h"
#include "femup/core/linalg/symmetric_spectrum.h"
#include "linalg/sparse_eigen.h"

namespace femup {
namespace {

void FixSigns(Eigen::MatrixXd* shapes) {
  for (Eigen::Index j = 0; j < shapes->cols(); ++j) {
    Eigen::Index imax = 0;
    shapes->col(j).cwiseAbs().maxCoeff(&imax);
    if ((*shapes)(imax, j) < 0) shapes->col(j) *= -1.0;
  }
}

// The lowest num_modes (-1: all) by LAPACK (symmetric_spectrum.h): only the
// vectors asked for are computed.
Modes SolveDense(const SparseMatrix& k, const SparseMatrix& m, int num_modes) {
  const int n = static_cast<int>(k.rows());
  const int count = num_modes < 0 ? n : num_modes;
  Modes modes;
  switch (SmallestPencilEigenpairs(Eigen::MatrixXd(k), Eigen::MatrixXd(m), count,
                                   &modes.eigenvalues, &modes.shapes)) {
    case PencilStatus::kOk:
      break;
    case PencilStatus::kMassNotPositiveDefinite:
      throw InputError(
          "modal analysis",
          "mass matrix is not positive definite (Cholesky factorisation failed)");
    case PencilStatus::kFailed:
      throw NumericalError("modal analysis",
                           "dense generalised eigensolver did not converge");
  }
  MassNormalise(m, &modes.shapes);
  // Each eigenvalue as its vector's Rayleigh quotient x' K x (x' M x = 1). A
  // dense solver's eigenvalues are accurate to about eps times the largest,
  // so where a model's axial or rotational DOFs are far stiffer than its
  // lowest modes (a beam: lambda_max / lambda_1 ~ 1e8-1e9) its lowest
  // eigenvalue comes out to only ~1e-8-1e-7 of itself; the quotient's error is
  // second order in the vector's: 5.5e-13 on a 60-DOF bar, 7.7e-10 on a
  // 300-DOF one (modal_test.cc, against long-double solutions). A fit on such
  // a model otherwise sees its misfit jump by ~1e-8 of itself between nearby
  // evaluations and goes on with rejected steps (half the evaluations of a
  // cantilever's diagnosis, measured on examples/diagnosis/air_and_water.yaml).
  for (int j = 0; j < count; ++j)
    modes.eigenvalues[j] = modes.shapes.col(j).dot(k * modes.shapes.col(j));
  FixSigns(&modes.shapes);
  return modes;
}

}  // namespace

Eigen::VectorXd Modes::FrequenciesHz() const {
  Eigen::VectorXd f(eigenvalues.size());
  for (Eigen::Index i = 0; i < eigenvalues.size(); ++i) {
    f[i] = eigenvalues[i] > 0 ? std::sqrt(eigenvalues[i]) / (2 * M_PI) : 0.0;
  }
  return f;
}

Invalid EigenOptions::Validate() const {
  if (num_modes == 0 || num_modes < -1)
    return {"num_modes", "num_modes must be -1 (all) or >= 1"};
  if (dense_limit < 1) return {"dense_limit", "dense_limit must be >= 1"};
  if (!std::isfinite(shift)) return {"shift", "shift must be finite"};
  if (!(tolerance > 0)) return {"tolerance", "tolerance must be positive"};
  if (max_iterations < 1) return {"max_iterations", "max_iterations must be >= 1"};
  if (threads < 0) return {"threads", "threads must be >= 0 (0: one per core)"};
  return {};
}

EigenSolution TrySolveModes(const SparseMatrix& stiffness, const SparseMatrix& mass,
                            const EigenOptions& options) {
  EigenSolution solution;
  try {
    solution.modes = SolveModes(stiffness, mass, options);
  } catch (const NumericalError& e) {
    solution.failure = e.what();
  }
  return solution;
}

Modes SolveModes(const SparseMatrix& stiffness, const SparseMatrix& mass,
                 const EigenOptions& options) {
  if (const Invalid bad = options.Validate())
    throw InputError("eigen options", bad.message);
  const Eigen::Index n = stiffness.rows();
  if (stiffness.cols() != n || mass.rows() != n || mass.cols() != n) {
    std::ostringstream msg;
    msg << "K is " << stiffness.rows() << " x " << stiffness.cols() << " and M is "
        << mass.rows() << " x " << mass.cols() << ": they must be square and equal";
    throw InputError("modal analysis", msg.str());
  }
  if (n == 0) throw InputError("modal analysis", "the model has no free DOF");
  if (options.num_modes > n) {
    std::ostringstream msg;
    msg << options.num_modes << " modes asked of a model with " << n << " DOFs";
    throw InputError("modal analysis", msg.str());
  }
  using Method = EigenOptions::Method;
  Method method = options.method;
  if (method == Method::kAuto) {
    method =
        (n <= options.dense_limit || options.num_modes < 0 || options.num_modes >= n - 1)
            ? Method::kDense
            : Method::kSparseShiftInvert;
  }
  if (method == Method::kDense) {
    if (options.shift != 0.0) {
      // Dense solves all modes; keep the ones nearest above the shift.
      Modes all = SolveDense(stiffness, mass, -1);
      int first = 0;
      while (first < all.size() && all.eigenvalues[first] < options.shift) ++first;
      const int count = options.num_modes < 0
                            ? all.size() - first
                            : std::min(options.num_modes, all.size() - first);
      Modes out;
      out.eigenvalues = all.eigenvalues.segment(first, count);
      out.shapes = all.shapes.middleCols(first, count);
      return out;
    }
    return SolveDense(stiffness, mass, options.num_modes);
  }
  if (options.num_modes < 0) {
    throw InputError("modal analysis",
                     "the sparse eigensolver needs a number of modes (num_modes >= 1)");
  }
  return internal::SolveModesSparse(stiffness, mass, options);
}

void MassNormalise(const SparseMatrix& mass, Eigen::MatrixXd* shapes) {
  for (Eigen::Index j = 0; j < shapes->cols(); ++j) {
    const double mm = shapes->col(j).dot(mass * shapes->col(j));
    if (!(mm > 0)) {
      throw InputError("mass normalisation",
                       "mode " + std::to_string(j + 1) + " has phi' M phi <= 0");
    }
    shapes->col(j) /= std::sqrt(mm);
  }
}

double Mac(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  if (a.size() != b.size()) {
    throw InputError("MAC", "vectors of sizes " + std::to_string(a.size()) + " and " +
                                std::to_string(b.size()));
  }
  const double aa = a.squaredNorm(), bb = b.squaredNorm();
  if (aa == 0 || bb == 0) return 0.0;
  const double ab = a.dot(b);
  return ab * ab / (aa * bb);
}

Eigen::MatrixXd MacMatrix(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  Eigen::MatrixXd out(a.cols(), b.cols());
  for (Eigen::Index i = 0; i < a.cols(); ++i) {
    for (Eigen::Index j = 0; j < b.cols(); ++j) out(i, j) = Mac(a.col(i), b.col(j));
  }
  return out;
}

std::vector<ModePair> PairModesByMac(const Eigen::MatrixXd& reference,
                                     const Eigen::MatrixXd& candidate, double min_mac) {
  Eigen::MatrixXd mac = MacMatrix(reference, candidate);
  std::vector<ModePair> pairs(reference.cols());
  for (Eigen::Index i = 0; i < reference.cols(); ++i)
    pairs[i].reference = static_cast<int>(i);
  const Eigen::Index rounds = std::min(reference.cols(), candidate.cols());
  for (Eigen::Index r = 0; r < rounds; ++r) {
    Eigen::Index i = 0, j = 0;
    const double best = mac.maxCoeff(&i, &j);
    if (best < min_mac || best < 0) break;
    pairs[i].candidate = static_cast<int>(j);
    pairs[i].mac = best;
    mac.row(i).setConstant(-1.0);
    mac.col(j).setConstant(-1.0);
  }
  return pairs;
}

Eigen::Index LastOfRepeated(const Modes& modes, Eigen::Index first, double tolerance) {
  Eigen::Index last = first;
  while (last + 1 < modes.size() &&
         modes.eigenvalues[last + 1] - modes.eigenvalues[last] <=
             tolerance * std::abs(modes.eigenvalues[last + 1])) {
    ++last;
  }
  return last;
}

void AlignRepeatedModes(const Eigen::MatrixXd& reference, const Eigen::MatrixXd& seen,
                        Modes* modes, double tolerance) {
  const Eigen::Index num = modes->size();
  if (seen.cols() != num || seen.rows() != reference.rows()) {
    throw InputError("seen", "expected " + std::to_string(reference.rows()) + " x " +
                                 std::to_string(num) + " (the reference's rows, one " +
                                 "column per mode), got " + std::to_string(seen.rows()) +
                                 " x " + std::to_string(seen.cols()));
  }
  if (reference.cols() == 0 || num < 3) return;
  for (Eigen::Index first = 0; first < num;) {
    const Eigen::Index last = LastOfRepeated(*modes, first, tolerance);
    const Eigen::Index dim = last - first + 1;
    if (dim < 2 || last + 1 >= num) {
      first = last + 1;
      continue;
    }
    const Eigen::MatrixXd space = seen.middleCols(first, dim);
    const Eigen::JacobiSVD<Eigen::MatrixXd> span(
        space, Eigen::ComputeThinU | Eigen::ComputeThinV);
    // Each reference shape's MAC with the eigenspace (with its best
    // combination, the least-squares one) and with the best single mode
    // outside it.
    struct Candidate {
      double mac;
      Eigen::VectorXd combination;
    };
    std::vector<Candidate> candidates;
    for (Eigen::Index j = 0; j < reference.cols(); ++j) {
      const Eigen::VectorXd psi = reference.col(j);
      if (!(psi.squaredNorm() > 0)) continue;
      const Eigen::VectorXd a = span.solve(psi);
      const double norm = a.norm();
      if (!(norm > 0) || !std::isfinite(norm)) continue;
      const double mac = Mac(psi, space * a);
      double outside = 0;
      for (Eigen::Index q = 0; q < num; ++q) {
        if (q < first || q > last) outside = std::max(outside, Mac(psi, seen.col(q)));
      }
      if (mac >= outside) candidates.push_back({mac, a / norm});
    }
    if (candidates.empty()) {
      first = last + 1;
      continue;
    }
    std::stable_sort(
        candidates.begin(), candidates.end(),
        [](const Candidate& a, const Candidate& b) { return a.mac > b.mac; });
    const Eigen::Index k = std::min<Eigen::Index>(dim, candidates.size());
    Eigen::MatrixXd combination(dim, k);
    for (Eigen::Index q = 0; q < k; ++q) combination.col(q) = candidates[q].combination;
    // The nearest orthonormal set to the combinations (the polar factor),
    // completed by the rest of the eigenspace: an orthogonal dim x dim matrix.
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(
        combination, Eigen::ComputeFullU | Eigen::ComputeThinV);
    Eigen::MatrixXd rotation(dim, dim);
    rotation.leftCols(k) = svd.matrixU().leftCols(k) * svd.matrixV().transpose();
    rotation.rightCols(dim - k) = svd.matrixU().rightCols(dim - k);
    const Eigen::MatrixXd basis = modes->shapes.middleCols(first, dim);
    modes->shapes.middleCols(first, dim) = basis * rotation;
    first = last + 1;
  }
}

std::vector<ModePair> PairModesByMacAndMisfit(const Eigen::MatrixXd& mac,
                                              const Eigen::MatrixXd& shape_misfit,
                                              const Eigen::MatrixXd& frequency_misfit,
                                              double min_mac, double tie) {
  if (shape_misfit.rows() != mac.rows() || shape_misfit.cols() != mac.cols() ||
      frequency_misfit.rows() != mac.rows() || frequency_misfit.cols() != mac.cols()) {
    throw InputError("misfit", "matrices of the MAC matrix's size expected");
  }
  if (!(tie >= 0)) throw InputError("tie", "must be >= 0");
  Eigen::MatrixXd left = mac;  // -1: taken
  std::vector<ModePair> pairs(mac.rows());
  for (Eigen::Index i = 0; i < mac.rows(); ++i) pairs[i].reference = static_cast<int>(i);
  const Eigen::Index rounds = std::min(mac.rows(), mac.cols());
  for (Eigen::Index r = 0; r < rounds; ++r) {
    Eigen::Index i = 0, j = 0;
    const double best = left.maxCoeff(&i, &j);
    if (best < min_mac || best < 0) break;
    Eigen::Index chosen = j;
    for (Eigen::Index k = 0; k < mac.cols(); ++k) {
      if (k == j || left(i, k) < min_mac || left(i, k) < 0) continue;
      if (!(shape_misfit(i, k) <= shape_misfit(i, j) + tie)) continue;
      if (shape_misfit(i, k) + frequency_misfit(i, k) <
          shape_misfit(i, chosen) + frequency_misfit(i, chosen)) {
        chosen = k;
      }
    }
    pairs[i].candidate = static_cast<int>(chosen);
    pairs[i].mac = mac(i, chosen);
    left.row(i).setConstant(-1.0);
    left.col(chosen).setConstant(-1.0);
  }
  return pairs;
}

std::vector<ModePair> PairModesInOrder(const Eigen::MatrixXd& reference,
                                       const Eigen::MatrixXd& candidate) {
  const Eigen::MatrixXd mac = MacMatrix(reference, candidate);
  const Eigen::Index m = reference.cols(), c = candidate.cols();
  // best(i, j): the best pairing of the first i references with the first j
  // candidates, ordered by (pairs made, sum of MACs).
  struct Score {
    Eigen::Index pairs = 0;
    double sum = 0;
    bool operator<(const Score& o) const {
      return pairs != o.pairs ? pairs < o.pairs : sum < o.sum;
    }
    bool operator==(const Score& o) const { return pairs == o.pairs && sum == o.sum; }
  };
  std::vector<std::vector<Score>> best(m + 1, std::vector<Score>(c + 1));
  for (Eigen::Index i = 1; i <= m; ++i) {
    for (Eigen::Index j = 1; j <= c; ++j) {
      Score s = std::max(best[i - 1][j], best[i][j - 1]);
      const Score paired{best[i - 1][j - 1].pairs + 1,
                         best[i - 1][j - 1].sum + mac(i - 1, j - 1)};
      best[i][j] = s < paired ? paired : s;
    }
  }
  std::vector<ModePair> pairs(m);
  for (Eigen::Index i = 0; i < m; ++i) pairs[i].reference = static_cast<int>(i);
  for (Eigen::Index i = m, j = c; i > 0 && j > 0;) {
    const Score paired{best[i - 1][j - 1].pairs + 1,
                       best[i - 1][j - 1].sum + mac(i - 1, j - 1)};
    if (best[i][j] == paired) {
      pairs[i - 1].candidate = static_cast<int>(j - 1);
      pairs[i - 1].mac = mac(i - 1, j - 1);
      --i;
      --j;
    } else if (best[i][j] == best[i][j - 1]) {
      --j;
    } else {
      --i;
    }
  }
  return pairs;
}

}  // namespace femup
