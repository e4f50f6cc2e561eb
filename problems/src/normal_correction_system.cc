#include "femup/problems/normal_correction_system.h"

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

#include "femup/errors.h"

namespace femup {
namespace {

double Since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Right-hand-side columns solved together (memory: DOFs x kBlock doubles).
constexpr int kBlock = 128;

}  // namespace

LinearProblem BuildNormalCorrectionSystem(const ParametrisedModel& model,
                                          const std::vector<ModalData>& states,
                                          NormalCorrectionStats* stats) {
  const auto t0 = std::chrono::steady_clock::now();
  const int dofs = model.num_dofs();
  const int p = model.num_parameters();
  if (p == 0)
    throw InputError("parameters", "the model has no correction factor to identify");
  if (states.empty()) throw InputError("measurements", "no measured state is given");

  Eigen::SimplicialLLT<SparseMatrix, Eigen::Lower, Eigen::AMDOrdering<int>> chol(
      model.mass());
  if (chol.info() != Eigen::Success) {
    throw InputError("model.mass", "is not positive definite (no Cholesky factor)");
  }

  Eigen::MatrixXd g = Eigen::MatrixXd::Zero(p, p);
  Eigen::VectorXd h = Eigen::VectorXd::Zero(p);
  double f2 = 0;
  int modes = 0;
  for (const ModalData& st : states) {
    const std::string where = "measurements." + st.state;
    st.Validate(dofs, where);
    const Eigen::MatrixXd shapes = st.FullShapes(dofs, where);
    const Eigen::VectorXd lambdas = st.Eigenvalues();
    const bool wet = st.immersion == Immersion::kWet;
    for (int j = 0; j < st.num_modes(); ++j) {
      ++modes;
      const Eigen::VectorXd phi = shapes.col(j);
      const double lambda = lambdas[j];
      // Z_j column by column (sparse: each basis acts on its own DOFs).
      std::vector<Eigen::Triplet<double>> t;
      for (int k = 0; k < p; ++k) {
        const Parameter& q = model.parameter(k);
        double factor = 0;
        switch (q.kind) {
          case ParameterKind::kStiffness:
            factor = 1.0;
            break;
          case ParameterKind::kMass:
            factor = -lambda;
            break;
          case ParameterKind::kAddedMass:
            factor = wet ? -lambda : 0.0;
            break;
        }
        if (factor == 0.0) continue;
        const Eigen::VectorXd col = q.basis * phi;
        for (Eigen::Index i = 0; i < col.size(); ++i) {
          if (col[i] != 0.0) t.emplace_back(static_cast<int>(i), k, factor * col[i]);
        }
      }
      SparseMatrix z(dofs, p);
      z.setFromTriplets(t.begin(), t.end());
      const Eigen::VectorXd f =
          -(model.stiffness() * phi - lambda * (model.mass() * phi));
      const Eigen::VectorXd minv_f = chol.solve(f);
      f2 += f.dot(minv_f);
      h += z.transpose() * minv_f;
      for (int c0 = 0; c0 < p; c0 += kBlock) {
        const int nc = std::min(kBlock, p - c0);
        const Eigen::MatrixXd x = chol.solve(Eigen::MatrixXd(z.middleCols(c0, nc)));
        g.middleCols(c0, nc) += z.transpose() * x;
      }
    }
  }
  g = 0.5 * (g + g.transpose()).eval();
  const double assembly = Since(t0);

  // Column-scaled eigen-decomposition: D G D = V S V', A = S^1/2 V' D^-1.
  const auto t1 = std::chrono::steady_clock::now();
  Eigen::VectorXd d(p);
  for (int k = 0; k < p; ++k) d[k] = g(k, k) > 0 ? 1.0 / std::sqrt(g(k, k)) : 1.0;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(d.asDiagonal() * g *
                                                           d.asDiagonal());
  const Eigen::VectorXd& s = eig.eigenvalues();  // ascending
  const double smax = s.size() > 0 ? std::max(s[s.size() - 1], 0.0) : 0.0;
  const double threshold = p * std::numeric_limits<double>::epsilon() * smax;
  LinearProblem problem;
  problem.A = Eigen::MatrixXd::Zero(p, p);
  problem.b = Eigen::VectorXd::Zero(p);
  const Eigen::VectorXd hs = eig.eigenvectors().transpose() * (d.asDiagonal() * h);
  int dropped = 0;
  for (int i = 0; i < p; ++i) {
    const int row = p - 1 - i;  // largest first
    if (!(s[i] > threshold)) {
      ++dropped;
      continue;
    }
    const double root = std::sqrt(s[i]);
    problem.A.row(row) =
        root * eig.eigenvectors().col(i).transpose() * d.cwiseInverse().asDiagonal();
    problem.b[row] = hs[i] / root;
  }
  problem.source_rows = dofs * modes;
  problem.residual_offset = std::max(0.0, f2 - problem.b.squaredNorm());
  problem.names = model.ParameterNames();
  for (const Parameter& q : model.parameters())
    problem.groups.push_back(ToString(q.kind));
  if (stats != nullptr) {
    stats->dropped = dropped;
    stats->seconds_assembly = assembly;
    stats->seconds_compress = Since(t1);
  }
  return problem;
}

}  // namespace femup
