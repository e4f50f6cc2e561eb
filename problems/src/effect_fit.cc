#include "femup/problems/effect_fit.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "femup/core/errors.h"
#include "femup/core/linalg/modal.h"

namespace femup {

namespace {

const double kTwoPi = 2 * std::acos(-1.0);

bool IsAxial(const std::string& label) {
  return label.size() > 3 && label.compare(label.size() - 3, 3, ":uy") == 0;
}

// Offsets of each effect's parameters in the concatenated vector.
std::vector<int> Offsets(const EffectFitData& data,
                         const std::vector<const Effect*>& effects) {
  std::vector<int> offsets{0};
  for (const Effect* e : effects) {
    offsets.push_back(offsets.back() +
                      static_cast<int>(e->Parameters(data.nominal).size()));
  }
  return offsets;
}

struct BendingModes {
  Eigen::VectorXd frequencies_hz;  // ascending
  Eigen::MatrixXd shapes;          // bending DOFs x modes (mass-normalised)
  std::map<std::string, int> row;  // label -> bending row
  // Kept for the Jacobian (SolveBending with `keep`): the bending matrices,
  // the eigenvalues and the bending DOFs' labels in row order.
  Eigen::MatrixXd kb, mb;
  Eigen::VectorXd eigenvalues;
  std::vector<std::string> labels;
};

// The bending modes of `spec`; their shapes only when `shapes` (frequency-only
// data need none, and accumulating the eigenvectors is a large part of the
// eigen-solution's cost). With `keep`, also the matrices, eigenvalues and labels
// (and the shapes, whatever `shapes` says).
bool SolveBending(const CantileverSpec& spec, bool shapes, bool keep, BendingModes* out,
                  std::string* why) {
  Eigen::MatrixXd kb, mb;
  std::vector<std::string> labels;
  if (!AssembleBendingMatrices(spec, &kb, &mb, &labels, why)) return false;
  shapes = shapes || keep;
  const int nb = static_cast<int>(labels.size());
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(
      kb, mb,
      shapes ? Eigen::ComputeEigenvectors | Eigen::Ax_lBx : Eigen::EigenvaluesOnly);
  if (eig.info() != Eigen::Success) {
    if (why) *why = "the mass matrix is not positive definite";
    return false;
  }
  const Eigen::VectorXd lambda = eig.eigenvalues();
  out->frequencies_hz.resize(nb);
  for (int i = 0; i < nb; ++i) {
    out->frequencies_hz[i] = std::sqrt(std::max(lambda[i], 0.0)) / kTwoPi;
  }
  if (!out->frequencies_hz.allFinite()) {
    if (why) *why = "the eigen-solution is not finite";
    return false;
  }
  if (shapes) out->shapes = eig.eigenvectors();
  out->row.clear();
  for (int i = 0; i < nb; ++i) out->row[labels[i]] = i;
  if (keep) {
    out->kb = std::move(kb);
    out->mb = std::move(mb);
    out->eigenvalues = lambda;
    out->labels = std::move(labels);
  }
  return true;
}

bool StateUsesShapes(const EffectFitData& data, const ObservedState& st) {
  if (!data.use_shapes || st.sensors.empty()) return false;
  for (const ObservedMode& m : st.modes) {
    if (m.shape.size() == 0) return false;
  }
  return !st.modes.empty();
}

Eigen::VectorXd UnitPeak(const Eigen::VectorXd& v) {
  const double peak = v.cwiseAbs().maxCoeff();
  return peak > 0 ? Eigen::VectorXd(v / peak) : v;
}

}  // namespace

bool AssembleBendingMatrices(const CantileverSpec& spec, Eigen::MatrixXd* kb,
                             Eigen::MatrixXd* mb, std::vector<std::string>* labels,
                             std::string* why) {
  Structure s;
  try {
    CantileverSpec global_only = spec;
    global_only.element_matrices = false;
    s = BuildCantilever(global_only);
  } catch (const InputError& e) {
    if (why) *why = e.what();
    return false;
  }
  // Bending rows (ux, rz) in order; axial DOFs map to -1.
  const int n = static_cast<int>(s.dof_labels.size());
  std::vector<int> index(n, -1);
  labels->clear();
  for (int i = 0; i < n; ++i) {
    if (!IsAxial(s.dof_labels[i])) {
      index[i] = static_cast<int>(labels->size());
      labels->push_back(s.dof_labels[i]);
    }
  }
  const int nb = static_cast<int>(labels->size());
  kb->setZero(nb, nb);
  mb->setZero(nb, nb);
  bool coupled = false;
  for (auto [matrix, dense] : {std::pair{&s.stiffness, kb}, std::pair{&s.mass, mb}}) {
    double largest = 0, coupling = 0;
    for (int col = 0; col < matrix->outerSize(); ++col) {
      for (SparseMatrix::InnerIterator it(*matrix, col); it; ++it) {
        const int i = index[it.row()], j = index[it.col()];
        largest = std::max(largest, std::abs(it.value()));
        if (i >= 0 && j >= 0) {
          (*dense)(i, j) += it.value();
        } else if (i >= 0 || j >= 0) {
          coupling = std::max(coupling, std::abs(it.value()));
        }
      }
    }
    coupled = coupled || coupling > 1e-10 * largest;
  }
  if (coupled) {
    if (why)
      *why =
          "bending and axial DOFs are coupled; the effect fit needs a "
          "straight cantilever";
    return false;
  }
  return true;
}

Invalid EffectFitData::Validate() const {
  if (states.empty()) return {"states", "no measured state"};
  if (!(shape_sigma > 0) || !std::isfinite(shape_sigma))
    return {"shape_sigma", "must be positive and finite"};
  if (extra_modes < 0) return {"extra_modes", "must be >= 0"};
  for (std::size_t s = 0; s < states.size(); ++s) {
    const ObservedState& st = states[s];
    const std::string where = "states[" + std::to_string(s + 1) + "] (" + st.state + ")";
    if (st.modes.empty()) return {where, "no modes"};
    for (const std::string& label : st.sensors) {
      if (st.sensor_terms.empty() && IsAxial(label))
        return {where, "sensor " + label + " is axial; use ux sensors"};
    }
    if (!st.sensor_terms.empty() && st.sensor_terms.size() != st.sensors.size())
      return {where, "sensor_terms must have one entry per sensor"};
    for (std::size_t i = 0; i < st.sensor_terms.size(); ++i) {
      for (const auto& [label, w] : st.sensor_terms[i])
        if (IsAxial(label) || !std::isfinite(w))
          return {where,
                  "sensor " + st.sensors[i] + " reads " + label + "; use ux sensors"};
    }
    for (std::size_t j = 0; j < st.modes.size(); ++j) {
      const ObservedMode& m = st.modes[j];
      const std::string mw = where + ".modes[" + std::to_string(j + 1) + "]";
      if (m.number < 1) return {mw, "mode numbers start at 1"};
      if (!(m.frequency_hz > 0) || !std::isfinite(m.frequency_hz))
        return {mw, "frequency must be positive and finite"};
      if (!(m.frequency_sigma > 0) || !std::isfinite(m.frequency_sigma))
        return {mw, "frequency sigma must be positive and finite"};
      if (m.shape.size() > 0) {
        if (m.shape.size() != static_cast<Eigen::Index>(st.sensors.size()))
          return {mw, "shape has " + std::to_string(m.shape.size()) + " entries for " +
                          std::to_string(st.sensors.size()) + " sensors"};
        if (!m.shape.allFinite() || m.shape.cwiseAbs().maxCoeff() == 0)
          return {mw, "shape must be finite and not all zero"};
      }
      if (m.shape_sigma.size() > 0) {
        if (m.shape_sigma.size() != m.shape.size())
          return {mw, "shape sigma has " + std::to_string(m.shape_sigma.size()) +
                          " entries for a shape of " + std::to_string(m.shape.size())};
        if (!m.shape_sigma.allFinite() || !(m.shape_sigma.minCoeff() > 0))
          return {mw, "shape sigma must be positive and finite"};
      }
    }
    for (std::size_t j = 0; j < st.companions.size(); ++j) {
      const ObservedMode& m = st.companions[j];
      const std::string mw = where + ".companions[" + std::to_string(j + 1) + "]";
      if (m.number < 1) return {mw, "mode numbers start at 1"};
      if (!(m.frequency_hz >= 0) || !std::isfinite(m.frequency_hz))
        return {mw, "frequency must be finite and not negative"};
      if (m.shape.size() > 0 &&
          m.shape.size() != static_cast<Eigen::Index>(st.sensors.size()))
        return {mw, "shape has " + std::to_string(m.shape.size()) + " entries for " +
                        std::to_string(st.sensors.size()) + " sensors"};
      if (m.shape.size() > 0 && !m.shape.allFinite()) return {mw, "shape must be finite"};
    }
  }
  return {};
}

namespace {

// What the Jacobian needs of a prediction besides the predicted modes: per
// state, the model mode paired with each observed one (0-based) and the
// bending rows of the sensors.
struct PredictionDetail {
  std::vector<int> pair;
  Eigen::MatrixXd reader;  // sensors x bending rows: the sensors' readings
};

// The nominal model changed by the effects with parameters theta, for a state
// of the given immersion.
CantileverSpec SpecFor(const EffectFitData& data,
                       const std::vector<const Effect*>& effects,
                       const std::vector<int>& offsets, const Eigen::VectorXd& theta,
                       Immersion immersion) {
  CantileverSpec spec = data.nominal;
  for (std::size_t e = 0; e < effects.size(); ++e) {
    effects[e]->Apply(theta.segment(offsets[e], offsets[e + 1] - offsets[e]), immersion,
                      data.wet_only_added_mass, data.nominal, &spec);
  }
  return spec;
}

// PredictEffectModes, keeping (with `keep`) each immersion's matrices and
// eigen-solution in *models and each state's pairing in *details.
bool Predict(const EffectFitData& data, const std::vector<const Effect*>& effects,
             const Eigen::VectorXd& theta, bool keep,
             std::map<Immersion, BendingModes>* models_out,
             std::vector<PredictionDetail>* details, std::vector<PredictedState>* out,
             std::string* why) {
  const std::vector<int> offsets = Offsets(data, effects);
  if (theta.size() != offsets.back() || !theta.allFinite()) {
    if (why) *why = "parameters of the wrong size or not finite";
    return false;
  }
  // One model per immersion.
  std::map<Immersion, BendingModes>& models = *models_out;
  models.clear();
  details->assign(data.states.size(), PredictionDetail());
  out->assign(data.states.size(), PredictedState());
  for (std::size_t s = 0; s < data.states.size(); ++s) {
    const ObservedState& st = data.states[s];
    auto it = models.find(st.immersion);
    if (it == models.end()) {
      const CantileverSpec spec = SpecFor(data, effects, offsets, theta, st.immersion);
      BendingModes bm;
      // Shapes are needed where a state of this immersion has sensors.
      bool shapes = false;
      for (const ObservedState& other : data.states)
        shapes = shapes || (other.immersion == st.immersion && !other.sensors.empty());
      if (!SolveBending(spec, shapes, keep, &bm, why)) return false;
      it = models.emplace(st.immersion, std::move(bm)).first;
    }
    const BendingModes& bm = it->second;
    int highest = 0;
    for (const ObservedMode& m : st.modes) highest = std::max(highest, m.number);
    const bool by_mac = StateUsesShapes(data, st);
    // With shapes: the state's measured modes, own first, then its companions
    // that have a shape.
    std::vector<const ObservedMode*> all;
    if (by_mac) {
      for (const ObservedMode& m : st.modes) all.push_back(&m);
      for (const ObservedMode& m : st.companions) {
        if (m.shape.size() == 0) continue;
        all.push_back(&m);
        highest = std::max(highest, m.number);
      }
    }
    const int available = static_cast<int>(bm.frequencies_hz.size());
    if (highest > available) {
      if (why)
        *why = "mode " + std::to_string(highest) + " asked of a model with " +
               std::to_string(available) + " bending modes";
      return false;
    }
    const int candidates = std::min(available, highest + data.extra_modes);
    Eigen::MatrixXd reader =
        Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(st.sensors.size()),
                              static_cast<Eigen::Index>(bm.row.size()));
    for (std::size_t i = 0; i < st.sensors.size(); ++i) {
      const auto terms =
          st.sensor_terms.empty()
              ? std::vector<std::pair<std::string, double>>{{st.sensors[i], 1}}
              : st.sensor_terms[i];
      for (const auto& [label, w] : terms) {
        const auto r = bm.row.find(label);
        if (r == bm.row.end()) {
          if (why) *why = "the model has no DOF '" + label + "'";
          return false;
        }
        reader(static_cast<Eigen::Index>(i), r->second) += w;
      }
    }
    const Eigen::MatrixXd at_sensors =
        st.sensors.empty() ? Eigen::MatrixXd(0, candidates)
                           : Eigen::MatrixXd(reader * bm.shapes.leftCols(candidates));
    std::vector<int> pair(st.modes.size());
    if (by_mac) {
      // A cantilever's bending modes keep their order whatever the effects
      // (mode k has k - 1 nodes), so the measured modes, own and companions in
      // ascending frequency (then number), pair with model modes in ascending
      // order.
      std::vector<std::size_t> order(all.size());
      for (std::size_t j = 0; j < order.size(); ++j) order[j] = j;
      std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        if (all[a]->frequency_hz != all[b]->frequency_hz)
          return all[a]->frequency_hz < all[b]->frequency_hz;
        return all[a]->number < all[b]->number;
      });
      Eigen::MatrixXd measured(at_sensors.rows(), static_cast<Eigen::Index>(all.size()));
      for (std::size_t j = 0; j < order.size(); ++j)
        measured.col(static_cast<Eigen::Index>(j)) = all[order[j]]->shape;
      const std::vector<ModePair> pairs = PairModesInOrder(measured, at_sensors);
      for (std::size_t j = 0; j < order.size(); ++j) {
        if (order[j] < st.modes.size()) pair[order[j]] = pairs[j].candidate;
      }
    } else {
      for (std::size_t j = 0; j < st.modes.size(); ++j) pair[j] = st.modes[j].number - 1;
    }
    (*details)[s].pair = pair;
    (*details)[s].reader = reader;
    PredictedState& ps = (*out)[s];
    for (std::size_t j = 0; j < st.modes.size(); ++j) {
      PredictedMode pm;
      if (pair[j] < 0) {
        if (why) *why = "no model mode pairs with measured mode " + std::to_string(j + 1);
        return false;
      }
      pm.model_mode = pair[j] + 1;
      pm.frequency_hz = bm.frequencies_hz[pair[j]];
      const Eigen::VectorXd s_vec = at_sensors.col(pair[j]);
      const ObservedMode& om = st.modes[j];
      if (om.shape.size() > 0 && s_vec.size() > 0) {
        const Eigen::VectorXd t = UnitPeak(om.shape);
        const double ss = s_vec.squaredNorm();
        const double c = ss > 0 ? s_vec.dot(t) / ss : 0.0;
        pm.shape = c * s_vec;
        pm.mac = Mac(s_vec, t);
      } else if (s_vec.size() > 0) {
        pm.shape = UnitPeak(s_vec);
      }
      ps.modes.push_back(std::move(pm));
    }
  }
  return true;
}

// Column i of the Jacobian of EffectResiduals at x, from the eigen-solution
// kept at x (`models`, `details`): dK and dM by a forward (backward at the
// upper bound) difference of the assembled bending matrices over a step of
// 1e-6 of the parameter's range, then exact eigenpair derivatives for that
// dK and dM: d lambda = phi'(dK - lambda dM) phi, and d phi by the expansion on
// all the model's bending modes (a complete basis of the dense problem):
//   d phi_p = sum_{q != p} phi_q phi_q'(dK - lambda_p dM) phi_p / (lambda_p - lambda_q)
//             - 1/2 (phi_p' dM phi_p) phi_p.
// The pairing is held. Returns false (with *why unset) where that does not
// apply: the step changes the DOFs, a paired eigenvalue is not positive, or
// two eigenvalues are too close for the expansion; the caller then differences
// the residuals instead.
bool SemiAnalyticColumn(const EffectFitData& data,
                        const std::vector<const Effect*>& effects,
                        const std::vector<int>& offsets, const Eigen::VectorXd& x,
                        Eigen::Index i, double step,
                        const std::map<Immersion, BendingModes>& models,
                        const std::vector<PredictionDetail>& details,
                        Eigen::Ref<Eigen::VectorXd> column, bool* failed,
                        std::string* why) {
  *failed = false;
  Eigen::VectorXd xs = x;
  xs[i] += step;
  std::map<Immersion, std::pair<Eigen::MatrixXd, Eigen::MatrixXd>> derivative;
  for (const auto& [immersion, bm] : models) {
    Eigen::MatrixXd kb, mb;
    std::vector<std::string> labels;
    if (!AssembleBendingMatrices(SpecFor(data, effects, offsets, xs, immersion), &kb, &mb,
                                 &labels, why)) {
      *failed = true;
      return false;
    }
    if (labels != bm.labels) return false;
    derivative[immersion] = {(kb - bm.kb) / step, (mb - bm.mb) / step};
  }
  Eigen::Index k = 0;
  for (std::size_t s = 0; s < data.states.size(); ++s) {
    const ObservedState& st = data.states[s];
    const bool shapes = StateUsesShapes(data, st);
    const BendingModes& bm = models.at(st.immersion);
    const auto& [dk, dm] = derivative.at(st.immersion);
    const PredictionDetail& detail = details[s];
    for (std::size_t j = 0; j < st.modes.size(); ++j) {
      const ObservedMode& om = st.modes[j];
      const int p = detail.pair[j];
      const double lambda = bm.eigenvalues[p];
      if (!(lambda > 0)) return false;
      const auto phi = bm.shapes.col(p);
      const Eigen::VectorXd dm_phi = dm * phi;
      const Eigen::VectorXd g = dk * phi - lambda * dm_phi;
      const double dlambda = phi.dot(g);
      // f = sqrt(lambda) / 2 pi, so df = f dlambda / (2 lambda).
      column[k++] = bm.frequencies_hz[p] * dlambda / (2 * lambda) / om.frequency_hz /
                    om.frequency_sigma;
      if (!shapes) continue;
      Eigen::VectorXd coefficient = bm.shapes.transpose() * g;
      for (Eigen::Index q = 0; q < coefficient.size(); ++q) {
        if (q == p) continue;
        const double gap = lambda - bm.eigenvalues[q];
        if (!(std::abs(gap) > 1e-9 * std::abs(lambda))) return false;
        coefficient[q] /= gap;
      }
      coefficient[p] = -0.5 * phi.dot(dm_phi);
      const Eigen::VectorXd dphi = bm.shapes * coefficient;
      const Eigen::Index m = detail.reader.rows();
      const Eigen::VectorXd sv = detail.reader * phi, ds = detail.reader * dphi;
      // The predicted shape is c s with c = s't / s's (PredictEffectModes).
      const Eigen::VectorXd t = UnitPeak(om.shape);
      const double ss = sv.squaredNorm();
      if (!(ss > 0)) return false;
      const double c = sv.dot(t) / ss;
      const double dc = ds.dot(t) / ss - 2 * sv.dot(t) * sv.dot(ds) / (ss * ss);
      const Eigen::VectorXd dshape = dc * sv + c * ds;
      const bool own = om.shape_sigma.size() > 0;
      for (Eigen::Index r = 0; r < m; ++r)
        column[k++] = dshape[r] / (own ? om.shape_sigma[r] : data.shape_sigma);
    }
  }
  return true;
}

}  // namespace

bool PredictEffectModes(const EffectFitData& data,
                        const std::vector<const Effect*>& effects,
                        const Eigen::VectorXd& theta, std::vector<PredictedState>* out,
                        std::string* why) {
  std::map<Immersion, BendingModes> models;
  std::vector<PredictionDetail> details;
  return Predict(data, effects, theta, false, &models, &details, out, why);
}

bool BendingModesAtSensors(
    const CantileverSpec& spec, const std::vector<std::string>& sensors, int count,
    Eigen::VectorXd* frequencies_hz, Eigen::MatrixXd* shapes, std::string* why,
    const std::vector<std::vector<std::pair<std::string, double>>>& terms) {
  // Frequency-only observations numbered 1..count pair mode k with the k-th
  // bending mode; their values do not enter the prediction.
  EffectFitData d;
  d.nominal = spec;
  ObservedState st;
  st.state = "modes";
  st.sensors = sensors;
  st.sensor_terms = terms;
  for (int k = 1; k <= count; ++k) {
    ObservedMode m;
    m.number = k;
    m.frequency_hz = 1;
    m.frequency_sigma = 1;
    st.modes.push_back(m);
  }
  d.states.push_back(st);
  std::vector<PredictedState> pred;
  if (!PredictEffectModes(d, {}, Eigen::VectorXd(), &pred, why)) return false;
  frequencies_hz->resize(count);
  shapes->resize(static_cast<Eigen::Index>(sensors.size()), count);
  for (int k = 0; k < count; ++k) {
    (*frequencies_hz)[k] = pred[0].modes[k].frequency_hz;
    if (!sensors.empty()) shapes->col(k) = pred[0].modes[k].shape;
  }
  return true;
}

int NumEffectResiduals(const EffectFitData& data) {
  int n = 0;
  for (const ObservedState& st : data.states) {
    const bool shapes = StateUsesShapes(data, st);
    for (std::size_t j = 0; j < st.modes.size(); ++j) {
      n += 1 + (shapes ? static_cast<int>(st.sensors.size()) : 0);
    }
  }
  return n;
}

int EffectDegreesOfFreedom(const EffectFitData& data) {
  int n = 0;
  for (const ObservedState& st : data.states) {
    const bool shapes = StateUsesShapes(data, st);
    for (std::size_t j = 0; j < st.modes.size(); ++j) {
      n += 1 + (shapes ? static_cast<int>(st.sensors.size()) - 1 : 0);
    }
  }
  return n;
}

Eigen::VectorXd EffectResiduals(const EffectFitData& data,
                                const std::vector<PredictedState>& predicted) {
  Eigen::VectorXd r(NumEffectResiduals(data));
  int k = 0;
  for (std::size_t s = 0; s < data.states.size(); ++s) {
    const ObservedState& st = data.states[s];
    const bool shapes = StateUsesShapes(data, st);
    for (std::size_t j = 0; j < st.modes.size(); ++j) {
      const ObservedMode& om = st.modes[j];
      const PredictedMode& pm = predicted[s].modes[j];
      r[k++] = (pm.frequency_hz / om.frequency_hz - 1) / om.frequency_sigma;
      if (shapes) {
        const Eigen::VectorXd t = UnitPeak(om.shape);
        const bool own = om.shape_sigma.size() > 0;
        for (Eigen::Index i = 0; i < t.size(); ++i) {
          r[k++] = (pm.shape[i] - t[i]) / (own ? om.shape_sigma[i] : data.shape_sigma);
        }
      }
    }
  }
  return r;
}

std::vector<EffectParameter> EffectSetParameters(
    const EffectFitData& data, const std::vector<const Effect*>& effects) {
  std::vector<EffectParameter> all;
  for (const Effect* e : effects) {
    for (EffectParameter p : e->Parameters(data.nominal)) {
      p.name = e->kind() + "." + p.name;
      all.push_back(p);
    }
  }
  return all;
}

NonlinearProblem BuildEffectFitProblem(const EffectFitData& data,
                                       const std::vector<const Effect*>& effects,
                                       const Eigen::VectorXd& start) {
  ThrowIfInvalid(data.Validate(), "diagnosis");
  const std::vector<EffectParameter> params = EffectSetParameters(data, effects);
  const int n = static_cast<int>(params.size());
  if (start.size() != n) {
    throw InputError("start", "has " + std::to_string(start.size()) + " values for " +
                                  std::to_string(n) + " effect parameters");
  }
  NonlinearProblem p;
  p.num_residuals = NumEffectResiduals(data);
  p.initial = start;
  p.lower.resize(n);
  p.upper.resize(n);
  for (int i = 0; i < n; ++i) {
    p.names.push_back(params[i].name);
    p.groups.push_back(params[i].name.substr(0, params[i].name.find('.')));
    p.lower[i] = params[i].lower;
    p.upper[i] = params[i].upper;
    if (!(start[i] >= p.lower[i] && start[i] <= p.upper[i])) {
      std::ostringstream msg;
      msg << params[i].name << " = " << start[i] << " is outside its range ["
          << p.lower[i] << ", " << p.upper[i] << "]";
      throw InputError("start", msg.str());
    }
  }
  p.residuals_whitened = true;
  const Eigen::VectorXd lower = p.lower, upper = p.upper;
  p.evaluate = [data, effects, lower, upper](const Eigen::VectorXd& x, Eigen::VectorXd* r,
                                             Eigen::MatrixXd* jac, std::string* why) {
    std::map<Immersion, BendingModes> models;
    std::vector<PredictionDetail> details;
    std::vector<PredictedState> pred;
    if (!Predict(data, effects, x, jac != nullptr, &models, &details, &pred, why))
      return false;
    *r = EffectResiduals(data, pred);
    if (jac == nullptr) return true;
    jac->resize(r->size(), x.size());
    const std::vector<int> offsets = Offsets(data, effects);
    for (Eigen::Index i = 0; i < x.size(); ++i) {
      const double h = 1e-6 * (upper[i] - lower[i]);
      const double step = x[i] + h <= upper[i] ? h : -h;
      bool failed = false;
      if (SemiAnalyticColumn(data, effects, offsets, x, i, step, models, details,
                             jac->col(i), &failed, why))
        continue;
      if (failed) return false;
      // Where the expansion does not apply: difference the residuals.
      Eigen::VectorXd xs = x;
      xs[i] = x[i] + step;
      if (!PredictEffectModes(data, effects, xs, &pred, why)) return false;
      jac->col(i) = (EffectResiduals(data, pred) - *r) / (xs[i] - x[i]);
    }
    return true;
  };
  return p;
}

}  // namespace femup
