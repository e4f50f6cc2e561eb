// The model's own form error on the measured data, as RankModelEffects allows
// for it (effect_ranking.h, EffectRankingOptions::formulation_error): where the
// structure's builder knows a richer formulation of it
// (Structure::form_variants: a frame of shear-deformable members, a finer
// mesh, a shear building's flexural deformation), each variant moves the
// nominal model's residuals by u_j, in noise units, to first order through the
// engine's own eigen-derivatives at the nominal model's paired modes. The
// covariance of the rows it covers (the frequencies; with
// EffectRankingOptions::form_error_on_shapes the shapes too) is then
// I + sum_j u_j u_j' (one standard deviation of form error along each
// variant's change), and a class is judged on its residuals and Jacobian
// whitened by it (by its symmetric inverse square root).
//
// Also here, the two ways a fitted class is moved to the mode of its whitened
// misfit before its evidence is taken: one Gauss-Newton step
// (GaussNewtonStepInForm; EffectRankingOptions::form_step) or a fit to
// convergence from its raw fit (FitToWhitenedMode; form_fit).
#pragma once

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <vector>

#include "femup/core/fe/form_variant.h"
#include "femup/core/fe/model.h"
#include "femup/core/fe/structure.h"
#include "femup/core/sysid/measurement.h"
#include "femup/problems/eigen_sensitivity.h"
#include "femup/problems/model_effects.h"
#include "femup/problems/nonlinear_problem.h"
#include "femup/solvers/nonlinear_solver.h"
#include "femup/studies/effect_ranking.h"

namespace femup {

// The nominal model (no effect) with the given extra unknowns (none: one whose
// basis is zero, since the engine needs an unknown), as the engine's
// output-error problem on the measured states, starting at zero.
NonlinearProblem NominalOutputErrorProblem(const Structure& structure,
                                           std::vector<Parameter> unknowns,
                                           const std::vector<ModalData>& states,
                                           const EigenSensitivityOptions& options);

// Which of an output-error problem's residual rows are eigenvalue rows (their
// labels end in " lambda"; the others are shape entries and priors).
std::vector<char> FrequencyRows(const NonlinearProblem& problem);

// A form variant's change of the nominal model's residuals, to first order:
// the nominal model moved along (K_v - K, M_v - M) by the engine's own
// eigen-derivatives at the nominal modes. The variant's own modes are not
// paired with the data: with few sensors or frequencies only, a variant whose
// modes swap order would be paired with other modes than the nominal's, and
// its "change" would be the distance between two modes. A variant on DOFs of
// its own (a finer mesh) is taken on the model's DOFs first (OnModelDofs).
// Throws InputError("measurements", ...) where the engine cannot compare it
// with the data.
Eigen::VectorXd FormVariantChange(const Structure& structure, const FormVariant& variant,
                                  const std::vector<ModalData>& states,
                                  const EigenSensitivityOptions& options);

// What the user states of the nominal model's overall stiffness and mass
// (relative standard deviations: EffectRankingOptions::stiffness_uncertainty,
// mass_uncertainty) as form variants on the model's DOFs: the model with its
// stiffness times (1 + stiffness), and with its mass times (1 + mass); none
// for a zero. Both move every frequency by the same relative amount (half the
// value, in opposite senses), so together they are one direction of the
// frequencies' covariance, of variance (stiffness^2 + mass^2) / 4 relative to
// a frequency: an overall error the user already expects, not a gap.
std::vector<FormVariant> StatedUncertaintyVariants(const Structure& structure,
                                                   double stiffness, double mass);

class ModelFormError {
 public:
  // No form error allowed for: not Active(), and Whiten and Unwhiten leave
  // every residual as it is.
  ModelFormError() = default;

  // From the residuals' rows (covered: which rows the form error is allowed
  // for on, the eigenvalue rows or every row) and the variants' changes of the
  // covered rows (each of the covered rows' count, in noise units). Active
  // where at least one row is covered, even with no direction (the covariance
  // is then the identity). Throws InputError("form_error", ...) for a direction
  // of another length or with a value that is not finite.
  ModelFormError(std::vector<char> covered,
                 const std::vector<Eigen::VectorXd>& directions);

  // Measured on the data: every one of `variants` (FormVariantChange; the
  // structure's form_variants, StatedUncertaintyVariants) on the frequency rows
  // of the nominal model's residuals (is_frequency), and on every row where
  // `shapes_too` (a variant that moves the shapes at the sensors, as a chain's
  // flexural deformation does in a tall building, is then allowed for there
  // too). For the report, each variant's size (`allowances`, appended: the
  // largest relative frequency change, a lambda row being in units of
  // 2 frequency_sigma, and the change's norm on the frequency rows in noise
  // units). Not Active, and nothing appended, where there is no variant or the
  // data no frequency.
  static ModelFormError Measure(const Structure& structure,
                                const std::vector<FormVariant>& variants,
                                const std::vector<ModalData>& states,
                                const EigenSensitivityOptions& options,
                                const std::vector<char>& is_frequency, bool shapes_too,
                                double frequency_sigma,
                                std::vector<FormErrorAllowance>* allowances);

  bool Active() const { return !covered_rows_.empty(); }
  // The rows the form error is allowed for on, in order.
  const std::vector<int>& covered_rows() const { return covered_rows_; }
  // The rank of the variants' changes (columns of an orthonormal basis).
  int NumDirections() const { return static_cast<int>(basis_.cols()); }

  // The covered rows of a residual, and of its Jacobian where `j` is not
  // null, whitened (C^-1/2 r, C^-1/2 the covariance's symmetric inverse square
  // root, the same whatever the rows' order), or turned back into raw ones
  // (C^1/2 r). Rows not covered are left as they are.
  // Throws InputError("residual", ...) for a residual of another length than
  // the covered flags, or a Jacobian whose rows do not match it.
  void Whiten(Eigen::VectorXd* r, Eigen::MatrixXd* j) const;
  void Unwhiten(Eigen::VectorXd* r, Eigen::MatrixXd* j) const;

  // The share of a raw Jacobian's squared norm (every row) whose covered
  // rows lie along the variants' changes: 1 for a class that can change the
  // data only as the model's own form error does; 0 where there is no
  // direction or the Jacobian is zero.
  double ShareAlongVariants(const Eigen::MatrixXd& raw_jacobian) const;

 private:
  void Transform(Eigen::VectorXd* r, Eigen::MatrixXd* j, bool back) const;

  std::size_t num_rows_ = 0;
  std::vector<int> covered_rows_;
  Eigen::MatrixXd basis_;  // orthonormal basis Q of the u_j
  // I + sum_j u_j u_j' = I + P L P' (P = Q V, orthonormal columns): its
  // symmetric square root is I + P diag(root_shift_) P', and that root's
  // inverse I + P diag(inverse_root_shift_) P'.
  Eigen::MatrixXd eigenbasis_;
  Eigen::VectorXd root_shift_, inverse_root_shift_;
};

// A class's parameter box and its stated normal priors linearised at its theta
// (LocalNormalPriors: sigma 0, or both empty, where the prior is uniform).
struct ClassPriors {
  Eigen::VectorXd lower, upper;
  Eigen::VectorXd mean, sigma;
  // sum over the normal priors of ((theta - mean) / sigma)^2.
  double Misfit(const Eigen::VectorXd& theta) const;
};

// One Gauss-Newton step from theta on |r + J d|^2 + priors.Misfit(theta + d)
// (r and J whitened), its end kept in the box: the end where it lowers that
// misfit, nothing where it does not (or J has no column).
std::optional<Eigen::VectorXd> GaussNewtonStepInForm(const Eigen::VectorXd& theta,
                                                     const Eigen::VectorXd& residual,
                                                     const Eigen::MatrixXd& jacobian,
                                                     const ClassPriors& priors);

// An instance fitted again on the whitened misfit, its stated normal priors'
// residuals with it, from `from` (where its raw fit ended) to convergence.
// ok only where the fit's misfit comes out below `from_misfit` (the whitened
// misfit and the priors' at `from`); then its end, the data's residual and
// Jacobian there, whitened and raw.
struct WhitenedModeFit {
  Eigen::VectorXd from;
  bool ok = false;
  Eigen::VectorXd theta, residual, raw_residual;
  Eigen::MatrixXd jacobian, raw_jacobian;
};

WhitenedModeFit FitToWhitenedMode(const ModelFormError& form,
                                  const std::shared_ptr<const Structure>& structure,
                                  const std::shared_ptr<const ModelEffect>& effect,
                                  const std::vector<ModalData>& states,
                                  const EigenSensitivityOptions& options,
                                  const NonlinearSolver& solver,
                                  const Eigen::VectorXd& from, double from_misfit);

}  // namespace femup
