#include "model_form_error.h"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>

#include "femup/core/errors.h"
#include "femup/problems/effect_priors.h"
#include "femup/problems/model_effect_pencil.h"
#include "femup/problems/parametrised_pencil.h"

namespace femup {

NonlinearProblem NominalOutputErrorProblem(const Structure& structure,
                                           std::vector<Parameter> unknowns,
                                           const std::vector<ModalData>& states,
                                           const EigenSensitivityOptions& options) {
  ParametrisedModel model(structure.stiffness, structure.mass, structure.dof_labels);
  if (unknowns.empty()) {
    Parameter unused;
    unused.name = "nominal";
    unused.kind = ParameterKind::kStiffness;
    unused.basis = BasisMatrix(SparseMatrix(model.num_dofs(), model.num_dofs()));
    unknowns.push_back(std::move(unused));
  }
  const int n = static_cast<int>(unknowns.size());
  for (Parameter& p : unknowns) model.AddParameter(std::move(p));
  return BuildOutputErrorProblem(std::make_shared<const ModelPencil>(std::move(model)),
                                 states, options, Eigen::VectorXd::Zero(n));
}

std::vector<char> FrequencyRows(const NonlinearProblem& problem) {
  std::vector<char> out;
  for (const std::string& label : problem.residual_labels) {
    const std::string_view suffix = " lambda";
    out.push_back(label.size() >= suffix.size() &&
                  label.compare(label.size() - suffix.size(), suffix.size(), suffix) ==
                      0);
  }
  return out;
}

Eigen::VectorXd FormVariantChange(const Structure& structure, const FormVariant& variant,
                                  const std::vector<ModalData>& states,
                                  const EigenSensitivityOptions& options) {
  // A variant on DOFs of its own (a finer mesh): as the model's modes that can
  // be paired with the data move on it.
  int modes = 1;
  for (const ModalData& d : states)
    modes = std::max(modes, d.num_modes() + options.extra_modes);
  const FormVariant v = OnModelDofs(
      structure, variant, std::min(modes, static_cast<int>(structure.stiffness.rows())));
  std::vector<Parameter> unknowns(2);
  unknowns[0].name = "form variant stiffness";
  unknowns[0].kind = ParameterKind::kStiffness;
  unknowns[0].basis =
      BasisMatrix(SparseMatrix((v.stiffness - structure.stiffness).pruned()));
  unknowns[1].name = "form variant mass";
  unknowns[1].kind = ParameterKind::kMass;
  unknowns[1].basis = BasisMatrix(SparseMatrix((v.mass - structure.mass).pruned()));
  const NonlinearProblem problem =
      NominalOutputErrorProblem(structure, unknowns, states, options);
  Eigen::VectorXd r;
  Eigen::MatrixXd j;
  std::string why;
  if (!problem.evaluate(Eigen::VectorXd::Zero(2), &r, &j, &why)) {
    throw InputError("measurements", "the model's form variant (" + v.name +
                                         ") cannot be compared with the data: " + why);
  }
  return j.col(0) + j.col(1);
}

ModelFormError::ModelFormError(std::vector<char> covered,
                               const std::vector<Eigen::VectorXd>& directions)
    : num_rows_(covered.size()) {
  for (std::size_t r = 0; r < covered.size(); ++r)
    if (covered[r]) covered_rows_.push_back(static_cast<int>(r));
  const auto rows = static_cast<Eigen::Index>(covered_rows_.size());
  for (std::size_t k = 0; k < directions.size(); ++k) {
    if (directions[k].size() != rows || !directions[k].allFinite()) {
      throw InputError("form_error", "direction " + std::to_string(k) + " has " +
                                         std::to_string(directions[k].size()) +
                                         " values, expected one finite value for "
                                         "each of the " +
                                         std::to_string(rows) + " covered rows");
    }
  }
  if (rows == 0 || directions.empty()) return;
  Eigen::MatrixXd u(rows, static_cast<Eigen::Index>(directions.size()));
  for (std::size_t j = 0; j < directions.size(); ++j)
    u.col(static_cast<Eigen::Index>(j)) = directions[j];
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(u);
  // No column where the variants change no covered row (rank 0): then no class
  // lies along them, and the covariance is the identity.
  basis_ = qr.householderQ() * Eigen::MatrixXd::Identity(rows, qr.rank());
  if (basis_.cols() == 0) return;
  // The covered rows' covariance C = I + U U' = I + Q S Q' (Q the basis, S =
  // Q'U U'Q, a square of the variants' count), and with S = V L V' its powers
  // C^p = I + (Q V) ((1 + L)^p - 1) (Q V)': the symmetric square root and its
  // inverse without a square of the rows' count (a jacket has a thousand of
  // them once the shapes are covered).
  // Any W with W' W = C^-1 gives every class the same chi2 and Laplace
  // evidence, but the bagged posterior resamples the whitened rows one by
  // one: a Cholesky factor would put nearly all of a residual along a
  // direction shared by every row into the first covered row, and the
  // copies that do not draw that row (a third of them) would see none of it.
  // C^-1/2 is the whitening nearest the identity and the same whatever the
  // rows' order: a residual along u_j stays spread over the rows as u_j is.
  const Eigen::MatrixXd qu = basis_.transpose() * u;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(qu * qu.transpose());
  const Eigen::VectorXd spread = eig.eigenvalues().cwiseMax(0.0).array() + 1.0;
  eigenbasis_ = basis_ * eig.eigenvectors();
  root_shift_ = spread.cwiseSqrt().array() - 1.0;
  inverse_root_shift_ = spread.cwiseSqrt().cwiseInverse().array() - 1.0;
}

std::vector<FormVariant> StatedUncertaintyVariants(const Structure& structure,
                                                   double stiffness, double mass) {
  std::vector<FormVariant> out;
  const auto percent = [](double x) {
    std::ostringstream s;
    s << std::setprecision(3) << 100 * x << " %";
    return s.str();
  };
  if (stiffness != 0) {
    FormVariant v;
    v.name = "the stated uncertainty of the model's overall stiffness (" +
             percent(stiffness) + ")";
    v.stiffness = (1 + stiffness) * structure.stiffness;
    v.mass = structure.mass;
    out.push_back(std::move(v));
  }
  if (mass != 0) {
    FormVariant v;
    v.name = "the stated uncertainty of the model's overall mass (" + percent(mass) + ")";
    v.stiffness = structure.stiffness;
    v.mass = (1 + mass) * structure.mass;
    out.push_back(std::move(v));
  }
  return out;
}

ModelFormError ModelFormError::Measure(const Structure& structure,
                                       const std::vector<FormVariant>& variants,
                                       const std::vector<ModalData>& states,
                                       const EigenSensitivityOptions& options,
                                       const std::vector<char>& is_frequency,
                                       bool shapes_too, double frequency_sigma,
                                       std::vector<FormErrorAllowance>* allowances) {
  const bool any_frequency =
      std::any_of(is_frequency.begin(), is_frequency.end(), [](char f) { return f; });
  if (variants.empty() || !any_frequency) return {};
  const std::vector<char> covered =
      shapes_too ? std::vector<char>(is_frequency.size(), 1) : is_frequency;
  const auto num_covered = static_cast<Eigen::Index>(
      std::count_if(covered.begin(), covered.end(), [](char f) { return f != 0; }));
  std::vector<Eigen::VectorXd> directions;
  for (const FormVariant& v : variants) {
    const Eigen::VectorXd change = FormVariantChange(structure, v, states, options);
    if (change.size() != static_cast<Eigen::Index>(is_frequency.size())) {
      throw InputError("measurements", "the model's form variant (" + v.name +
                                           ") gives " + std::to_string(change.size()) +
                                           " residuals, the nominal model " +
                                           std::to_string(is_frequency.size()));
    }
    Eigen::VectorXd u(num_covered);
    double largest = 0, squared = 0;  // on the frequency rows
    Eigen::Index k = 0;
    for (std::size_t r = 0; r < covered.size(); ++r) {
      const double c = change[static_cast<Eigen::Index>(r)];
      if (is_frequency[r]) {
        largest = std::max(largest, std::abs(c));
        squared += c * c;
      }
      if (covered[r]) u[k++] = c;
    }
    if (allowances != nullptr) {
      // Relative frequency change: a lambda row is in units of 2 sigma_f.
      allowances->push_back({v.name, largest * frequency_sigma, std::sqrt(squared)});
    }
    directions.push_back(std::move(u));
  }
  return ModelFormError(covered, directions);
}

void ModelFormError::Transform(Eigen::VectorXd* r, Eigen::MatrixXd* j, bool back) const {
  if (!Active()) return;
  if (static_cast<std::size_t>(r->size()) != num_rows_ ||
      (j != nullptr && static_cast<std::size_t>(j->rows()) != num_rows_)) {
    throw InputError("residual", std::to_string(r->size()) + " residuals" +
                                     (j != nullptr ? " and " + std::to_string(j->rows()) +
                                                         " Jacobian rows"
                                                   : std::string()) +
                                     ", expected " + std::to_string(num_rows_));
  }
  if (eigenbasis_.cols() == 0) return;  // the identity: no direction
  const Eigen::Index cols = j != nullptr ? j->cols() : 0;
  const auto rows = static_cast<Eigen::Index>(covered_rows_.size());
  Eigen::VectorXd rf(rows);
  Eigen::MatrixXd jf(rows, cols);
  for (Eigen::Index k = 0; k < rows; ++k) {
    rf[k] = (*r)[covered_rows_[static_cast<std::size_t>(k)]];
    if (cols > 0) jf.row(k) = j->row(covered_rows_[static_cast<std::size_t>(k)]);
  }
  // C^p x = x + P ((1 + L)^p - 1) P'x.
  const Eigen::VectorXd& shift = back ? root_shift_ : inverse_root_shift_;
  rf += eigenbasis_ * shift.asDiagonal() * (eigenbasis_.transpose() * rf);
  if (cols > 0) jf += eigenbasis_ * shift.asDiagonal() * (eigenbasis_.transpose() * jf);
  for (Eigen::Index k = 0; k < rows; ++k) {
    (*r)[covered_rows_[static_cast<std::size_t>(k)]] = rf[k];
    if (cols > 0) j->row(covered_rows_[static_cast<std::size_t>(k)]) = jf.row(k);
  }
}

void ModelFormError::Whiten(Eigen::VectorXd* r, Eigen::MatrixXd* j) const {
  Transform(r, j, false);
}

void ModelFormError::Unwhiten(Eigen::VectorXd* r, Eigen::MatrixXd* j) const {
  Transform(r, j, true);
}

double ModelFormError::ShareAlongVariants(const Eigen::MatrixXd& raw_jacobian) const {
  const Eigen::MatrixXd& j = raw_jacobian;
  if (basis_.cols() == 0 || j.cols() == 0 || !(j.squaredNorm() > 0)) return 0;
  if (static_cast<std::size_t>(j.rows()) != num_rows_) {
    throw InputError("jacobian", std::to_string(j.rows()) + " rows, expected " +
                                     std::to_string(num_rows_));
  }
  Eigen::MatrixXd jf(static_cast<Eigen::Index>(covered_rows_.size()), j.cols());
  for (std::size_t k = 0; k < covered_rows_.size(); ++k)
    jf.row(static_cast<Eigen::Index>(k)) = j.row(covered_rows_[k]);
  return (basis_.transpose() * jf).squaredNorm() / j.squaredNorm();
}

double ClassPriors::Misfit(const Eigen::VectorXd& theta) const {
  double sum = 0;
  for (Eigen::Index q = 0; q < sigma.size(); ++q)
    if (sigma[q] > 0) sum += std::pow((theta[q] - mean[q]) / sigma[q], 2);
  return sum;
}

std::optional<Eigen::VectorXd> GaussNewtonStepInForm(const Eigen::VectorXd& theta,
                                                     const Eigen::VectorXd& residual,
                                                     const Eigen::MatrixXd& jacobian,
                                                     const ClassPriors& priors) {
  const Eigen::MatrixXd& j = jacobian;
  if (j.cols() == 0) return std::nullopt;
  const Eigen::Index n = j.cols(), m = j.rows();
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(m + n, n);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(m + n);
  a.topRows(m) = j;
  b.head(m) = -residual;
  for (Eigen::Index q = 0; q < priors.sigma.size(); ++q) {
    if (!(priors.sigma[q] > 0)) continue;
    a(m + q, q) = 1.0 / priors.sigma[q];
    b[m + q] = -(theta[q] - priors.mean[q]) / priors.sigma[q];
  }
  const Eigen::VectorXd step = a.completeOrthogonalDecomposition().solve(b);
  const Eigen::VectorXd to = (theta + step).cwiseMax(priors.lower).cwiseMin(priors.upper);
  const Eigen::VectorXd moved = residual + j * (to - theta);
  if (!(moved.squaredNorm() + priors.Misfit(to) <
        residual.squaredNorm() + priors.Misfit(theta))) {
    return std::nullopt;
  }
  return to;
}

WhitenedModeFit FitToWhitenedMode(const ModelFormError& form,
                                  const std::shared_ptr<const Structure>& structure,
                                  const std::shared_ptr<const ModelEffect>& effect,
                                  const std::vector<ModalData>& states,
                                  const EigenSensitivityOptions& options,
                                  const NonlinearSolver& solver,
                                  const Eigen::VectorXd& from, double from_misfit) {
  WhitenedModeFit out;
  out.from = from;
  const std::vector<EffectParameter> params = effect->Parameters();
  NonlinearProblem data =
      BuildModelEffectFitProblem(structure, {effect}, states, options, from);
  const NonlinearProblem::Evaluate raw = data.evaluate;
  data.evaluate = [raw, &form](const Eigen::VectorXd& x, Eigen::VectorXd* r,
                               Eigen::MatrixXd* j, std::string* why) {
    if (!raw(x, r, j, why)) return false;
    try {
      form.Whiten(r, j);
    } catch (const InputError& e) {
      if (why != nullptr) *why = e.what();
      return false;
    }
    return true;
  };
  const int rows = data.num_residuals;
  const NonlinearProblem problem = WithPriorResiduals(std::move(data), params);
  const NonlinearSolution sol = solver.Solve(problem);
  if (sol.residual.size() != problem.num_residuals || !sol.residual.allFinite() ||
      sol.jacobian.rows() != problem.num_residuals || !sol.jacobian.allFinite() ||
      !(sol.residual.squaredNorm() < from_misfit)) {
    return out;
  }
  out.ok = true;
  out.theta = sol.x;
  out.residual = sol.residual.head(rows);
  out.jacobian = sol.jacobian.topRows(rows);
  out.raw_residual = out.residual;
  out.raw_jacobian = out.jacobian;
  form.Unwhiten(&out.raw_residual, &out.raw_jacobian);
  return out;
}

}  // namespace femup
