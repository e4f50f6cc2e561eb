// The iterative eigen-sensitivity updating problem: residuals between measured
// and predicted modes (eigenvalues, and mode shapes at the sensors) as nonlinear
// functions of the correction factors d, with the analytic Jacobian (eigenvalue
// derivatives, Nelson eigenvector derivatives). Model modes are paired with the
// measured ones at every evaluation. Any NonlinearSolver takes the result.
//
// Residuals, for each state s (in the given order), each measured mode j (in the
// measured order), paired with model mode (lambda, phi) of (K~, M~dry) or
// (K~, M~wet) as the state's immersion says:
//   eigenvalue:  (lambda / lambda_meas - 1) / frequency_sigma,
//                lambda_meas = (2 pi f_meas)^2; label "<state> mode <j> lambda".
//   shape (when use_shapes and the state has shapes), one per sensor i:
//                (c s_i - t_i) / (shape_sigma * max_i |t_i|) (shape_noise "max"),
//                or / (shape_sigma * max(|t_i|, entry_floor max_i |t_i|))
//                ("entry"); label "<state> mode <j> shape <dof label>".
//                s: phi at the sensor DOFs; psi: the measured shape there;
//                t and c by shape_scaling:
//                  "fit"  t = psi / max_i |psi_i| (largest entry +-1), c the
//                         modal scale factor that minimises the mode's weighted
//                         shape residuals (it also carries the sign);
//                  "unit" t = psi / ||psi||, c = sign / ||s||;
//                  "mass" t = psi (mass-normalised data), c = sign;
//                sign = +1 when s' psi >= 0, else -1.
//     With "fit" and "unit" the data's shape scaling is free: a positive factor
//     leaves the residuals unchanged, a negative one negates them. "mass" uses
//     the scale, which fixes the mass/stiffness scaling below.
// then, optionally:
//   prior:       (x_i - prior_mean_i) / prior_sigma_i for each parameter with a
//                prior (0 < prior_sigma_i < inf); label "prior <name>".
//   Tikhonov:    tikhonov_lambda * L (x - prior_mean) (prior_mean empty: zero),
//                L = tikhonov_operator (empty: identity); label "tikhonov <row>".
//
// Mass and stiffness scale together without changing eigenvalues or the
// directions of the shapes, so (1 + mass and stiffness factors, added-mass
// factors) scaled by a common number is a null direction of the data residuals
// unless shape_scaling is "mass": fix one factor (problem.fixed; the paper fixes
// mass 4), or give a prior.
#pragma once

#include <Eigen/Core>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "femup/core/fe/model.h"
#include "femup/core/invalid.h"
#include "femup/core/linalg/modal.h"
#include "femup/core/sysid/measurement.h"
#include "femup/problems/nonlinear_problem.h"
#include "femup/problems/parametrised_pencil.h"
#include "femup/problems/ritz_basis.h"

namespace femup {

struct EigenSensitivityOptions {
  // Add the shape residuals of states that have shapes (else eigenvalues only).
  bool use_shapes = true;
  // Relative standard deviation of a measured eigenvalue lambda = (2 pi f)^2.
  double frequency_sigma = 0.002;
  // Standard deviation of a measured shape entry, relative to the shape's
  // largest-magnitude entry.
  double shape_sigma = 0.02;
  // How shape noise scales: "max" (sigma times the shape's largest entry, the
  // same for every sensor) or "entry" (sigma times each entry's own size, for
  // noise proportional to the entry; floored at entry_floor times the largest
  // entry so that near-nodal sensors do not get unbounded weight).
  std::string shape_noise = "max";
  double entry_floor = 0.05;
  // How the model shape is scaled to the measured one: "fit" (by the weighted
  // least-squares modal scale factor), "unit" (both to unit Euclidean norm) or
  // "mass" (the measured shapes are mass-normalised, e.g. from FRFs with a
  // measured force: compared as they are, only the sign aligned).
  std::string shape_scaling = "fit";
  // Model modes computed beyond the number measured in a state (capped at the
  // number of DOFs), so that pairing can pick a model mode out of order.
  int extra_modes = 4;
  // Pair measured with model modes by MAC at the sensors at every evaluation
  // (states without shapes, or false here: measured mode j is model mode j).
  bool pair_by_mac = true;
  // A measured mode whose pair would have MAC below this fails the evaluation
  // (the step is rejected). In [0, 1].
  double min_mac = 0.0;
  // Optional Gaussian prior: both empty, or prior_sigma of size n (entries <= 0
  // or infinite: no prior on that parameter) and prior_mean of size n or empty
  // (zero). prior_mean is also the centre of the Tikhonov term.
  Eigen::VectorXd prior_mean;
  Eigen::VectorXd prior_sigma;
  // Optional Tikhonov rows tikhonov_lambda * L (x - prior_mean); none when 0.
  // L: p x n, empty = identity.
  double tikhonov_lambda = 0.0;
  Eigen::MatrixXd tikhonov_operator;
  // Threads for the Jacobian: the modes of a state get their eigenvector
  // derivatives (a sparse factorisation each and one solve per parameter) in
  // parallel. The Jacobian is the same whatever the number (>= 1).
  int threads = 1;
  // Eigen-solver settings; num_modes is set per state (measured + extra_modes).
  EigenOptions eigen;
  // Evaluate on this reduced model instead of the full one (null: full).
  std::shared_ptr<const RitzBasis> ritz;

  // Ok when valid, else the field and what is wrong. Sizes that depend on the
  // model are checked by BuildEigenSensitivityProblem.
  Invalid Validate() const;
};

// The problem over x = the factors d of `model`: every parameter, in the model's
// order, named as the model names them, grouped by kind ("mass", "stiffness",
// "added_mass"). Starts at `start` (n), or at zero (the nominal model) when
// `start` is empty. Nothing is fixed and there are no bounds: the caller adds
// them. residuals_whitened is true. The problem holds its own copies of the
// model and the data.
//
// Evaluation never throws: it returns false, with the reason in *why, when the
// eigen-solve fails (e.g. M~ not positive definite), when a measured mode cannot
// be paired (MAC below min_mac), or when a paired eigenvalue is repeated (the
// eigenvector derivative does not exist); x of the wrong size or not finite also
// returns false. Jacobian columns of added-mass factors are zero in dry states.
//
// Throws InputError naming the field for invalid options, no state, a state's
// data that ModalData::Validate rejects (e.g. a sensor DOF out of range), more
// modes measured than the model has DOFs, a model without parameters, or
// prior, Tikhonov or start sizes that do not match the model.
NonlinearProblem BuildEigenSensitivityProblem(const ParametrisedModel& model,
                                              const std::vector<ModalData>& states,
                                              const EigenSensitivityOptions& options,
                                              const Eigen::VectorXd& start = {});

// The same output-error problem over the unknowns of any pencil (the one engine
// behind the updating above and the effect fits: parametrised_pencil.h): names
// and groups from the pencil, the same residuals, options and errors; the
// Jacobian from the pencil's dK/dx and dM/dx at x. The problem shares the pencil.
// Throws InputError as above, and when the pencil has no unknown.
NonlinearProblem BuildOutputErrorProblem(std::shared_ptr<const ParametrisedPencil> pencil,
                                         const std::vector<ModalData>& states,
                                         const EigenSensitivityOptions& options,
                                         const Eigen::VectorXd& start = {});

// A measured mode's misfit read back from the output-error residuals above
// (BuildOutputErrorProblem's data rows, in its order, as evaluated with
// `options` on `states`): the paired model mode's frequency, lambda = lambda_meas
// (1 + frequency_sigma r), and where the state's shapes are residuals, the MAC
// at the sensors of that mode's shape with the measured one (the model shape
// up to its scale is t + r / w, t the target and w the weight of each entry).
// What a fit predicts, mode by mode, without solving the model again.
struct PairedModeMisfit {
  int state = 0;  // index into states
  int mode = 0;   // the measured mode's index in its state (0: the first)
  double measured_hz = 0;
  double model_hz = 0;
  double mac = std::numeric_limits<double>::quiet_NaN();  // NaN: shapes not compared
};

// Throws InputError("residual", ...) where the residual has fewer rows than the
// states' modes need, and as BuildOutputErrorProblem does for a zero shape.
std::vector<PairedModeMisfit> PairedModeMisfits(const std::vector<ModalData>& states,
                                                const EigenSensitivityOptions& options,
                                                const Eigen::VectorXd& residual);

}  // namespace femup
