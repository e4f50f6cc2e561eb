#include "femup/solvers/regularisation.h"

#include <Eigen/QR>
#include <Eigen/SVD>
#include <algorithm>
#include <boost/math/tools/minima.hpp>
#include <boost/math/tools/roots.hpp>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>

#include "femup/core/errors.h"

namespace femup {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
}  // namespace

Invalid RegularisationOptions::Validate() const {
  const std::vector<std::string> rules = {"gcv", "lcurve", "discrepancy",
                                          "quasi_optimality", "fixed"};
  if (std::find(rules.begin(), rules.end(), parameter_choice) == rules.end())
    return {"parameter_choice",
            "unknown rule '" + parameter_choice +
                "' (choose gcv, lcurve, discrepancy, quasi_optimality or fixed)"};
  const std::vector<std::string> ops = {"identity", "first_difference",
                                        "second_difference", "problem"};
  if (std::find(ops.begin(), ops.end(), op) == ops.end())
    return {"operator",
            "unknown operator '" + op +
                "' (choose identity, first_difference, second_difference or problem)"};
  std::ostringstream msg;
  if (parameter_choice == "fixed" && !(lambda >= 0 && std::isfinite(lambda))) {
    msg << "must be finite and >= 0 for the fixed rule, got " << lambda;
    return {"lambda", msg.str()};
  }
  if (parameter_choice == "discrepancy" &&
      !(noise_norm > 0 && std::isfinite(noise_norm))) {
    msg << "the discrepancy principle needs the noise norm ||e|| > 0, got " << noise_norm;
    return {"noise_norm", msg.str()};
  }
  if (!(discrepancy_factor >= 1 && std::isfinite(discrepancy_factor))) {
    msg << "must be >= 1, got " << discrepancy_factor;
    return {"discrepancy_factor", msg.str()};
  }
  if (grid_points < 3) {
    msg << "must be at least 3, got " << grid_points;
    return {"grid_points", msg.str()};
  }
  if (!(lambda_min >= 0) || !(lambda_max >= 0) || !std::isfinite(lambda_min) ||
      !std::isfinite(lambda_max) || (lambda_max > 0 && lambda_min >= lambda_max)) {
    msg << "need 0 <= lambda_min < lambda_max (0 = automatic), got " << lambda_min
        << " and " << lambda_max;
    return {"lambda_min/lambda_max", msg.str()};
  }
  return {};
}

TikhonovPath::TikhonovPath(const Eigen::MatrixXd& a, const Eigen::VectorXd& b,
                           const Eigen::MatrixXd& l, const Eigen::VectorXd& x0,
                           int source_rows, double residual_offset)
    : m_(static_cast<int>(a.rows())), n_(static_cast<int>(a.cols())), a_(a) {
  if (b.size() != a.rows()) throw InputError("tikhonov", "A and b sizes differ");
  if (l.size() > 0 && l.cols() != a.cols())
    throw InputError("tikhonov", "the regulariser has the wrong number of columns");
  x0_ = x0.size() > 0 ? x0 : Eigen::VectorXd::Zero(n_);
  b_ = b - a * x0_;

  Eigen::MatrixXd w;  // orthonormal basis of null(L)
  if (l.size() == 0) {
    p_ = n_;
    l_pinv_a_ = Eigen::MatrixXd::Identity(n_, n_);
    x_null_map_ = Eigen::MatrixXd::Zero(n_, m_);
  } else {
    // L = U S V': keep its row space (rank p), so ||L x|| = ||S_p V_p' x||.
    Eigen::JacobiSVD<Eigen::MatrixXd> lsvd(l, Eigen::ComputeFullV);
    const Eigen::VectorXd& s = lsvd.singularValues();
    const double tol = s.size() > 0 ? 1e-12 * s[0] * std::max(l.rows(), l.cols()) : 0.0;
    p_ = 0;
    while (p_ < s.size() && s[p_] > tol) ++p_;
    const Eigen::MatrixXd vp = lsvd.matrixV().leftCols(p_);
    w = lsvd.matrixV().rightCols(n_ - p_);
    const Eigen::MatrixXd l_pinv = vp * s.head(p_).cwiseInverse().asDiagonal();
    if (w.cols() > 0) {
      // A-weighted pseudo-inverse (Elden): the null-space component is fitted
      // without regularisation, L_A^+ = (I - W (A W)^+ A) L^+.
      const Eigen::MatrixXd aw = a * w;
      Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(aw);
      if (cod.rank() < aw.cols())
        throw InputError("tikhonov",
                         "A is blind to part of the regulariser's null space (e.g. a "
                         "constant for a difference operator): lambda cannot fix it");
      const Eigen::MatrixXd t = cod.pseudoInverse();
      x_null_map_ = w * t;
      l_pinv_a_ = l_pinv - w * (t * (a * l_pinv));
    } else {
      x_null_map_ = Eigen::MatrixXd::Zero(n_, m_);
      l_pinv_a_ = l_pinv;
    }
  }
  x_null_ = x_null_map_ * b_;
  const Eigen::MatrixXd a_bar = a * l_pinv_a_;
  const Eigen::VectorXd b_bar = b_ - a * x_null_;
  Eigen::BDCSVD<Eigen::MatrixXd> svd(a_bar, Eigen::ComputeThinU | Eigen::ComputeThinV);
  sigma_ = svd.singularValues();
  u_ = svd.matrixU();
  v_ = svd.matrixV();
  beta_ = u_.transpose() * b_bar;
  delta0_ = std::sqrt(std::max(0.0, b_bar.squaredNorm() - beta_.squaredNorm()) +
                      std::max(0.0, residual_offset));
  gcv_rows_ = std::max(m_, source_rows);
}

namespace {
// Filter factor f = s^2 / (s^2 + lambda^2); 0 for a zero singular value.
double Filter(double s, double lambda) {
  if (s <= 0) return 0.0;
  return s * s / (s * s + lambda * lambda);
}
}  // namespace

Eigen::VectorXd TikhonovPath::Solve(double lambda) const {
  Eigen::VectorXd c = Eigen::VectorXd::Zero(sigma_.size());
  for (Eigen::Index i = 0; i < sigma_.size(); ++i) {
    if (sigma_[i] > 0) c[i] = Filter(sigma_[i], lambda) * beta_[i] / sigma_[i];
  }
  return x0_ + l_pinv_a_ * (v_ * c) + x_null_;
}

double TikhonovPath::ResidualNorm(double lambda) const {
  double r2 = delta0_ * delta0_;
  for (Eigen::Index i = 0; i < sigma_.size(); ++i) {
    const double g = (1 - Filter(sigma_[i], lambda)) * beta_[i];
    r2 += g * g;
  }
  return std::sqrt(r2);
}

double TikhonovPath::SolutionNorm(double lambda) const {
  double e2 = 0;
  for (Eigen::Index i = 0; i < sigma_.size(); ++i) {
    if (sigma_[i] <= 0) continue;
    const double g = Filter(sigma_[i], lambda) * beta_[i] / sigma_[i];
    e2 += g * g;
  }
  return std::sqrt(e2);
}

double TikhonovPath::EffectiveParameters(double lambda) const {
  double t = n_ - p_;
  for (Eigen::Index i = 0; i < sigma_.size(); ++i) t += Filter(sigma_[i], lambda);
  return t;
}

double TikhonovPath::Gcv(double lambda) const {
  const double dof = gcv_rows_ - EffectiveParameters(lambda);
  if (dof <= 0) return std::numeric_limits<double>::infinity();
  const double r = ResidualNorm(lambda);
  return r * r / (dof * dof);
}

double TikhonovPath::Quasi(double lambda) const {
  double q2 = 0;
  for (Eigen::Index i = 0; i < sigma_.size(); ++i) {
    if (sigma_[i] <= 0) continue;
    const double f = Filter(sigma_[i], lambda);
    const double g = f * (1 - f) * beta_[i] / sigma_[i];
    q2 += g * g;
  }
  return std::sqrt(q2);
}

double TikhonovPath::Curvature(double lambda) const {
  // Curvature of (log ||A x - b||, log ||L x||) as a function of lambda, from the
  // first and second derivatives of eta = ||L x|| and rho = ||A x - b||
  // (Hansen, Rank-Deficient and Discrete Ill-Posed Problems, SIAM 1998, sec. 7.5).
  double eta = 0, rho = delta0_ * delta0_, phi = 0, psi = 0, dphi = 0, dpsi = 0;
  for (Eigen::Index i = 0; i < sigma_.size(); ++i) {
    if (sigma_[i] <= 0) {
      rho += beta_[i] * beta_[i];
      continue;
    }
    const double f = Filter(sigma_[i], lambda), cf = 1 - f;
    const double xi2 = (beta_[i] / sigma_[i]) * (beta_[i] / sigma_[i]);
    const double b2 = beta_[i] * beta_[i];
    const double f1 = -2 * f * cf / lambda;
    const double f2 = -f1 * (3 - 4 * f) / lambda;
    eta += f * f * xi2;
    rho += cf * cf * b2;
    phi += f * f1 * xi2;
    psi += cf * f1 * b2;
    dphi += (f1 * f1 + f * f2) * xi2;
    dpsi += (-f1 * f1 + cf * f2) * b2;
  }
  if (eta <= 0 || rho <= 0) return 0.0;
  // eta, rho as norms; derivatives in lambda, then of their logarithms.
  eta = std::sqrt(eta);
  rho = std::sqrt(rho);
  const double deta = phi / eta, drho = -psi / rho;
  const double ddeta = dphi / eta - deta * (deta / eta);
  const double ddrho = -dpsi / rho - drho * (drho / rho);
  const double dlogeta = deta / eta, dlogrho = drho / rho;
  const double ddlogeta = ddeta / eta - dlogeta * dlogeta;
  const double ddlogrho = ddrho / rho - dlogrho * dlogrho;
  const double den = std::pow(dlogrho * dlogrho + dlogeta * dlogeta, 1.5);
  if (den <= 0) return 0.0;
  // Positive where the curve turns like the L's corner (x = log rho, y = log eta).
  return (dlogrho * ddlogeta - ddlogrho * dlogeta) / den;
}

Eigen::MatrixXd TikhonovPath::Inverse(double lambda) const {
  Eigen::VectorXd d = Eigen::VectorXd::Zero(sigma_.size());
  for (Eigen::Index i = 0; i < sigma_.size(); ++i) {
    if (sigma_[i] > 0) d[i] = Filter(sigma_[i], lambda) / sigma_[i];
  }
  return l_pinv_a_ * (v_ * d.asDiagonal() * u_.transpose()) + x_null_map_;
}

double TikhonovPath::DefaultLambdaMax() const {
  return sigma_.size() > 0 && sigma_[0] > 0 ? sigma_[0] : 1.0;
}

double TikhonovPath::DefaultLambdaMin() const {
  const double smax = DefaultLambdaMax();
  double smin = smax;
  for (Eigen::Index i = 0; i < sigma_.size(); ++i) {
    if (sigma_[i] > 0) smin = std::min(smin, sigma_[i]);
  }
  return std::max(smin, 16 * std::numeric_limits<double>::epsilon() * smax);
}

namespace {

struct Optimum {
  double lambda = kNaN;
  bool at_end = false;
  std::string note;
};

// Minimises f(lambda) over [grid.front(), grid.back()] (log-spaced, ascending):
// every interior local minimum on the grid is refined by Brent's method in log
// lambda and the best one returned. When the grid has no interior minimum the
// better end point is returned and flagged, with the reason.
Optimum MinimiseOnGrid(const std::function<double(double)>& f,
                       const std::vector<double>& grid, const std::vector<double>& values,
                       const std::string& what) {
  Optimum best;
  double best_value = std::numeric_limits<double>::infinity();
  const int bits = std::numeric_limits<double>::digits / 2;
  auto in_log = [&f](double t) {
    const double v = f(std::exp(t));
    return std::isfinite(v) ? v : std::numeric_limits<double>::max();
  };
  const std::size_t g = grid.size();
  for (std::size_t i = 1; i + 1 < g; ++i) {
    if (!(values[i] <= values[i - 1] && values[i] <= values[i + 1])) continue;
    if (values[i] == values[i - 1] && values[i] == values[i + 1]) continue;  // flat
    const auto r = boost::math::tools::brent_find_minima(in_log, std::log(grid[i - 1]),
                                                         std::log(grid[i + 1]), bits);
    if (r.second < best_value) {
      best_value = r.second;
      best.lambda = std::exp(r.first);
    }
  }
  const bool low_end_better =
      values.front() < best_value && values.front() <= values.back();
  const bool high_end_better =
      values.back() < best_value && values.back() < values.front();
  std::ostringstream note;
  if (std::isnan(best.lambda)) {
    best.at_end = true;
    const bool low = values.front() <= values.back();
    best.lambda = low ? grid.front() : grid.back();
    note << what << " has no interior optimum in [" << grid.front() << ", " << grid.back()
         << "]: it decreases towards the " << (low ? "lower" : "upper")
         << " end; the end point is returned";
    best.note = note.str();
  } else if (low_end_better || high_end_better) {
    note << what << ": an end of the range ("
         << (low_end_better ? grid.front() : grid.back())
         << ") scores better than the interior optimum " << best.lambda
         << "; the interior one is returned";
    best.note = note.str();
  }
  return best;
}

}  // namespace

double ChooseLambda(const TikhonovPath& path, const RegularisationOptions& options,
                    RegularisationReport* report) {
  if (const Invalid bad = options.Validate()) {
    // where() names the field; the message keeps it too, as it always has.
    throw InputError(bad.Under("solver.regularisation").field, bad.ToString());
  }
  RegularisationReport local;
  RegularisationReport& rep = report ? *report : local;
  rep.parameter_choice = options.parameter_choice;

  const double lo = options.lambda_min > 0 ? options.lambda_min : path.DefaultLambdaMin();
  const double hi = options.lambda_max > 0 ? options.lambda_max : path.DefaultLambdaMax();
  const int k = options.grid_points;
  rep.grid_lambda.resize(k);
  rep.grid_residual_norm.resize(k);
  rep.grid_solution_norm.resize(k);
  rep.grid_gcv.resize(k);
  rep.grid_curvature.resize(k);
  rep.grid_quasi.resize(k);
  const double span = hi > lo ? std::log(hi / lo) : 0.0;
  for (int i = 0; i < k; ++i) {
    const double lambda = lo * std::exp(span * i / (k - 1));
    rep.grid_lambda[i] = lambda;
    rep.grid_residual_norm[i] = path.ResidualNorm(lambda);
    rep.grid_solution_norm[i] = path.SolutionNorm(lambda);
    rep.grid_gcv[i] = path.Gcv(lambda);
    rep.grid_curvature[i] = path.Curvature(lambda);
    rep.grid_quasi[i] = path.Quasi(lambda);
  }

  std::vector<double> neg_curvature(k);
  for (int i = 0; i < k; ++i) neg_curvature[i] = -rep.grid_curvature[i];
  const Optimum gcv = MinimiseOnGrid([&](double l) { return path.Gcv(l); },
                                     rep.grid_lambda, rep.grid_gcv, "the GCV function");
  const Optimum lcurve =
      MinimiseOnGrid([&](double l) { return -path.Curvature(l); }, rep.grid_lambda,
                     neg_curvature, "the L-curve curvature (negated)");
  const Optimum quasi =
      MinimiseOnGrid([&](double l) { return path.Quasi(l); }, rep.grid_lambda,
                     rep.grid_quasi, "the quasi-optimality function");
  Optimum discrepancy;
  if (options.noise_norm > 0) {
    const double target = options.discrepancy_factor * options.noise_norm;
    const double r_lo = path.ResidualNorm(lo), r_hi = path.ResidualNorm(hi);
    std::ostringstream note;
    if (target <= r_lo) {
      discrepancy.lambda = lo;
      discrepancy.at_end = true;
      note << "discrepancy principle: the target residual " << target
           << " is below the residual at the smallest lambda (" << r_lo
           << "); the noise level is smaller than the misfit A x - b can reach";
    } else if (target >= r_hi) {
      discrepancy.lambda = hi;
      discrepancy.at_end = true;
      note << "discrepancy principle: the target residual " << target
           << " exceeds the residual at the largest lambda (" << r_hi << ")";
    } else {
      // The residual grows monotonically with lambda: bracketed root in log lambda.
      auto g = [&](double t) {
        return std::log(path.ResidualNorm(std::exp(t)) / target);
      };
      std::uintmax_t iterations = 200;
      const auto root = boost::math::tools::toms748_solve(
          g, std::log(lo), std::log(hi), boost::math::tools::eps_tolerance<double>(50),
          iterations);
      discrepancy.lambda = std::exp(0.5 * (root.first + root.second));
    }
    discrepancy.note = note.str();
  }
  rep.lambda_gcv = gcv.lambda;
  rep.lambda_lcurve = lcurve.lambda;
  rep.lambda_quasi = quasi.lambda;
  rep.lambda_discrepancy = discrepancy.lambda;

  Optimum chosen;
  if (options.parameter_choice == "gcv") chosen = gcv;
  if (options.parameter_choice == "lcurve") chosen = lcurve;
  if (options.parameter_choice == "quasi_optimality") chosen = quasi;
  if (options.parameter_choice == "discrepancy") chosen = discrepancy;
  if (options.parameter_choice == "fixed") chosen.lambda = options.lambda;
  rep.lambda = chosen.lambda;
  rep.at_range_end = chosen.at_end;
  rep.note = chosen.note;
  return chosen.lambda;
}

}  // namespace femup
