// Mode-shape expansion: a measured shape known at sensor DOFs, extended to every
// DOF of the model, so that methods needing full shapes (the paper's Z d = F)
// can use test data.
//   "serep"   System Equivalent Reduction Expansion Process (O'Callahan et al.):
//             phi = Phi (Phi_a)^+ psi, Phi the model's lowest `num_modes` modes,
//             Phi_a their rows at the sensors. Exact for a shape in span(Phi).
//   "lsq"     least-squares modal expansion: the same fit of modal coordinates,
//             but the measured entries are kept as measured (only the other DOFs
//             come from the fit).
//   "dynamic" dynamic (Guyan when lambda = 0) expansion from the model's
//             matrices: phi_o = -(K_oo - lambda M_oo)^-1 (K_oa - lambda M_oa) psi,
//             lambda the measured eigenvalue; measured entries kept.
// Quality: MAC between the expansion's values at the sensors, before they are
// replaced by the measured ones, and the measured shape (1 when the model's
// subspace explains the data), and the condition number of the fit.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "femup/core/fe/model.h"
#include "femup/core/invalid.h"
#include "femup/core/linalg/modal.h"

namespace femup {

struct ExpansionOptions {
  std::string method = "serep";  // serep | lsq | dynamic
  int num_modes = 0;             // serep/lsq: model modes used; 0 = number of sensors
  Invalid Validate() const;      // ok, or the field and what is wrong
};

struct ExpandedShape {
  Eigen::VectorXd shape;        // every DOF
  double sensor_mac = 0;        // fit at the sensors vs the measured shape
  double condition_number = 0;  // of Phi_a (serep, lsq); 0 for dynamic
};

// `model_modes`: M-normalised modes of the model (at least num_modes of them).
// `sensors`: DOF index of each entry of `measured`; distinct, in range. Throws
// InputError naming the field for bad sizes, repeated or out-of-range sensors,
// more modes than sensors, or a singular K_oo - lambda M_oo.
ExpandedShape ExpandShape(const SparseMatrix& stiffness, const SparseMatrix& mass,
                          const Modes& model_modes, const std::vector<int>& sensors,
                          const Eigen::VectorXd& measured, double eigenvalue,
                          const ExpansionOptions& options);

// The same for sensors between nodes (sensor.h): `sensors` is the sensors x
// DOFs matrix whose rows read a full shape. serep fits Phi_a = sensors * Phi;
// lsq is serep here (no DOF is measured to keep); dynamic needs sensors on
// DOFs and is refused, naming serep and lsq.
ExpandedShape ExpandShape(const SparseMatrix& stiffness, const SparseMatrix& mass,
                          const Modes& model_modes, const SparseMatrix& sensors,
                          const Eigen::VectorXd& measured, double eigenvalue,
                          const ExpansionOptions& options);

}  // namespace femup
