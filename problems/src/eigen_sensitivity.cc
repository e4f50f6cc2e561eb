#include "femup/problems/eigen_sensitivity.h"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>
#include <sstream>
#include <utility>

#include "femup/core/errors.h"
#include "femup/core/linalg/eigen_derivatives.h"
#include "femup/core/parallel.h"
#include "mode_pairing.h"
#include "output_error_context.h"

namespace femup {
namespace {

using output_error::AlignRepeatedModes;
using output_error::AtSensors;
using output_error::Context;
using output_error::PairMeasuredModes;
using output_error::ScaleShape;
using output_error::ShapeScale;
using output_error::StateTerms;

bool Fail(std::string* why, const std::string& message) {
  if (why != nullptr) *why = message;
  return false;
}

// Where paired model modes have a repeated eigenvalue, their eigenvectors are
// replaced by the M-orthonormal combinations of the eigenspace that best match
// the measured shapes paired with them at the sensors, and each keeps the eigenspace
// for its derivative. Without this the shape residuals jump from one
// evaluation to the next by the eigensolver's arbitrary rotation. The Jacobian
// rows of these modes move the eigenspace (NelsonSolver with the cluster) but
// hold the fitted rotation: an approximation (5 % of the column on a square
// frame's mass, EigenSensitivity.RepeatedEigenvaluesAreRotatedToTheMeasuredShapes)
// that slows the last iterations, not where they converge. An
// eigenspace that may extend beyond the modes solved (it holds the last one)
// is left as it is.
template <typename Terms>
void RotateRepeatedModes(const StateTerms& st, const Modes& modes,
                         const std::vector<int>& pairing, std::vector<Terms>* terms) {
  const Eigen::Index num = modes.size();
  Eigen::Index first = 0;
  while (first < num) {
    const Eigen::Index last = LastOfRepeated(modes, first);  // modes first..last
    std::vector<Eigen::Index> measured;
    for (std::size_t j = 0; j < pairing.size(); ++j) {
      if (pairing[j] >= first && pairing[j] <= last)
        measured.push_back(static_cast<Eigen::Index>(j));
    }
    if (last > first && last + 1 < num && !measured.empty()) {
      const Eigen::MatrixXd basis = modes.shapes.middleCols(first, last - first + 1);
      const Eigen::MatrixXd at_sensors = AtSensors(st, basis);
      const Eigen::MatrixXd targets = st.targets(Eigen::all, measured);
      // Each measured shape's least-squares combination of the eigenspace at
      // the sensors, normalised; then the nearest orthonormal set (the polar
      // factor), which keeps the combinations M-orthonormal eigenvectors. Exact
      // data in any rotation give that rotation back.
      Eigen::MatrixXd combination =
          at_sensors.jacobiSvd(Eigen::ComputeThinU | Eigen::ComputeThinV).solve(targets);
      bool seen = true;
      for (Eigen::Index q = 0; q < combination.cols(); ++q) {
        const double norm = combination.col(q).norm();
        if (!(norm > 0) || !std::isfinite(norm)) seen = false;
        if (seen) combination.col(q) /= norm;
      }
      if (!seen) {  // the sensors do not see a measured mode in this eigenspace
        first = last + 1;
        continue;
      }
      Eigen::JacobiSVD<Eigen::MatrixXd> svd(combination,
                                            Eigen::ComputeThinU | Eigen::ComputeThinV);
      const Eigen::MatrixXd rotation = svd.matrixU() * svd.matrixV().transpose();
      for (std::size_t q = 0; q < measured.size(); ++q) {
        Terms& t = (*terms)[static_cast<std::size_t>(measured[q])];
        t.phi = basis * rotation.col(static_cast<Eigen::Index>(q));
        t.cluster = basis;
      }
    }
    first = last + 1;
  }
}

// The projected pencil of a state's immersion, when the problem has a Ritz basis.
struct Reduced {
  const Eigen::MatrixXd* basis = nullptr;       // V, n x r
  const Eigen::MatrixXd* mass_basis = nullptr;  // M(x0) V
  Eigen::MatrixXd k, m;                         // V' K(x) V, V' M(x) V
};

// V' B V for a derivative basis B, from B's own DOFs.
Eigen::MatrixXd Project(const BasisMatrix& b, const Eigen::MatrixXd& v) {
  const Eigen::MatrixXd at_dofs = v(b.dofs(), Eigen::all);
  return at_dofs.transpose() * b.RestrictedProduct(v);
}

// Residuals (and Jacobian rows) of one state, given K~ and the state's M~ at x
// (or, with `reduced`, their projections).
bool EvaluateState(const Context& c, const StateTerms& st, const Eigen::VectorXd& x,
                   const SparseMatrix& k, const SparseMatrix& m, const Reduced* reduced,
                   Eigen::VectorXd* r, Eigen::MatrixXd* jac, std::string* why) {
  Modes modes;
  Eigen::VectorXd reduced_values;   // every eigenvalue of the projected pencil
  Eigen::MatrixXd reduced_vectors;  // its eigenvectors, V' M V-orthonormal
  if (reduced != nullptr) {
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(reduced->k,
                                                                     reduced->m);
    if (solver.info() != Eigen::Success || !solver.eigenvalues().allFinite()) {
      return Fail(why, st.name +
                           ": the reduced eigen-solve failed (the projected mass matrix "
                           "is not positive definite)");
    }
    reduced_values = solver.eigenvalues();
    reduced_vectors = solver.eigenvectors();
    const Eigen::Index count =
        std::min<Eigen::Index>(st.num_model_modes, reduced_values.size());
    modes.eigenvalues = reduced_values.head(count);
    modes.shapes = *reduced->basis * reduced_vectors.leftCols(count);
  } else {
    EigenOptions eigen = c.eigen;
    eigen.num_modes = st.num_model_modes;
    EigenSolution solution;
    try {
      solution = TrySolveModes(k, m, eigen);
    } catch (const InputError& e) {
      return Fail(why, st.name + ": eigen-solve failed: " + e.what());
    }
    if (!solution.ok())
      return Fail(why, st.name + ": eigen-solve failed: " + solution.failure);
    modes = std::move(solution.modes);
  }
  if (modes.size() < st.lambdas.size()) {
    return Fail(why, st.name + ": the eigen-solve returned too few modes");
  }

  // Measured mode j is paired with model mode pairing[j].
  std::vector<int> pairing;
  if (st.pair_by_mac) AlignRepeatedModes(st, &modes);
  if (!PairMeasuredModes(c, st, modes, &pairing, why)) return false;

  // Residuals mode by mode; what the Jacobian rows of each mode need is kept.
  struct ModeTerms {
    int row = 0;
    double lambda = 0, lambda_weight = 0, c_scale = 1;
    Eigen::VectorXd phi, s, dc_ds;
    Eigen::MatrixXd cluster;  // phi's eigenspace when its eigenvalue is repeated
  };
  std::vector<ModeTerms> terms(st.lambdas.size());
  for (Eigen::Index j = 0; j < st.lambdas.size(); ++j) {
    terms[j].phi = modes.shapes.col(pairing[j]);
  }
  if (st.shape_residuals) RotateRepeatedModes(st, modes, pairing, &terms);
  for (Eigen::Index j = 0; j < st.lambdas.size(); ++j) {
    ModeTerms& t = terms[j];
    t.row = st.first_row + static_cast<int>(j) * st.rows_per_mode();
    const int row = t.row;
    t.lambda = modes.eigenvalues[pairing[j]];
    t.lambda_weight = 1.0 / (st.lambdas[j] * c.frequency_sigma);
    (*r)[row] = (t.lambda / st.lambdas[j] - 1.0) / c.frequency_sigma;

    // The model shape at the sensors enters as c s (ScaleShape); c's
    // derivative is linear in the shape's: dc = dc_ds' ds.
    const Eigen::Index num_sensors = static_cast<Eigen::Index>(st.num_sensors());
    if (st.shape_residuals) {
      t.s = AtSensors(st, t.phi);
      const Eigen::VectorXd& s = t.s;
      const Eigen::VectorXd target = st.targets.col(j);
      if (!(s.norm() > 0)) {
        std::ostringstream msg;
        msg << st.name << " mode " << j + 1 << ": the paired model mode "
            << pairing[j] + 1 << " is zero at every sensor";
        return Fail(why, msg.str());
      }
      ShapeScale scale = ScaleShape(st, j, s);
      t.c_scale = scale.c;
      t.dc_ds = std::move(scale.dc_ds);
      r->segment(row + 1, num_sensors) =
          st.shape_weights.col(j).cwiseProduct(t.c_scale * s - target);
    }
  }
  if (jac == nullptr) return true;

  // Jacobian rows, mode by mode in parallel (c.threads): each mode factorises
  // its own Nelson matrix and writes only its own rows, so the result does not
  // depend on the thread count.
  PencilDerivatives derivatives;
  c.pencil->Derivatives(x, st.wet, &derivatives);
  const int num_parameters = c.pencil->num_parameters();
  if (reduced != nullptr) {
    // Modal expansion over every projected mode outside the paired mode's
    // eigenspace: d phi = sum_k q_k' (dK - lambda dM) q / (lambda - lambda_k) q_k
    // - (q' dM q / 2) q, lifted by V (the same fixed-rotation rule as above for
    // repeated eigenvalues).
    const Eigen::MatrixXd& v = *reduced->basis;
    const Eigen::MatrixXd v_at_sensors = AtSensors(st, v);
    std::vector<Eigen::VectorXd> q(terms.size());
    for (std::size_t j = 0; j < terms.size(); ++j) {
      q[j] = reduced->mass_basis->transpose() * terms[j].phi;
    }
    for (int p = 0; p < num_parameters; ++p) {
      const BasisMatrix* dk = derivatives.stiffness[p];
      const BasisMatrix* dm = derivatives.mass[p];
      if (dk == nullptr && dm == nullptr) continue;
      const Eigen::MatrixXd dkr = dk != nullptr ? Project(*dk, v) : Eigen::MatrixXd();
      const Eigen::MatrixXd dmr = dm != nullptr ? Project(*dm, v) : Eigen::MatrixXd();
      for (std::size_t j = 0; j < terms.size(); ++j) {
        const ModeTerms& t = terms[j];
        Eigen::VectorXd g = Eigen::VectorXd::Zero(q[j].size());
        double mass_form = 0;
        if (dk != nullptr) g += dkr * q[j];
        if (dm != nullptr) {
          const Eigen::VectorXd dm_q = dmr * q[j];
          g -= t.lambda * dm_q;
          mass_form = q[j].dot(dm_q);
        }
        (*jac)(t.row, p) = t.lambda_weight * q[j].dot(g);
        if (!st.shape_residuals) continue;
        Eigen::VectorXd coefficient = reduced_vectors.transpose() * g;
        for (Eigen::Index i = 0; i < coefficient.size(); ++i) {
          const double gap = t.lambda - reduced_values[i];
          coefficient[i] =
              std::abs(gap) <= kRepeatedEigenvalueTolerance * std::abs(t.lambda)
                  ? 0.0
                  : coefficient[i] / gap;
        }
        const Eigen::VectorXd dq = reduced_vectors * coefficient - 0.5 * mass_form * q[j];
        const Eigen::VectorXd ds = v_at_sensors * dq;
        const Eigen::Index num_sensors = static_cast<Eigen::Index>(st.num_sensors());
        jac->block(t.row + 1, p, num_sensors, 1) =
            st.shape_weights.col(static_cast<Eigen::Index>(j))
                .cwiseProduct(t.dc_ds.dot(ds) * t.s + t.c_scale * ds);
      }
    }
    return true;
  }
  std::vector<std::string> failure(st.lambdas.size());
  ParallelFor(static_cast<int>(st.lambdas.size()), c.threads, [&](int j) {
    const ModeTerms& t = terms[j];
    const int row = t.row;
    const Eigen::Index num_sensors = static_cast<Eigen::Index>(st.num_sensors());
    std::unique_ptr<NelsonSolver> nelson;
    if (st.shape_residuals) {
      nelson = t.cluster.cols() > 1
                   ? std::make_unique<NelsonSolver>(k, m, t.lambda, t.phi, t.cluster)
                   : std::make_unique<NelsonSolver>(k, m, t.lambda, t.phi);
      if (!nelson->ok()) {
        std::ostringstream msg;
        msg << st.name << " mode " << j + 1 << " (model mode " << pairing[j] + 1
            << "): no eigenvector derivative: " << nelson->message();
        failure[j] = msg.str();
        return;
      }
    }
    for (int p = 0; p < num_parameters; ++p) {
      const BasisMatrix* dk = derivatives.stiffness[p];
      const BasisMatrix* dm = derivatives.mass[p];
      if (dk == nullptr && dm == nullptr) continue;
      if (!nelson) {
        (*jac)(row, p) = t.lambda_weight * EigenvalueDerivative(t.phi, t.lambda, dk, dm);
        continue;
      }
      const EigenpairDerivative d = nelson->Derivative(dk, dm);
      (*jac)(row, p) = t.lambda_weight * d.eigenvalue;
      const Eigen::VectorXd ds = AtSensors(st, d.eigenvector);
      // d(c s) = dc s + c ds.
      jac->block(row + 1, p, num_sensors, 1) =
          st.shape_weights.col(j).cwiseProduct(t.dc_ds.dot(ds) * t.s + t.c_scale * ds);
    }
  });
  for (const std::string& f : failure) {
    if (!f.empty()) return Fail(why, f);
  }
  return true;
}

bool Evaluate(const Context& c, const Eigen::VectorXd& x, Eigen::VectorXd* r,
              Eigen::MatrixXd* jac, std::string* why) {
  const int n = c.pencil->num_parameters();
  if (x.size() != n) {
    return Fail(why, "x has " + std::to_string(x.size()) + " entries; expected " +
                         std::to_string(n));
  }
  if (!x.allFinite()) return Fail(why, "x has a NaN or infinite entry");
  r->setZero(c.num_residuals);
  if (jac != nullptr) jac->setZero(c.num_residuals, n);
  try {
    // Assembled (and projected) once per immersion that a state needs.
    SparseMatrix k[2], m[2];
    Reduced reduced[2];
    for (const StateTerms& st : c.states) {
      const int w = st.wet ? 1 : 0;
      if (m[w].size() == 0) {
        c.pencil->Assemble(x, st.wet, &k[w], &m[w]);
        if (c.ritz) {
          Reduced& red = reduced[w];
          red.basis = st.wet ? &c.ritz->wet : &c.ritz->dry;
          red.mass_basis = st.wet ? &c.ritz->mass_times_wet : &c.ritz->mass_times_dry;
          const Eigen::MatrixXd& v = *red.basis;
          red.k = v.transpose() * (k[w].selfadjointView<Eigen::Lower>() * v);
          red.m = v.transpose() * (m[w].selfadjointView<Eigen::Lower>() * v);
          // Symmetric to rounding, for the dense solver.
          red.k = (0.5 * (red.k + red.k.transpose())).eval();
          red.m = (0.5 * (red.m + red.m.transpose())).eval();
        }
      }
      if (!EvaluateState(c, st, x, k[w], m[w], c.ritz ? &reduced[w] : nullptr, r, jac,
                         why)) {
        return false;
      }
    }
  } catch (const InputError& e) {
    return Fail(why, e.what());
  } catch (const NumericalError& e) {
    return Fail(why, e.what());
  }

  int row = c.prior_first_row;
  for (int i : c.prior_index) {
    (*r)[row] = (x[i] - c.prior_mean[i]) / c.prior_sigma[i];
    if (jac != nullptr) (*jac)(row, i) = 1.0 / c.prior_sigma[i];
    ++row;
  }
  if (c.tikhonov.rows() > 0) {
    r->segment(row, c.tikhonov.rows()) = c.tikhonov * (x - c.prior_mean);
    if (jac != nullptr) jac->middleRows(row, c.tikhonov.rows()) = c.tikhonov;
  }
  return true;
}

// The measured shapes as the shape residuals compare them (psi / max |psi|
// for "fit", psi / ||psi|| for "unit", psi for "mass") and each entry's weight,
// 1 / its standard deviation in that scale. A mode that is zero at every
// sensor is an error where its shape is a residual; otherwise its weights are
// zero (its frequency alone pairs it).
void ShapeTargets(const ModalData& data, const EigenSensitivityOptions& options,
                  bool shape_residuals, const std::string& where,
                  Eigen::MatrixXd* targets, Eigen::MatrixXd* weights) {
  *targets = data.shapes;
  weights->resize(data.shapes.rows(), data.num_modes());
  for (int j = 0; j < data.num_modes(); ++j) {
    double peak = data.shapes.col(j).cwiseAbs().maxCoeff();
    if (!(peak > 0) && !shape_residuals) {
      weights->col(j).setZero();
      continue;
    }
    if (!(peak > 0)) {
      throw InputError(where + ".shapes",
                       "mode " + std::to_string(j + 1) + " is zero at every sensor");
    }
    if (options.shape_scaling == "fit") targets->col(j) /= peak;
    if (options.shape_scaling == "unit") targets->col(j).normalize();
    // The noise is relative to the shape in the residual's scale.
    peak = targets->col(j).cwiseAbs().maxCoeff();
    for (Eigen::Index k = 0; k < targets->rows(); ++k) {
      const double scale =
          options.shape_noise == "entry"
              ? std::max(std::abs((*targets)(k, j)), options.entry_floor * peak)
              : peak;
      (*weights)(k, j) = 1.0 / (options.shape_sigma * scale);
    }
  }
}

bool HasPrior(double sigma) { return sigma > 0 && std::isfinite(sigma); }

}  // namespace

Invalid EigenSensitivityOptions::Validate() const {
  if (!(frequency_sigma > 0) || !std::isfinite(frequency_sigma)) {
    return {"frequency_sigma", "must be positive and finite"};
  }
  if (shape_scaling != "fit" && shape_scaling != "unit" && shape_scaling != "mass")
    return {"shape_scaling", "expected fit, unit or mass, got '" + shape_scaling + "'"};
  if (shape_noise != "max" && shape_noise != "entry")
    return {"shape_noise", "expected max or entry, got '" + shape_noise + "'"};
  if (!(entry_floor > 0 && entry_floor <= 1)) return {"entry_floor", "must be in (0, 1]"};
  if (!(shape_sigma > 0) || !std::isfinite(shape_sigma)) {
    return {"shape_sigma", "must be positive and finite"};
  }
  if (extra_modes < 0) return {"extra_modes", "must be >= 0"};
  if (threads < 1) return {"threads", "must be >= 1"};
  if (!(min_mac >= 0 && min_mac <= 1)) return {"min_mac", "must be in [0, 1]"};
  if (!prior_mean.allFinite()) return {"prior_mean", "has a NaN or infinite entry"};
  if (prior_sigma.hasNaN()) return {"prior_sigma", "has a NaN entry"};
  if (!(tikhonov_lambda >= 0) || !std::isfinite(tikhonov_lambda)) {
    return {"tikhonov_lambda", "must be finite and >= 0"};
  }
  if (!tikhonov_operator.allFinite()) {
    return {"tikhonov_operator", "has a NaN or infinite entry"};
  }
  EigenOptions eigen_checked = eigen;
  eigen_checked.num_modes = 1;  // set per state at evaluation
  // EigenOptions' messages name their field: kept as "eigen: num_modes must ...".
  if (const Invalid bad = eigen_checked.Validate()) return {"eigen", bad.message};
  return {};
}

NonlinearProblem BuildEigenSensitivityProblem(const ParametrisedModel& model,
                                              const std::vector<ModalData>& states,
                                              const EigenSensitivityOptions& options,
                                              const Eigen::VectorXd& start) {
  if (model.num_parameters() == 0) {
    throw InputError("model.parameters", "the model has no correction factor to update");
  }
  return BuildOutputErrorProblem(std::make_shared<const ModelPencil>(model), states,
                                 options, start);
}

NonlinearProblem BuildOutputErrorProblem(std::shared_ptr<const ParametrisedPencil> pencil,
                                         const std::vector<ModalData>& states,
                                         const EigenSensitivityOptions& options,
                                         const Eigen::VectorXd& start) {
  if (const Invalid bad = options.Validate())
    throw InputError("eigen sensitivity options", bad.ToString());
  if (!pencil) throw InputError("pencil", "no model is given");
  const int n = pencil->num_parameters();
  const int num_dofs = pencil->num_dofs();
  if (n == 0) throw InputError("parameters", "there is no unknown to fit");
  if (states.empty()) throw InputError("states", "no measured state is given");
  auto size_error = [n](const std::string& field, Eigen::Index size) {
    std::ostringstream msg;
    msg << "has " << size << " entries; expected " << n
        << " (one per model parameter) or none";
    return InputError(field, msg.str());
  };
  if (options.prior_mean.size() != 0 && options.prior_mean.size() != n) {
    throw size_error("options.prior_mean", options.prior_mean.size());
  }
  if (options.prior_sigma.size() != 0 && options.prior_sigma.size() != n) {
    throw size_error("options.prior_sigma", options.prior_sigma.size());
  }
  if (options.tikhonov_operator.size() != 0 && options.tikhonov_operator.cols() != n) {
    std::ostringstream msg;
    msg << "has " << options.tikhonov_operator.cols() << " columns; expected " << n
        << " (one per model parameter)";
    throw InputError("options.tikhonov_operator", msg.str());
  }
  if (start.size() != 0 && start.size() != n) throw size_error("start", start.size());
  if (!start.allFinite()) throw InputError("start", "has a NaN or infinite entry");

  auto context = std::make_shared<Context>();
  Context& c = *context;
  c.pencil = pencil;
  c.frequency_sigma = options.frequency_sigma;
  c.min_mac = options.min_mac;
  c.threads = options.threads;
  c.eigen = options.eigen;
  c.ritz = options.ritz;
  if (c.ritz) {
    for (const ModalData& data : states) {
      const bool wet = data.immersion == Immersion::kWet;
      const Eigen::MatrixXd& v = wet ? c.ritz->wet : c.ritz->dry;
      const Eigen::MatrixXd& mv = wet ? c.ritz->mass_times_wet : c.ritz->mass_times_dry;
      if (v.rows() != num_dofs || v.cols() == 0 || mv.rows() != v.rows() ||
          mv.cols() != v.cols()) {
        std::ostringstream msg;
        msg << "the " << (wet ? "wet" : "dry") << " basis is " << v.rows() << " x "
            << v.cols() << " (M V " << mv.rows() << " x " << mv.cols() << "); expected "
            << num_dofs << " rows (one per DOF) and at least one column";
        throw InputError("options.ritz", msg.str());
      }
    }
  }

  NonlinearProblem problem;
  int row = 0;
  for (std::size_t i = 0; i < states.size(); ++i) {
    const ModalData& data = states[i];
    const std::string where =
        "states." + (data.state.empty() ? std::to_string(i + 1) : data.state);
    data.Validate(num_dofs, where);
    if (data.num_modes() > num_dofs) {
      std::ostringstream msg;
      msg << data.num_modes() << " modes measured; the model has only " << num_dofs
          << " DOFs";
      throw InputError(where + ".frequencies", msg.str());
    }
    StateTerms st;
    st.name = data.state.empty() ? "state " + std::to_string(i + 1) : data.state;
    st.wet = data.immersion == Immersion::kWet;
    if (data.HasInterpolatedSensors()) {
      st.observe = data.sensor_weights;
    } else if (data.sensor_dofs.empty()) {
      st.sensors.resize(num_dofs);
      std::iota(st.sensors.begin(), st.sensors.end(), 0);
    } else {
      st.sensors = data.sensor_dofs;
    }
    st.lambdas = data.Eigenvalues();
    st.shapes = data.shapes;
    st.pair_by_mac = options.pair_by_mac && data.HasShapes();
    st.shape_residuals = options.use_shapes && data.HasShapes();
    st.num_model_modes = std::min(num_dofs, data.num_modes() + options.extra_modes);
    st.first_row = row;
    // The targets and weights serve the pairing too, where shapes pair the
    // modes but are not residuals.
    if (data.HasShapes()) {
      st.scaling = options.shape_scaling;
      ShapeTargets(data, options, st.shape_residuals, where, &st.targets,
                   &st.shape_weights);
    }
    for (int j = 0; j < data.num_modes(); ++j) {
      const std::string mode = st.name + " mode " + std::to_string(j + 1);
      problem.residual_labels.push_back(mode + " lambda");
      if (!st.shape_residuals) continue;
      for (int q = 0; q < st.num_sensors(); ++q) {
        const std::string sensor =
            st.observe.size() == 0
                ? pencil->dof_labels()[st.sensors[static_cast<std::size_t>(q)]]
            : q < static_cast<int>(data.sensor_names.size())
                ? data.sensor_names[static_cast<std::size_t>(q)]
                : "sensor " + std::to_string(q + 1);
        problem.residual_labels.push_back(mode + " shape " + sensor);
      }
    }
    row += data.num_modes() * st.rows_per_mode();
    c.states.push_back(std::move(st));
  }

  const std::vector<std::string> names = pencil->ParameterNames();
  c.prior_first_row = row;
  c.prior_mean = options.prior_mean.size() == n ? options.prior_mean
                                                : Eigen::VectorXd::Zero(n).eval();
  c.prior_sigma = options.prior_sigma;
  for (int i = 0; i < options.prior_sigma.size(); ++i) {
    if (!HasPrior(options.prior_sigma[i])) continue;
    c.prior_index.push_back(i);
    problem.residual_labels.push_back("prior " + names[i]);
    ++row;
  }
  if (options.tikhonov_lambda > 0) {
    c.tikhonov = options.tikhonov_lambda * (options.tikhonov_operator.size() == 0
                                                ? Eigen::MatrixXd::Identity(n, n).eval()
                                                : options.tikhonov_operator);
    for (Eigen::Index i = 0; i < c.tikhonov.rows(); ++i) {
      problem.residual_labels.push_back("tikhonov " + std::to_string(i + 1));
    }
    row += static_cast<int>(c.tikhonov.rows());
  }
  c.num_residuals = row;

  problem.num_residuals = row;
  problem.initial = start.size() == n ? start : Eigen::VectorXd::Zero(n).eval();
  problem.names = names;
  problem.groups = pencil->ParameterGroups();
  problem.residuals_whitened = true;
  std::shared_ptr<const Context> shared = std::move(context);
  problem.evaluate = [shared](const Eigen::VectorXd& x, Eigen::VectorXd* residuals,
                              Eigen::MatrixXd* jacobian, std::string* why) {
    return Evaluate(*shared, x, residuals, jacobian, why);
  };
  return problem;
}

std::vector<PairedModeMisfit> PairedModeMisfits(const std::vector<ModalData>& states,
                                                const EigenSensitivityOptions& options,
                                                const Eigen::VectorXd& residual) {
  std::vector<PairedModeMisfit> out;
  Eigen::Index row = 0;
  for (std::size_t i = 0; i < states.size(); ++i) {
    const ModalData& data = states[i];
    const bool shape_residuals = options.use_shapes && data.HasShapes();
    Eigen::MatrixXd targets, weights;
    if (shape_residuals) {
      ShapeTargets(data, options, true, "states." + std::to_string(i + 1), &targets,
                   &weights);
    }
    const Eigen::Index sensors = shape_residuals ? targets.rows() : 0;
    const Eigen::VectorXd lambdas = data.Eigenvalues();
    for (int j = 0; j < data.num_modes(); ++j) {
      if (row + 1 + sensors > residual.size()) {
        throw InputError("residual", std::to_string(residual.size()) +
                                         " rows: fewer than the states' modes need");
      }
      PairedModeMisfit m;
      m.state = static_cast<int>(i);
      m.mode = j;
      m.measured_hz = data.frequencies_hz[j];
      const double lambda = lambdas[j] * (1.0 + options.frequency_sigma * residual[row]);
      m.model_hz = std::sqrt(std::max(lambda, 0.0)) / (2.0 * 3.14159265358979323846);
      if (shape_residuals) {
        // r = w (c s - t): the model shape, up to its scale c, is t + r / w.
        const Eigen::VectorXd t = targets.col(j);
        const Eigen::VectorXd s =
            t + residual.segment(row + 1, sensors).cwiseQuotient(weights.col(j));
        const double st = s.dot(t);
        m.mac = st * st / (s.squaredNorm() * t.squaredNorm());
      }
      out.push_back(m);
      row += 1 + sensors;
    }
  }
  return out;
}

}  // namespace femup
