#include "femup/studies/modes_study.h"

#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>

#include "femup/core/linalg/node_ordering.h"

namespace femup {

ModesResult RunModes(const Study& study, int num_modes) {
  ModesResult r;
  r.study_name = study.name;
  r.model_description = study.structure.description;
  r.dof_labels = study.model.dof_labels();
  r.dof_positions = study.structure.dof_positions;
  EigenOptions options;
  const int n = study.model.num_dofs();
  options.num_modes = num_modes > 0 ? std::min(num_modes, n) : (n <= 1500 ? -1 : 10);
  r.nominal = SolveModes(study.model.stiffness(), study.model.mass(),
                         WithNodeOrdering(options, study.model.dof_labels()));
  const SparseMatrix& k = study.model.stiffness();
  const SparseMatrix& m = study.model.mass();
  for (int j = 0; j < r.nominal.size(); ++j) {
    const Eigen::VectorXd phi = r.nominal.shapes.col(j);
    const Eigen::VectorXd kphi = k * phi;
    const double res = (kphi - r.nominal.eigenvalues[j] * (m * phi)).norm() /
                       std::max(kphi.norm(), 1e-300);
    r.max_residual = std::max(r.max_residual, res);
  }
  const Eigen::MatrixXd orth =
      r.nominal.shapes.transpose() * (m * r.nominal.shapes) -
      Eigen::MatrixXd::Identity(r.nominal.size(), r.nominal.size());
  r.max_orthogonality_error = orth.cwiseAbs().maxCoeff();
  return r;
}

}  // namespace femup
