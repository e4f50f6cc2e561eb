// Ritz bases: reduced models on which output-error fits of large models search
// cheaply (eigen_sensitivity.h evaluates on one when its options carry it).
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "femup/core/sysid/measurement.h"
#include "femup/problems/parametrised_pencil.h"

namespace femup {

struct EigenSensitivityOptions;

// A Ritz basis: a reduced model for searching fits of a large model cheaply.
// With one, the problem's eigenpairs are those of the projected pencil
// (V' K(x) V, V' M(x) V), lifted back by V, and its eigenvector derivatives are
// the projected pencil's (by modal expansion over all its r modes: exact for
// the projected pencil), lifted by V. An evaluation then costs two projections
// and a dense r x r eigenproblem instead of a sparse shift-invert solve and a
// sparse factorisation per mode. The residuals are the full model's where its
// modes lie in the span of V, and approximate them otherwise: search with it,
// then finish on the full model (effect_ranking.h does). BuildRitzBasis makes one.
struct RitzBasis {
  // n x r each, for the dry and the wet states (empty where no state needs it),
  // and mass_times_* = M(x0) V, with V M(x0)-orthonormal: a vector v in the span
  // of V has the coordinates (M(x0) V)' v.
  Eigen::MatrixXd dry, wet;
  Eigen::MatrixXd mass_times_dry, mass_times_wet;
};

// The Ritz basis for fits of `pencil` to `states` near x0: for each immersion
// the states use, the lowest modes of the pencil at x0 (as many as a state
// pairs, measured + extra_modes, plus extra_modes more), and for each paired
// mode phi_i and each unknown p the static corrections (K - sigma M)^-1 dK_p
// phi_i and (K - sigma M)^-1 dM_p phi_i at x0 (sigma = -lambda_1 / 2, so that
// the matrix is positive definite; one factorisation serves them all), which
// span the modes' first-order change (Nelson's derivative lies in the span of
// phi_i and (K - lambda_i M)^-1 (dK_p - lambda_i dM_p) phi_i, which the static
// corrections approximate for the low modes). The columns are made
// M(x0)-orthonormal; directions with a relative norm below 1e-10 are dropped.
// Throws InputError as BuildOutputErrorProblem does, and when the pencil at x0
// cannot be solved.
std::shared_ptr<const RitzBasis> BuildRitzBasis(const ParametrisedPencil& pencil,
                                                const std::vector<ModalData>& states,
                                                const EigenSensitivityOptions& options,
                                                const Eigen::VectorXd& x0);

}  // namespace femup
