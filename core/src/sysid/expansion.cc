#include "femup/core/sysid/expansion.h"

#include <Eigen/Dense>
#include <Eigen/SparseLU>
#include <algorithm>
#include <limits>
#include <sstream>

#include "femup/core/errors.h"

namespace femup {

Invalid ExpansionOptions::Validate() const {
  if (method != "serep" && method != "lsq" && method != "dynamic")
    return {"method", "expected serep, lsq or dynamic, got '" + method + "'"};
  if (num_modes < 0) return {"num_modes", "must be >= 0"};
  return {};
}

namespace {

// serep's fit: modal coordinates q = (Phi_a)^+ psi, the shape Phi q, and the
// condition number of Phi_a.
ExpandedShape FitModalCoordinates(const Eigen::MatrixXd& phi,
                                  const Eigen::MatrixXd& phi_a,
                                  const Eigen::VectorXd& measured) {
  ExpandedShape out;
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(phi_a,
                                              Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::VectorXd& sv = svd.singularValues();
  out.condition_number = sv[sv.size() - 1] > 0 ? sv[0] / sv[sv.size() - 1]
                                               : std::numeric_limits<double>::infinity();
  out.shape = phi * svd.solve(measured);
  return out;
}

// How many model modes the modal-coordinate fit uses (options.num_modes, or
// one per sensor), checked against the sensors and the model modes given.
int ModesToFit(const ExpansionOptions& options, int s, const Modes& model_modes, int n) {
  const int k = options.num_modes > 0 ? options.num_modes : s;
  if (k > s) {
    throw InputError("expansion.num_modes",
                     std::to_string(k) + " modes from " + std::to_string(s) +
                         " sensors: at most as many modes as sensors");
  }
  if (k > model_modes.size() || model_modes.shapes.rows() != n) {
    throw InputError(
        "expansion.model_modes",
        "needs " + std::to_string(k) + " modes on " + std::to_string(n) + " DOFs");
  }
  return k;
}

}  // namespace

ExpandedShape ExpandShape(const SparseMatrix& stiffness, const SparseMatrix& mass,
                          const Modes& model_modes, const std::vector<int>& sensors,
                          const Eigen::VectorXd& measured, double eigenvalue,
                          const ExpansionOptions& options) {
  ThrowIfInvalid(options.Validate(), "expansion");
  const int n = static_cast<int>(stiffness.rows());
  const int s = static_cast<int>(sensors.size());
  if (measured.size() != s || s == 0) {
    std::ostringstream msg;
    msg << "has " << measured.size() << " entries for " << s << " sensors";
    throw InputError("expansion.measured", msg.str());
  }
  if (!measured.allFinite()) throw InputError("expansion.measured", "has a NaN entry");
  std::vector<char> is_sensor(n, 0);
  for (int d : sensors) {
    if (d < 0 || d >= n) {
      throw InputError(
          "expansion.sensors",
          "DOF " + std::to_string(d) + " is outside 0.." + std::to_string(n - 1));
    }
    if (is_sensor[d]) {
      throw InputError("expansion.sensors",
                       "DOF " + std::to_string(d) + " is listed twice");
    }
    is_sensor[d] = 1;
  }
  ExpandedShape out;
  if (options.method == "dynamic") {
    std::vector<int> others;
    for (int i = 0; i < n; ++i) {
      if (!is_sensor[i]) others.push_back(i);
    }
    const SparseMatrix d = stiffness - eigenvalue * mass;
    const Eigen::MatrixXd dense = Eigen::MatrixXd(d);  // small and medium models
    const Eigen::MatrixXd doo = dense(others, others), doa = dense(others, sensors);
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(doo);
    if (others.size() > 0 && !lu.isInvertible()) {
      throw InputError("expansion.dynamic",
                       "K_oo - lambda M_oo is singular at this eigenvalue (a model "
                       "eigenvalue of the unmeasured part): use serep or lsq");
    }
    out.shape = Eigen::VectorXd::Zero(n);
    out.shape(sensors) = measured;
    if (!others.empty()) out.shape(others) = -lu.solve(doa * measured);
    out.sensor_mac = 1.0;  // measured entries kept; nothing fitted at the sensors
    out.condition_number = 0;
    return out;
  }
  const int k = ModesToFit(options, s, model_modes, n);
  const Eigen::MatrixXd phi = model_modes.shapes.leftCols(k);
  const Eigen::MatrixXd phi_a = phi(sensors, Eigen::all);
  out = FitModalCoordinates(phi, phi_a, measured);
  out.sensor_mac = Mac(out.shape(sensors), measured);
  if (options.method == "lsq") out.shape(sensors) = measured;
  return out;
}

ExpandedShape ExpandShape(const SparseMatrix& stiffness, const SparseMatrix& mass,
                          const Modes& model_modes, const SparseMatrix& sensors,
                          const Eigen::VectorXd& measured, double /*eigenvalue*/,
                          const ExpansionOptions& options) {
  ThrowIfInvalid(options.Validate(), "expansion");
  const int n = static_cast<int>(stiffness.rows());
  const int s = static_cast<int>(sensors.rows());
  if (mass.rows() != n || sensors.cols() != n) {
    throw InputError("expansion.sensors",
                     "the sensors read " + std::to_string(sensors.cols()) +
                         " DOFs; the model has " + std::to_string(n));
  }
  if (measured.size() != s || s == 0) {
    std::ostringstream msg;
    msg << "has " << measured.size() << " entries for " << s << " sensors";
    throw InputError("expansion.measured", msg.str());
  }
  if (!measured.allFinite()) throw InputError("expansion.measured", "has a NaN entry");
  if (options.method == "dynamic") {
    throw InputError("expansion.method",
                     "dynamic expansion needs sensors on model DOFs; these read between "
                     "nodes: use serep or lsq");
  }
  const int k = ModesToFit(options, s, model_modes, n);
  const Eigen::MatrixXd phi = model_modes.shapes.leftCols(k);
  const Eigen::MatrixXd phi_a = sensors * phi;
  ExpandedShape out = FitModalCoordinates(phi, phi_a, measured);
  out.sensor_mac = Mac(Eigen::VectorXd(sensors * out.shape), measured);
  return out;
}

}  // namespace femup