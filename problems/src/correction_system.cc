#include "femup/problems/correction_system.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "femup/core/enum_names.h"
#include "femup/core/errors.h"

namespace femup {

constexpr EnumName<SystemForm> kSystemFormNames[] = {
    {SystemForm::kSummed, "summed"},
    {SystemForm::kStacked, "stacked"},
};

const char* ToString(SystemForm form) {
  return NameIn(kSystemFormNames, form, "stacked");
}

bool SystemFormFromString(const std::string& text, SystemForm* form) {
  return ValueIn(kSystemFormNames, text, form);
}

PreparedCorrectionSystem::PreparedCorrectionSystem(const ParametrisedModel& model,
                                                   const Modes& fem_modes,
                                                   const CorrectionSystemOptions& options)
    : model_(&model), options_(options) {
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
  nf_ = options.num_fem_modes < 0 ? fem_modes.size() : options.num_fem_modes;
  if (nf_ < 1 || nf_ > fem_modes.size()) {
    std::ostringstream msg;
    msg << "asks for " << options.num_fem_modes << " FEM modes; between 1 and "
        << fem_modes.size() << " are available";
    throw InputError("fem_modes", msg.str());
  }
  const auto phi = fem_modes.shapes.leftCols(nf_);
  // K and M are symmetric: Phi' K = (K Phi)'.
  phi_t_k_ = (model.stiffness() * phi).transpose();
  phi_t_m_ = (model.mass() * phi).transpose();
  projections_.reserve(static_cast<std::size_t>(model.num_parameters()));
  for (const Parameter& p : model.parameters()) {
    Projection q;
    q.kind = p.kind;
    // B is symmetric: Phi' B restricted to the basis's DOFs is (B Phi)' there.
    q.support = &p.basis.dofs();
    q.phi_t_b = p.basis.RestrictedProduct(phi).transpose();
    projections_.push_back(std::move(q));
  }
}

void PreparedCorrectionSystem::SummedStates(const std::vector<ModalData>& states,
                                            int* dry, int* wet) const {
  *dry = -1;
  *wet = -1;
  for (std::size_t s = 0; s < states.size(); ++s) {
    int& slot = states[s].immersion == Immersion::kWet ? *wet : *dry;
    if (slot >= 0) {
      throw InputError("form",
                       "the summed form pairs one dry state with one wet state; "
                       "there are several " +
                           std::string(ToString(states[s].immersion)) +
                           " states (use form: stacked)");
    }
    slot = static_cast<int>(s);
  }
  if (*dry < 0 || *wet < 0) {
    throw InputError("form",
                     "the summed form needs both a dry (air) and a wet (water) "
                     "state (use form: stacked)");
  }
}

void PreparedCorrectionSystem::Fill(const std::vector<ModalData>& states, Workspace* work,
                                    Eigen::MatrixXd* a, Eigen::VectorXd* b) const {
  const int n = model_->num_dofs();
  const int np = model_->num_parameters();
  if (states.empty()) throw InputError("measurements", "no measured state is given");
  int dry = -1, wet = -1;
  if (options_.form == SystemForm::kSummed) SummedStates(states, &dry, &wet);

  // Stacked blocks for every measured mode, per state:
  // Z_j column k = Phi' B_k phi_j (times -lambda_j for mass and added mass;
  // added mass only in wet states), F_j = -Phi' (K phi_j - lambda_j M phi_j).
  work->z.resize(states.size());
  work->f.resize(states.size());
  work->where.resize(states.size());
  for (std::size_t s = 0; s < states.size(); ++s) {
    const ModalData& st = states[s];
    // "measurements.<state>", rebuilt only when the state's name changes.
    static const std::string kPrefix = "measurements.";
    std::string& where = work->where[s];
    if (where.size() != kPrefix.size() + st.state.size() ||
        where.compare(kPrefix.size(), std::string::npos, st.state) != 0) {
      where = kPrefix + st.state;
    }
    st.Validate(n, where);
    const bool direct =
        st.sensor_dofs.empty() && !st.HasInterpolatedSensors() && st.shapes.rows() == n;
    if (!direct) work->shapes = st.FullShapes(n, where);
    const Eigen::MatrixXd& shapes = direct ? st.shapes : work->shapes;
    const int modes = st.num_modes();
    work->z[s].resize(static_cast<std::size_t>(modes));
    work->f[s].resize(static_cast<std::size_t>(modes));
    work->k_shapes.noalias() = phi_t_k_ * shapes;
    work->m_shapes.noalias() = phi_t_m_ * shapes;
    for (int j = 0; j < modes; ++j) {
      // lambda = (2 pi f)^2, as ModalData::Eigenvalues (without its vector).
      const double lambda = std::pow(2 * M_PI * st.frequencies_hz[j], 2);
      const auto phi = shapes.col(j);
      Eigen::MatrixXd& z = work->z[s][static_cast<std::size_t>(j)];
      z.setZero(nf_, np);
      for (int k = 0; k < np; ++k) {
        const Projection& q = projections_[static_cast<std::size_t>(k)];
        if (q.kind == ParameterKind::kAddedMass && st.immersion != Immersion::kWet)
          continue;
        // Plain loops: the supports are a few DOFs, the columns a few FEM
        // modes, too small for Eigen's product kernels to pay off.
        double* column = z.col(k).data();
        const double* p = q.phi_t_b.data();
        const double sign = q.kind == ParameterKind::kStiffness ? 1.0 : -lambda;
        const std::vector<int>& support = *q.support;
        for (std::size_t i = 0; i < support.size(); ++i, p += nf_) {
          const double w = sign * phi[support[i]];
          for (int r = 0; r < nf_; ++r) column[r] += p[r] * w;
        }
      }
      work->f[s][static_cast<std::size_t>(j)] =
          lambda * work->m_shapes.col(j) - work->k_shapes.col(j);
    }
  }

  if (options_.form == SystemForm::kStacked) {
    int rows = 0;
    for (const auto& z : work->z) rows += static_cast<int>(z.size()) * nf_;
    if (a->rows() != rows || a->cols() != np) a->resize(rows, np);
    if (b->size() != rows) b->resize(rows);
    int r = 0;
    for (std::size_t s = 0; s < states.size(); ++s) {
      for (std::size_t j = 0; j < work->z[s].size(); ++j) {
        a->middleRows(r, nf_) = work->z[s][j];
        b->segment(r, nf_) = work->f[s][j];
        r += nf_;
      }
    }
    return;
  }

  // Summed form: one row per (FEM mode i, air mode j, water mode p).
  const auto& zd = work->z[static_cast<std::size_t>(dry)];
  const auto& zw = work->z[static_cast<std::size_t>(wet)];
  const auto& fd = work->f[static_cast<std::size_t>(dry)];
  const auto& fw = work->f[static_cast<std::size_t>(wet)];
  const int rows = nf_ * static_cast<int>(zd.size() * zw.size());
  if (a->rows() != rows || a->cols() != np) a->resize(rows, np);
  if (b->size() != rows) b->resize(rows);
  // Column by column (the storage order of a); the blocks are column-major
  // nf x p, so entry (i, k) of every block is at k * nf + i.
  auto sum_rows = [&](auto dry_entry, auto wet_entry, double* out) {
    for (int i = 0; i < nf_; ++i) {
      for (std::size_t j = 0; j < zd.size(); ++j) {
        const double dry_part = dry_entry(j, i);
        for (std::size_t p = 0; p < zw.size(); ++p) *out++ = dry_part + wet_entry(p, i);
      }
    }
  };
  for (int k = 0; k < np; ++k) {
    const Eigen::Index offset = static_cast<Eigen::Index>(k) * nf_;
    sum_rows([&](std::size_t j, int i) { return zd[j].data()[offset + i]; },
             [&](std::size_t p, int i) { return zw[p].data()[offset + i]; },
             a->col(k).data());
  }
  sum_rows([&](std::size_t j, int i) { return fd[j][i]; },
           [&](std::size_t p, int i) { return fw[p][i]; }, b->data());
}

LinearProblem PreparedCorrectionSystem::Build(
    const std::vector<ModalData>& states) const {
  LinearProblem problem;
  Workspace work;
  Fill(states, &work, &problem.A, &problem.b);
  problem.names = model_->ParameterNames();
  for (const auto& p : model_->parameters()) problem.groups.push_back(ToString(p.kind));
  if (!options_.row_labels) return problem;
  std::vector<std::vector<std::string>> labels(states.size());
  for (std::size_t s = 0; s < states.size(); ++s) {
    for (int j = 0; j < states[s].num_modes(); ++j)
      labels[s].push_back(states[s].state + " mode " + std::to_string(j + 1));
  }
  if (options_.form == SystemForm::kStacked) {
    for (std::size_t s = 0; s < states.size(); ++s) {
      for (const std::string& mode : labels[s]) {
        for (int i = 0; i < nf_; ++i)
          problem.row_labels.push_back(mode + " / FEM mode " + std::to_string(i + 1));
      }
    }
    return problem;
  }
  int dry = -1, wet = -1;
  SummedStates(states, &dry, &wet);
  for (int i = 0; i < nf_; ++i) {
    for (const std::string& air : labels[static_cast<std::size_t>(dry)]) {
      for (const std::string& water : labels[static_cast<std::size_t>(wet)]) {
        problem.row_labels.push_back("FEM mode " + std::to_string(i + 1) + " / " + air +
                                     " + " + water);
      }
    }
  }
  return problem;
}

LinearProblem BuildCorrectionSystem(const ParametrisedModel& model,
                                    const Modes& fem_modes,
                                    const std::vector<ModalData>& states,
                                    const CorrectionSystemOptions& options) {
  return PreparedCorrectionSystem(model, fem_modes, options).Build(states);
}

}  // namespace femup
