#include "femup/problems/correction_system.h"

#include <sstream>

#include "femup/errors.h"

namespace femup {

const char* ToString(SystemForm form) {
  return form == SystemForm::kSummed ? "summed" : "stacked";
}

bool SystemFormFromString(const std::string& text, SystemForm* form) {
  if (text == "summed") {
    *form = SystemForm::kSummed;
  } else if (text == "stacked") {
    *form = SystemForm::kStacked;
  } else {
    return false;
  }
  return true;
}

namespace {

// The stacked rows of one measured mode: Nf x (num_parameters) block and its F.
struct ModeBlock {
  Eigen::MatrixXd z;
  Eigen::VectorXd f;
};

// `bphi` is scratch space (num_dofs), reused across calls.
ModeBlock BlockFor(const ParametrisedModel& model, const Eigen::MatrixXd& phi_fem,
                   double lambda, const Eigen::VectorXd& phi, Immersion immersion,
                   Eigen::VectorXd* bphi) {
  const int nf = static_cast<int>(phi_fem.cols());
  ModeBlock block{Eigen::MatrixXd::Zero(nf, model.num_parameters()), Eigen::VectorXd()};
  for (int k = 0; k < model.num_parameters(); ++k) {
    const Parameter& p = model.parameter(k);
    if (p.kind == ParameterKind::kAddedMass && immersion != Immersion::kWet) continue;
    bphi->noalias() = p.basis * phi;
    auto column = block.z.col(k);
    column.noalias() = phi_fem.transpose() * *bphi;
    if (p.kind != ParameterKind::kStiffness) column *= -lambda;
  }
  const Eigen::VectorXd r = model.stiffness() * phi - lambda * (model.mass() * phi);
  block.f = -(phi_fem.transpose() * r);
  return block;
}

}  // namespace

LinearProblem BuildCorrectionSystem(const ParametrisedModel& model,
                                    const Modes& fem_modes,
                                    const std::vector<ModalData>& states,
                                    const CorrectionSystemOptions& options) {
  const int n = model.num_dofs();
  if (fem_modes.shapes.rows() != n) {
    std::ostringstream msg;
    msg << "FEM mode shapes have " << fem_modes.shapes.rows() << " rows, the model has "
        << n << " DOFs";
    throw InputError("correction system", msg.str());
  }
  if (model.num_parameters() == 0) {
    throw InputError("parameters", "the model has no correction factor to identify");
  }
  int nf = options.num_fem_modes < 0 ? fem_modes.size() : options.num_fem_modes;
  if (nf < 1 || nf > fem_modes.size()) {
    std::ostringstream msg;
    msg << "asks for " << options.num_fem_modes << " FEM modes; between 1 and "
        << fem_modes.size() << " are available";
    throw InputError("fem_modes", msg.str());
  }
  if (states.empty()) throw InputError("measurements", "no measured state is given");
  const Eigen::MatrixXd phi_fem = fem_modes.shapes.leftCols(nf);

  // Stacked blocks for every measured mode, per state.
  std::vector<std::vector<ModeBlock>> blocks(states.size());
  std::vector<std::vector<std::string>> labels(states.size());
  Eigen::VectorXd bphi(n);
  for (std::size_t s = 0; s < states.size(); ++s) {
    const ModalData& st = states[s];
    const std::string where = "measurements." + st.state;
    st.Validate(n, where);
    const Eigen::MatrixXd shapes = st.FullShapes(n, where);
    const Eigen::VectorXd lambdas = st.Eigenvalues();
    for (int j = 0; j < st.num_modes(); ++j) {
      blocks[s].push_back(
          BlockFor(model, phi_fem, lambdas[j], shapes.col(j), st.immersion, &bphi));
      if (options.row_labels)
        labels[s].push_back(st.state + " mode " + std::to_string(j + 1));
    }
  }

  LinearProblem problem;
  problem.names = model.ParameterNames();
  for (const auto& p : model.parameters()) problem.groups.push_back(ToString(p.kind));

  if (options.form == SystemForm::kStacked) {
    int rows = 0;
    for (const auto& b : blocks) rows += static_cast<int>(b.size()) * nf;
    problem.A.resize(rows, model.num_parameters());
    problem.b.resize(rows);
    int r = 0;
    for (std::size_t s = 0; s < blocks.size(); ++s) {
      for (std::size_t j = 0; j < blocks[s].size(); ++j) {
        problem.A.middleRows(r, nf) = blocks[s][j].z;
        problem.b.segment(r, nf) = blocks[s][j].f;
        for (int i = 0; options.row_labels && i < nf; ++i) {
          problem.row_labels.push_back(labels[s][j] + " / FEM mode " +
                                       std::to_string(i + 1));
        }
        r += nf;
      }
    }
    return problem;
  }

  // Summed form: exactly one dry and one wet state.
  int dry = -1, wet = -1;
  for (std::size_t s = 0; s < states.size(); ++s) {
    int& slot = states[s].immersion == Immersion::kWet ? wet : dry;
    if (slot >= 0) {
      throw InputError("form",
                       "the summed form pairs one dry state with one wet state; "
                       "there are several " +
                           std::string(ToString(states[s].immersion)) +
                           " states (use form: stacked)");
    }
    slot = static_cast<int>(s);
  }
  if (dry < 0 || wet < 0) {
    throw InputError("form",
                     "the summed form needs both a dry (air) and a wet (water) "
                     "state (use form: stacked)");
  }
  const int na = static_cast<int>(blocks[dry].size());
  const int nw = static_cast<int>(blocks[wet].size());
  const int rows = nf * na * nw;
  problem.A.resize(rows, model.num_parameters());
  problem.b.resize(rows);
  int r = 0;
  for (int i = 0; i < nf; ++i) {
    for (int j = 0; j < na; ++j) {
      for (int p = 0; p < nw; ++p) {
        problem.A.row(r) = blocks[dry][j].z.row(i) + blocks[wet][p].z.row(i);
        problem.b[r] = blocks[dry][j].f[i] + blocks[wet][p].f[i];
        if (options.row_labels) {
          problem.row_labels.push_back("FEM mode " + std::to_string(i + 1) + " / " +
                                       labels[dry][j] + " + " + labels[wet][p]);
        }
        ++r;
      }
    }
  }
  return problem;
}

}  // namespace femup
