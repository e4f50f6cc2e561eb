#include "femup/solvers/bagged_posterior.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <string>

#include "femup/core/counter_rng.h"
#include "femup/core/errors.h"

namespace femup {

namespace {

const char* const kWhere = "bagged_posterior";

std::string At(std::size_t c, const char* what) {
  std::ostringstream s;
  s << "classes[" << c << "]." << what;
  return s.str();
}

void Check(const std::vector<ClassFit>& classes) {
  if (classes.empty()) throw InputError(kWhere, "needs at least one class");
  const Eigen::Index n = classes[0].residual.size();
  if (n == 0) throw InputError(At(0, "residual"), "is empty");
  for (std::size_t c = 0; c < classes.size(); ++c) {
    const ClassFit& f = classes[c];
    if (f.residual.size() != n) {
      std::ostringstream msg;
      msg << "has " << f.residual.size() << " rows; classes[0] has " << n;
      throw InputError(At(c, "residual"), msg.str());
    }
    if (!f.residual.allFinite() || !std::isfinite(f.log_evidence))
      throw InputError(At(c, "residual"), "residuals and log evidence must be finite");
    if (!(f.prior > 0) || !std::isfinite(f.prior))
      throw InputError(At(c, "prior"), "must be positive and finite");
  }
}

}  // namespace

Invalid BaggingOptions::Validate() const {
  if (copies < 1) {
    std::ostringstream msg;
    msg << "must be at least 1, got " << copies;
    return {"copies", msg.str()};
  }
  return {};
}

Eigen::VectorXd BaggedPosteriorProbabilities(const std::vector<ClassFit>& classes,
                                             const BaggingOptions& options,
                                             const std::vector<int>& strata) {
  ThrowIfInvalid(options.Validate(), kWhere);
  Check(classes);
  const Eigen::Index m = static_cast<Eigen::Index>(classes.size());
  const Eigen::Index n = classes[0].residual.size();
  if (!strata.empty() && strata.size() != static_cast<std::size_t>(n))
    throw InputError(std::string(kWhere) + ".strata", "needs one stratum per residual");
  // The rows of each stratum (one stratum of every row when none are given).
  std::map<int, std::vector<Eigen::Index>> rows;
  for (Eigen::Index i = 0; i < n; ++i)
    rows[strata.empty() ? 0 : strata[static_cast<std::size_t>(i)]].push_back(i);
  // Squared residuals, a column per class, and each class's score on the data.
  Eigen::MatrixXd squared(n, m);
  Eigen::VectorXd base(m);
  for (Eigen::Index c = 0; c < m; ++c) {
    const ClassFit& f = classes[static_cast<std::size_t>(c)];
    squared.col(c) = f.residual.cwiseAbs2();
    base[c] = f.log_evidence + std::log(f.prior) + 0.5 * squared.col(c).sum();
  }
  Eigen::VectorXd mean = Eigen::VectorXd::Zero(m);
  Eigen::VectorXd w(n);
  for (int b = 0; b < options.copies; ++b) {
    // Multinomial weights: as many draws from each stratum as it has rows,
    // each row equally likely.
    CounterRng rng(options.seed, static_cast<std::uint64_t>(b), 0);
    w.setZero();
    for (const auto& [stratum, in] : rows) {
      const std::size_t size = in.size();
      for (std::size_t d = 0; d < size; ++d) {
        const double u = static_cast<double>(rng() >> 11) * 0x1.0p-53;
        w[in[std::min(size - 1,
                      static_cast<std::size_t>(u * static_cast<double>(size)))]] += 1;
      }
    }
    Eigen::VectorXd score = base - 0.5 * (squared.transpose() * w);
    score.array() -= score.maxCoeff();
    const Eigen::ArrayXd p = score.array().exp();
    mean += (p / p.sum()).matrix();
  }
  return mean / options.copies;
}

}  // namespace femup
