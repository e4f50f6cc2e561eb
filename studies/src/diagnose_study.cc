#include "femup/studies/diagnose_study.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "femup/errors.h"
#include "femup/plot.h"
#include "femup/problems/effect_priors.h"
#include "femup/solvers/nonlinear_solver.h"
#include "femup/solvers/sampled_evidence.h"
#include "json_util.h"
#include "render_staged.h"
#include "stated_priors_text.h"

namespace femup {

namespace {

bool EndsWith(const std::string& s, const char* tail) {
  const std::string t(tail);
  return s.size() >= t.size() && s.compare(s.size() - t.size(), t.size(), t) == 0;
}

// One element's bending stiffness (EI times 1 + factor) or an added transverse
// mass (factor times rho A) over the element: the localisation scan's classes.
class ElementChange : public Effect {
 public:
  ElementChange(bool stiffness, double z0, double z1)
      : stiffness_(stiffness), z0_(z0), z1_(z1) {}
  std::string kind() const override {
    return stiffness_ ? "element_stiffness" : "element_mass";
  }
  std::vector<EffectParameter> Parameters(const CantileverSpec&) const override {
    if (stiffness_) return {{"factor", "EI change (fraction)", -0.95, 3.0, false}};
    return {{"factor", "added mass (fraction of rho A)", 0.0, 10.0, false}};
  }
  std::vector<Eigen::VectorXd> Starts(const CantileverSpec&) const override {
    return {Eigen::VectorXd::Constant(1, stiffness_ ? 0.0 : 0.01)};
  }
  void Apply(const Eigen::VectorXd& t, Immersion, bool, const CantileverSpec& nominal,
             CantileverSpec* spec) const override {
    if (stiffness_) {
      CantileverSpec::StiffnessChange c;
      c.z0 = z0_;
      c.z1 = z1_;
      c.factor = t[0];
      if (t[0] != 0) spec->stiffness_changes.push_back(c);
    } else if (t[0] > 0) {
      CantileverSpec::DistributedMass m;
      m.z0 = z0_;
      m.z1 = z1_;
      m.mass_per_length = t[0] * BeamMassPerLength(nominal);
      spec->distributed_masses.push_back(m);
    }
  }
  EffectLocation Location(const CantileverSpec&, const Eigen::VectorXd&) const override {
    EffectLocation l;
    l.x0 = z0_;
    l.x1 = z1_;
    return l;
  }
  std::vector<EffectMagnitude> Magnitudes(const CantileverSpec&,
                                          const Eigen::VectorXd& t) const override {
    return {{"factor", "1", t[0]}};
  }

 private:
  bool stiffness_;
  double z0_, z1_;
};

// Upper tail of chi2 with nu degrees of freedom (Wilson-Hilferty).
double Chi2UpperTail(double chi2, int nu) {
  if (nu <= 0) return chi2 > 0 ? 0.0 : 1.0;
  const double v = nu;
  const double z = (std::cbrt(chi2 / v) - (1 - 2 / (9 * v))) / std::sqrt(2 / (9 * v));
  return 0.5 * std::erfc(z / std::sqrt(2.0));
}

std::vector<const Effect*> Pointers(const std::vector<std::unique_ptr<Effect>>& effects) {
  std::vector<const Effect*> out;
  for (const auto& e : effects) out.push_back(e.get());
  return out;
}

struct FitOutcome {
  bool ok = false;
  bool converged = false;
  std::string message;
  Eigen::VectorXd theta;
  Eigen::MatrixXd jacobian;
  double chi2 = 0;
  std::vector<LocalOptimum> optima;  // every start's answer, distinct ones only
};

// Multi-start fit of one class on `data`, the stated normal priors' residuals
// included (effect_priors.h): the best start is the one with the least misfit
// with them; chi2 and the Jacobians kept are the data's alone.
FitOutcome FitClass(const EffectFitData& data, const std::vector<const Effect*>& effects,
                    const std::vector<Eigen::VectorXd>& starts,
                    const NonlinearSolver& solver, int* runs) {
  FitOutcome best;
  double best_misfit = 0;
  std::string last_error;
  const std::vector<EffectParameter> params = EffectSetParameters(data, effects);
  for (const Eigen::VectorXd& start : starts) {
    const NonlinearProblem fit = BuildEffectFitProblem(data, effects, start);
    const NonlinearProblem problem = WithPriorResiduals(fit, params);
    NonlinearSolution sol = solver.Solve(problem);
    ++*runs;
    if (sol.residual.size() != problem.num_residuals || !sol.residual.allFinite() ||
        sol.jacobian.rows() != problem.num_residuals) {
      last_error = sol.summary.message;
      continue;
    }
    const double misfit = sol.residual.squaredNorm();
    if (problem.num_residuals != fit.num_residuals) {
      sol.residual = Eigen::VectorXd(sol.residual.head(fit.num_residuals));
      sol.jacobian = Eigen::MatrixXd(sol.jacobian.topRows(fit.num_residuals));
    }
    const double chi2 = sol.residual.squaredNorm();
    bool seen = false;
    for (const LocalOptimum& o : best.optima)
      seen = seen || (o.theta - sol.x).cwiseAbs().maxCoeff() <= 1e-6;
    if (!seen) {
      LocalOptimum o;
      o.theta = sol.x;
      o.jacobian = sol.jacobian;
      o.chi2 = chi2;
      best.optima.push_back(std::move(o));
    }
    if (!best.ok || misfit < best_misfit) {
      best.ok = true;
      best_misfit = misfit;
      best.chi2 = chi2;
      best.theta = sol.x;
      best.jacobian = sol.jacobian;
      best.converged = sol.summary.usable();
      best.message = sol.summary.message;
    }
  }
  if (!best.ok)
    best.message = last_error.empty() ? "no start could be evaluated" : last_error;
  return best;
}

// Adds midpoints to every element.
CantileverSpec Refined(const CantileverSpec& spec) {
  CantileverSpec fine = spec;
  fine.node_heights.clear();
  for (std::size_t i = 0; i + 1 < spec.node_heights.size(); ++i) {
    fine.node_heights.push_back(spec.node_heights[i]);
    fine.node_heights.push_back(0.5 * (spec.node_heights[i] + spec.node_heights[i + 1]));
  }
  fine.node_heights.push_back(spec.node_heights.back());
  // Lumped masses sit on nodes: node k becomes node 2k.
  for (LumpedMass& m : fine.lumped_masses) m.node *= 2;
  return fine;
}

// Bending frequencies 1..count of a spec (no effects), for the mesh check.
Eigen::VectorXd BendingFrequencies(const CantileverSpec& spec, int count) {
  Eigen::VectorXd f;
  Eigen::MatrixXd unused;
  std::string why;
  if (!BendingModesAtSensors(spec, {}, count, &f, &unused, &why))
    throw InputError("model", "the nominal model cannot be solved: " + why);
  return f;
}

std::string Fixed(double v, int digits) {
  std::ostringstream o;
  o << std::fixed << std::setprecision(digits) << v;
  return o.str();
}

struct GapSummary {
  double rms_fitted = 0, rms_held_out = NAN, mean_mac_fitted = NAN,
         mean_mac_held_out = NAN;
};

void Accumulate(const EffectFitData& data, const std::vector<PredictedState>& pred,
                double* sum_sq, int* count, double* mac_sum, int* mac_count) {
  for (std::size_t s = 0; s < data.states.size() && s < pred.size(); ++s) {
    for (std::size_t j = 0; j < data.states[s].modes.size(); ++j) {
      const double e =
          pred[s].modes[j].frequency_hz / data.states[s].modes[j].frequency_hz - 1;
      *sum_sq += e * e;
      ++*count;
      if (data.states[s].modes[j].shape.size() > 0) {
        *mac_sum += pred[s].modes[j].mac;
        ++*mac_count;
      }
    }
  }
}

GapSummary Summarise(const DiagnosisResult& r, const std::vector<PredictedState>& fitted,
                     const std::vector<PredictedState>& held) {
  GapSummary g;
  double ss = 0, ms = 0;
  int n = 0, mn = 0;
  Accumulate(r.fitted_data, fitted, &ss, &n, &ms, &mn);
  g.rms_fitted = n > 0 ? std::sqrt(ss / n) : NAN;
  g.mean_mac_fitted = mn > 0 ? ms / mn : NAN;
  ss = ms = 0;
  n = mn = 0;
  Accumulate(r.held_out_data, held, &ss, &n, &ms, &mn);
  if (n > 0) g.rms_held_out = std::sqrt(ss / n);
  if (mn > 0) g.mean_mac_held_out = ms / mn;
  return g;
}

nlohmann::json GapJson(const GapSummary& g) {
  using json_util::Number;
  return {{"rms_frequency_error", Number(g.rms_fitted)},
          {"rms_frequency_error_held_out", Number(g.rms_held_out)},
          {"mean_mac", Number(g.mean_mac_fitted)},
          {"mean_mac_held_out", Number(g.mean_mac_held_out)}};
}

nlohmann::json LocationJson(const EffectLocation& l) {
  nlohmann::json j = nlohmann::json::object();
  if (std::isfinite(l.depth)) j["depth"] = l.depth;
  if (std::isfinite(l.x)) j["x"] = l.x;
  if (std::isfinite(l.x0)) j["x0"] = l.x0;
  if (std::isfinite(l.x1)) j["x1"] = l.x1;
  return j;
}

}  // namespace

DiagnosisResult RunDiagnosis(const Study& study) {
  if (!study.cantilever) {
    throw InputError(study.path,
                     "model: diagnose needs a cantilever model (type: cantilever)");
  }
  if (study.measurements.empty())
    throw InputError(study.path, "measurements: missing (nothing to diagnose)");
  const DiagnosisSpec spec = study.diagnosis.value_or(DiagnosisSpec());
  const CantileverSpec& nominal = *study.cantilever;
  DiagnosisResult r;
  r.study_name = study.name;
  r.description = study.description;
  r.length = BeamLength(nominal);
  r.frequency_noise = spec.frequency_noise;
  r.shape_noise = spec.shape_noise;
  r.form_error_fraction = spec.form_error;
  r.confidence = spec.confidence;
  r.priors = spec.priors;

  // The stated priors (effect_priors.h), checked before any work: families the
  // diagnosis tries, quantities of theirs, no regions (the cantilever's effects
  // are placed by a fitted height), no normal prior with sampled evidence.
  const std::vector<std::string> kinds =
      spec.candidates.empty() ? DefaultEffects() : spec.candidates;
  {
    auto fail = [&](const std::string& field, const std::string& what) {
      throw InputError(study.path, "diagnosis." + field + ": " + what);
    };
    const std::string invalid = spec.priors.Validate();
    if (!invalid.empty()) throw InputError(study.path, "diagnosis." + invalid);
    auto tried = [&](const std::string& kind) {
      return std::find(kinds.begin(), kinds.end(), kind) != kinds.end();
    };
    for (const auto& [kind, w] : spec.priors.weights)
      if (kind != "none" && !tried(kind))
        fail("weights." + kind, "is not among the families tried");
    for (const FamilyPrior& f : spec.priors.families) {
      const std::string field = "priors." + f.kind;
      if (!tried(f.kind)) fail(field, "is not among the families tried");
      if (!f.regions.empty())
        fail(field + ".regions",
             "the cantilever's effects are placed by a fitted height, not by region: "
             "state x_m: [from, to] instead");
      for (const QuantityPrior& q : f.quantities)
        if (q.normal && spec.evidence == "sampled")
          fail(field + "." + q.quantity,
               "a normal prior needs evidence: laplace (the sampled evidence draws from "
               "uniform priors)");
      try {
        WithFamilyPrior(CreateEffect(f.kind), f, nominal);
      } catch (const InputError& e) {
        fail(field + "." + e.where(), std::string(e.what()).substr(e.where().size() + 2));
      }
    }
  }
  // A family's effect with its stated priors.
  auto make_effect = [&](const std::string& kind) {
    std::unique_ptr<Effect> e = CreateEffect(kind);
    if (const FamilyPrior* f = spec.priors.Find(kind))
      e = WithFamilyPrior(std::move(e), *f, nominal);
    return e;
  };

  // Measured states as observed modes at their sensors.
  const std::vector<PreparedState> prepared = PrepareMeasurements(study);
  const std::vector<std::string>& labels = study.model.dof_labels();
  std::vector<ObservedState> observed;
  bool any_wet = false;
  int highest = 1;
  for (std::size_t s = 0; s < prepared.size(); ++s) {
    const ModalData& md = prepared[s].at_sensors;
    ObservedState st;
    st.state = md.state;
    st.immersion = md.immersion;
    any_wet = any_wet || md.immersion == Immersion::kWet;
    std::vector<int> rows;  // rows of md.shapes used
    if (md.HasShapes()) {
      const int num_rows = static_cast<int>(md.shapes.rows());
      for (int i = 0; i < num_rows; ++i) {
        const int dof = md.sensor_dofs.empty() ? i : md.sensor_dofs[i];
        const std::string& label = labels.at(dof);
        if (EndsWith(label, ":uy")) continue;  // axial: not a bending sensor
        if (md.sensor_dofs.empty() && !EndsWith(label, ":ux")) continue;
        rows.push_back(i);
        st.sensors.push_back(label);
      }
      if (rows.size() < 2) {
        r.warnings.push_back(
            "state " + md.state +
            ": fewer than 2 transverse sensors; its shapes are not used");
        st.sensors.clear();
        rows.clear();
      }
    }
    for (int j = 1; j < md.num_modes(); ++j) {
      // A cantilever's bending modes come in one order (mode k has k - 1
      // nodes); the pairing and the mode numbers rely on it.
      if (!(md.frequencies_hz[j] > md.frequencies_hz[j - 1])) {
        std::ostringstream msg;
        msg << "state " << md.state << ": frequencies must be listed in ascending order "
            << "(bending mode 1 first); mode " << j << " is " << md.frequencies_hz[j - 1]
            << " Hz and mode " << j + 1 << " is " << md.frequencies_hz[j] << " Hz";
        throw InputError("measurements", msg.str());
      }
    }
    for (int j = 0; j < md.num_modes(); ++j) {
      ObservedMode m;
      m.number =
          prepared[s].identified_modes.empty() ? j + 1 : prepared[s].identified_modes[j];
      m.frequency_hz = md.frequencies_hz[j];
      m.frequency_sigma = spec.frequency_noise;
      if (!rows.empty()) {
        m.shape.resize(static_cast<Eigen::Index>(rows.size()));
        for (std::size_t i = 0; i < rows.size(); ++i)
          m.shape[static_cast<Eigen::Index>(i)] = md.shapes(rows[i], j);
      }
      highest = std::max(highest, m.number);
      st.modes.push_back(m);
    }
    observed.push_back(st);
  }

  // Discretisation error of the nominal mesh, added to the noise.
  Eigen::VectorXd mesh_error = Eigen::VectorXd::Zero(highest);
  if (spec.mesh_error) {
    const Eigen::VectorXd coarse = BendingFrequencies(nominal, highest);
    const Eigen::VectorXd fine = BendingFrequencies(Refined(nominal), highest);
    mesh_error = (coarse.array() / fine.array() - 1).abs().matrix();
  }

  // Fitted and held-out modes.
  r.fitted_data.nominal = r.held_out_data.nominal = nominal;
  r.fitted_data.shape_sigma = r.held_out_data.shape_sigma = spec.shape_noise;
  r.fitted_data.use_shapes = r.held_out_data.use_shapes = spec.use_shapes;
  r.fitted_data.wet_only_added_mass = r.held_out_data.wet_only_added_mass = any_wet;
  std::set<std::pair<std::string, int>> held(spec.held_out_modes.begin(),
                                             spec.held_out_modes.end());
  for (const auto& h : held) {
    const auto it =
        std::find_if(observed.begin(), observed.end(),
                     [&](const ObservedState& o) { return o.state == h.first; });
    if (it == observed.end())
      throw InputError("diagnosis.held_out",
                       "no measured state is called '" + h.first + "'");
    if (h.second < 1 || h.second > static_cast<int>(it->modes.size())) {
      throw InputError("diagnosis.held_out", "state " + h.first + " has modes 1.." +
                                                 std::to_string(it->modes.size()) +
                                                 ", not " + std::to_string(h.second));
    }
  }
  // Per state, the nominal model's modes by number (frequencies, and shapes at
  // the sensors) for the families' form error: a fraction of the nominal
  // model's misfit, per frequency and per shape entry (measured, not fitted,
  // so every class is judged with the same uncertainty); and the mesh's error
  // in the shapes: each entry's change when every element is halved (node k
  // becomes node 2k).
  for (std::size_t s = 0; s < observed.size(); ++s) {
    ObservedState& st = observed[s];
    const bool shape_mesh = spec.mesh_error && !st.sensors.empty();
    Eigen::VectorXd nominal_hz;
    Eigen::MatrixXd coarse, fine;
    if (shape_mesh || spec.form_error > 0) {
      std::string why;
      if (!BendingModesAtSensors(nominal, st.sensors, highest, &nominal_hz, &coarse,
                                 &why))
        throw InputError("model", "the nominal model cannot be solved: " + why);
    }
    if (shape_mesh) {
      std::vector<std::string> fine_sensors;
      for (const std::string& label : st.sensors) {
        const std::size_t colon = label.find(':');
        fine_sensors.push_back("n" +
                               std::to_string(2 * std::stoi(label.substr(1, colon - 1))) +
                               label.substr(colon));
      }
      Eigen::VectorXd unused;
      std::string why;
      if (!BendingModesAtSensors(Refined(nominal), fine_sensors, highest, &unused, &fine,
                                 &why))
        throw InputError("model", "the refined nominal model cannot be solved: " + why);
    }
    for (std::size_t j = 0; j < st.modes.size(); ++j) {
      ObservedMode& m = st.modes[j];
      const int k = m.number - 1;
      const double e = mesh_error[k];
      const double form =
          spec.form_error > 0
              ? spec.form_error * std::abs(nominal_hz[k] / m.frequency_hz - 1)
              : 0.0;
      m.frequency_sigma =
          std::sqrt(m.frequency_sigma * m.frequency_sigma + e * e + form * form);
      if (m.shape.size() > 0 && (shape_mesh || spec.form_error > 0)) {
        const Eigen::VectorXd c = coarse.col(k);
        Eigen::ArrayXd var =
            Eigen::ArrayXd::Constant(m.shape.size(), spec.shape_noise * spec.shape_noise);
        if (shape_mesh) {
          const Eigen::VectorXd f = fine.col(k);
          var += (c - f * (f.dot(c) / f.squaredNorm())).array().square();
        }
        if (spec.form_error > 0) {
          const Eigen::VectorXd t = m.shape / m.shape.cwiseAbs().maxCoeff();
          var +=
              (spec.form_error * (c * (c.dot(t) / c.squaredNorm()) - t).array()).square();
        }
        m.shape_sigma = var.sqrt().matrix();
      }
      r.mesh_error.push_back(e);
      r.form_error.push_back(form);
    }
    ObservedState fit = st, out = st;
    fit.modes.clear();
    out.modes.clear();
    const int count = static_cast<int>(st.modes.size());
    for (int j = 0; j < count; ++j) {
      bool is_held = false;
      if (spec.held_out == "auto") {
        is_held = count >= 3 && j == count - 1;
      } else if (spec.held_out == "list") {
        is_held = held.count({st.state, j + 1}) > 0;
      }
      (is_held ? out : fit).modes.push_back(st.modes[j]);
    }
    // Both sets pair against all of the state's measured shapes, so a held-out
    // mode never takes the model mode a fitted one has.
    fit.companions = out.modes;
    out.companions = fit.modes;
    if (!fit.modes.empty()) r.fitted_data.states.push_back(fit);
    if (!out.modes.empty()) r.held_out_data.states.push_back(out);
  }
  if (r.fitted_data.states.empty())
    throw InputError("diagnosis.held_out",
                     "every measured mode is held out; none left to fit");
  {
    const std::string invalid = r.fitted_data.Validate();
    if (!invalid.empty()) throw InputError("measurements", invalid);
  }
  r.degrees_of_freedom = EffectDegreesOfFreedom(r.fitted_data);

  std::string why;
  if (!PredictEffectModes(r.fitted_data, {}, Eigen::VectorXd(), &r.nominal_fitted, &why))
    throw InputError("model", "the nominal model cannot be paired with the data: " + why);
  if (!r.held_out_data.states.empty() &&
      !PredictEffectModes(r.held_out_data, {}, Eigen::VectorXd(), &r.nominal_held_out,
                          &why))
    throw InputError("model", "the nominal model cannot be paired with the data: " + why);

  NonlinearSolverOptions options;
  // chi2 to 1e-6 relative is far finer than any evidence difference that matters.
  options.max_iterations = 60;
  options.function_tolerance = 1e-7;
  options.gradient_tolerance = 1e-8;
  options.parameter_tolerance = 1e-6;
  options.initial_trust_region = 1e4;
  options.kkt_tolerance = 1e-3;
  options.max_restarts = 0;
  const std::unique_ptr<NonlinearSolver> solver =
      CreateNonlinearSolver(spec.solver, options);

  // Candidate classes.
  std::vector<std::vector<std::string>> classes{{}};
  for (const auto& k : kinds) classes.push_back({k});
  const std::size_t num_singles = kinds.size();
  if (spec.max_effects >= 2) {
    for (std::size_t a = 0; a < kinds.size(); ++a)
      for (std::size_t b = a + 1; b < kinds.size(); ++b)
        classes.push_back({kinds[a], kinds[b]});
  }
  const std::size_t num_pairs = classes.size() - 1 - num_singles;

  std::map<std::string, Eigen::VectorXd> best_single;  // kind -> theta
  for (const auto& cls : classes) {
    DiagnosisCandidate c;
    c.kinds = cls;
    c.label = "none";
    std::vector<std::unique_ptr<Effect>> effects;
    for (std::size_t i = 0; i < cls.size(); ++i) {
      effects.push_back(make_effect(cls[i]));
      c.label = i == 0 ? cls[i] : c.label + "+" + cls[i];
    }
    const std::vector<const Effect*> ptrs = Pointers(effects);
    for (const auto& p : EffectSetParameters(r.fitted_data, ptrs))
      c.names.push_back(p.name);
    if (cls.empty()) {
      c.converged = true;
      c.theta = Eigen::VectorXd();
      c.jacobian =
          Eigen::MatrixXd(EffectResiduals(r.fitted_data, r.nominal_fitted).size(), 0);
      c.chi2 = EffectResiduals(r.fitted_data, r.nominal_fitted).squaredNorm();
    } else {
      std::vector<Eigen::VectorXd> starts;
      if (cls.size() == 1) {
        starts = effects[0]->Starts(nominal);
      } else {
        const Eigen::VectorXd& a = best_single[cls[0]];
        const Eigen::VectorXd& b = best_single[cls[1]];
        auto join = [](const Eigen::VectorXd& x, const Eigen::VectorXd& y) {
          Eigen::VectorXd v(x.size() + y.size());
          v << x, y;
          return v;
        };
        starts.push_back(join(a, b));
        const auto sa = effects[0]->Starts(nominal);
        const auto sb = effects[1]->Starts(nominal);
        for (std::size_t k = 0; k < 2; ++k) {
          if (k < sb.size()) starts.push_back(join(a, sb[k]));
          if (k < sa.size()) starts.push_back(join(sa[k], b));
        }
      }
      const FitOutcome fit = FitClass(r.fitted_data, ptrs, starts, *solver, &c.starts);
      if (!fit.ok) {
        c.message = fit.message;
        r.warnings.push_back(c.label + ": no fit (" + fit.message + ")");
        continue;
      }
      c.converged = fit.converged;
      c.message = fit.message;
      c.theta = fit.theta;
      c.jacobian = fit.jacobian;
      c.chi2 = fit.chi2;
      c.optima = fit.optima;
      if (cls.size() == 1) best_single[cls[0]] = fit.theta;
    }
    if (!PredictEffectModes(r.fitted_data, ptrs, c.theta, &c.fitted, &why)) continue;
    c.held_out_jacobian.resize(0, c.theta.size());
    if (!r.held_out_data.states.empty()) {
      if (!PredictEffectModes(r.held_out_data, ptrs, c.theta, &c.held_out, &why))
        continue;
      c.held_out_residual = EffectResiduals(r.held_out_data, c.held_out);
      c.held_out_chi2 = c.held_out_residual.squaredNorm();
      c.held_out_jacobian.resize(c.held_out_residual.size(), c.theta.size());
      if (c.theta.size() > 0) {
        const NonlinearProblem p = BuildEffectFitProblem(r.held_out_data, ptrs, c.theta);
        Eigen::VectorXd rh;
        if (!p.evaluate(c.theta, &rh, &c.held_out_jacobian, &why)) continue;
      }
    }
    // Each optimum's own prediction of the held-out modes (basins, below).
    for (LocalOptimum& o : c.optima) {
      o.held_out_jacobian.resize(0, o.theta.size());
      if (r.held_out_data.states.empty()) {
        o.predicts = true;
        continue;
      }
      std::vector<PredictedState> predicted;
      if (!PredictEffectModes(r.held_out_data, ptrs, o.theta, &predicted, &why)) continue;
      o.held_out_residual = EffectResiduals(r.held_out_data, predicted);
      o.held_out_jacobian.resize(o.held_out_residual.size(), o.theta.size());
      const NonlinearProblem p = BuildEffectFitProblem(r.held_out_data, ptrs, o.theta);
      Eigen::VectorXd rh;
      o.predicts = p.evaluate(o.theta, &rh, &o.held_out_jacobian, &why);
    }
    int offset = 0;
    for (const auto& e : effects) {
      const int n = static_cast<int>(e->Parameters(nominal).size());
      const Eigen::VectorXd t = c.theta.segment(offset, n);
      c.locations.push_back(e->Location(nominal, t));
      c.magnitudes.push_back(e->Magnitudes(nominal, t));
      offset += n;
    }
    r.candidates.push_back(std::move(c));
  }
  if (r.candidates.empty()) throw InputError("diagnosis", "no candidate could be fitted");

  // Evidence, at the stated noise, then tempered if even the best class fails.
  auto prior_box = [&](const std::vector<const Effect*>& effects, Eigen::VectorXd* lo,
                       Eigen::VectorXd* hi) {
    const auto params = EffectSetParameters(r.fitted_data, effects);
    lo->resize(static_cast<Eigen::Index>(params.size()));
    hi->resize(lo->size());
    for (std::size_t i = 0; i < params.size(); ++i) {
      (*lo)[static_cast<Eigen::Index>(i)] = params[i].lower;
      (*hi)[static_cast<Eigen::Index>(i)] = params[i].upper;
    }
  };
  auto score_all = [&](double temperature) {
    for (DiagnosisCandidate& c : r.candidates) {
      std::vector<std::unique_ptr<Effect>> effects;
      for (const auto& k : c.kinds) effects.push_back(make_effect(k));
      Eigen::VectorXd lo, hi;
      prior_box(Pointers(effects), &lo, &hi);
      const std::vector<EffectParameter> params =
          EffectSetParameters(r.fitted_data, Pointers(effects));
      Eigen::VectorXd normal_mean, normal_sigma;
      LocalNormalPriors(params, c.theta, &normal_mean, &normal_sigma);
      c.evidence = LaplaceEvidence(c.chi2, c.jacobian, c.theta, lo, hi, temperature,
                                   normal_mean, normal_sigma);
      c.held_out_log_predictive = LogPredictiveDensity(
          c.held_out_residual, c.held_out_jacobian, c.evidence.covariance, temperature);
      // Laplace's approximation at every separated basin the multi-start fit
      // found, summed (a posterior with several modes: a location that few
      // modes cannot pin down), and the held-out modes' density as the mixture
      // of each basin's prediction, weighted by its evidence. One basin: the
      // best fit's Laplace evidence and prediction as they are.
      std::vector<double> log_z{c.evidence.log_evidence};
      std::vector<double> log_p{c.held_out_log_predictive};
      std::vector<const LocalOptimum*> order;
      for (const LocalOptimum& o : c.optima) order.push_back(&o);
      std::sort(
          order.begin(), order.end(),
          [](const LocalOptimum* a, const LocalOptimum* b) { return a->chi2 < b->chi2; });
      // The kept basins: where, their chi2, and their Laplace covariance.
      std::vector<Eigen::VectorXd> kept_theta{c.theta};
      std::vector<double> kept_chi2{c.chi2};
      std::vector<Eigen::LDLT<Eigen::MatrixXd>> kept_covariance;
      if (c.theta.size() > 0) kept_covariance.emplace_back(c.evidence.covariance);
      const std::vector<const Effect*> ptrs = Pointers(effects);
      for (const LocalOptimum* o : order) {
        // Optima whose likelihood is below e^-15 of the best's add nothing.
        if (!o->predicts || o->chi2 > c.chi2 + 30 * temperature || c.theta.size() == 0 ||
            !o->jacobian.allFinite())
          continue;
        LocalNormalPriors(params, o->theta, &normal_mean, &normal_sigma);
        const ModelEvidence e = LaplaceEvidence(o->chi2, o->jacobian, o->theta, lo, hi,
                                                temperature, normal_mean, normal_sigma);
        const Eigen::LDLT<Eigen::MatrixXd> covariance(e.covariance);
        // The same basin as a kept one: within 3 of its posterior standard
        // deviations, measured by either basin's covariance, or no barrier
        // between the two (chi2 halfway no more than 2 T above the higher of
        // the two).
        bool separate = true;
        for (std::size_t k = 0; k < kept_theta.size() && separate; ++k) {
          const Eigen::VectorXd d = o->theta - kept_theta[k];
          std::vector<PredictedState> halfway;
          std::string unused;
          separate =
              d.dot(kept_covariance[k].solve(d)) > 9 && d.dot(covariance.solve(d)) > 9 &&
              PredictEffectModes(r.fitted_data, ptrs, 0.5 * (o->theta + kept_theta[k]),
                                 &halfway, &unused) &&
              EffectResiduals(r.fitted_data, halfway).squaredNorm() >
                  std::max(o->chi2, kept_chi2[k]) + 2 * temperature;
        }
        if (!separate) continue;
        log_z.push_back(e.log_evidence);
        log_p.push_back(LogPredictiveDensity(o->held_out_residual, o->held_out_jacobian,
                                             e.covariance, temperature));
        kept_theta.push_back(o->theta);
        kept_chi2.push_back(o->chi2);
        kept_covariance.push_back(covariance);
      }
      c.basins = static_cast<int>(log_z.size());
      if (log_z.size() > 1) {
        const BasinMixture mix = CombineBasins(log_z, log_p);
        c.evidence.log_occam += mix.log_evidence - c.evidence.log_evidence;
        c.evidence.log_evidence = mix.log_evidence;
        c.held_out_log_predictive = mix.log_predictive;
      }
      c.score = c.evidence.log_evidence + c.held_out_log_predictive;
      c.laplace_score = c.score;
    }
  };
  // The same by importance sampling over each class's prior (sampled_evidence.h),
  // the proposal's components at the distinct optima of its multi-start fit: the
  // evidence of the fitted modes, and of fitted and held-out modes together, from
  // the same draws (their difference is the held-out modes' predictive density).
  // Classes whose Laplace score is more than kSampledBelow under the best keep
  // it: their probability is below e^-kSampledBelow either way.
  constexpr double kSampledBelow = 25;
  // The largest standard error of a sampled log evidence that replaces Laplace's.
  constexpr double kSampledStandardError = 0.2;
  auto sample_all = [&](double temperature) {
    double best_laplace = -std::numeric_limits<double>::infinity();
    for (const DiagnosisCandidate& c : r.candidates)
      best_laplace = std::max(best_laplace, c.laplace_score);
    for (std::size_t i = 0; i < r.candidates.size(); ++i) {
      DiagnosisCandidate& c = r.candidates[i];
      if (c.theta.size() == 0) continue;  // no parameters: Laplace is exact
      if (c.laplace_score < best_laplace - kSampledBelow) continue;
      std::vector<std::unique_ptr<Effect>> effects;
      for (const auto& k : c.kinds) effects.push_back(make_effect(k));
      const std::vector<const Effect*> ptrs = Pointers(effects);
      Eigen::VectorXd lo, hi;
      prior_box(ptrs, &lo, &hi);
      std::vector<EvidenceComponent> components;
      for (const LocalOptimum& o : c.optima) {
        // Optima whose likelihood is below e^-15 of the best's add nothing.
        if (o.chi2 > c.chi2 + 30 * temperature) continue;
        components.push_back(
            {o.theta, LaplaceEvidence(o.chi2, o.jacobian, o.theta, lo, hi, temperature)
                          .covariance});
      }
      const bool has_held_out = !r.held_out_data.states.empty();
      std::vector<PredictedState> predicted;
      std::string unused;
      const MisfitFunction misfit = [&](const Eigen::VectorXd& t, Eigen::VectorXd* chi2) {
        chi2->setZero(2);
        if (!PredictEffectModes(r.fitted_data, ptrs, t, &predicted, &unused))
          return false;
        (*chi2)[0] = EffectResiduals(r.fitted_data, predicted).squaredNorm();
        if (!has_held_out) return true;
        if (!PredictEffectModes(r.held_out_data, ptrs, t, &predicted, &unused))
          return false;
        (*chi2)[1] = EffectResiduals(r.held_out_data, predicted).squaredNorm();
        return true;
      };
      SampledEvidenceOptions sampling;
      sampling.samples = spec.evidence_samples;
      sampling.stream = i;  // classes in a fixed order: the same draws on every run
      sampling.temperature = temperature;
      const EvidenceSamples draws =
          SampleEvidence(misfit, 2, lo, hi, components, sampling);
      const SampledLogEvidence fitted =
          LogEvidenceFromSamples(draws, {true, false}, temperature);
      const SampledLogEvidence all =
          LogEvidenceFromSamples(draws, {true, true}, temperature);
      c.evidence_draws = static_cast<int>(draws.log_weight.size());
      c.evidence_effective_draws = all.effective_samples;
      c.evidence_standard_error = all.log_standard_error;
      // A poor proposal (a thin curved ridge in several dimensions) shows as few
      // effective draws and a large error, and its estimate is biased low: keep
      // Laplace's then.
      if (!std::isfinite(fitted.log_evidence) || !std::isfinite(all.log_evidence) ||
          std::max(fitted.log_standard_error, all.log_standard_error) >
              kSampledStandardError)
        continue;
      c.evidence_method = "sampled";
      c.evidence.log_evidence = fitted.log_evidence;
      c.evidence.log_occam = fitted.log_evidence + 0.5 * c.chi2 / temperature;
      c.held_out_log_predictive = all.log_evidence - fitted.log_evidence;
      c.score = all.log_evidence;
    }
  };
  score_all(1.0);
  const auto best =
      std::max_element(r.candidates.begin(), r.candidates.end(),
                       [](const DiagnosisCandidate& a, const DiagnosisCandidate& b) {
                         return a.score < b.score;
                       });
  const int nu = std::max(1, r.degrees_of_freedom - best->evidence.num_parameters);
  r.best_chi2_p_value = Chi2UpperTail(best->chi2, nu);
  if (r.best_chi2_p_value < 0.01) {
    r.temperature = std::max(1.0, best->chi2 / nu);
    score_all(r.temperature);
    std::ostringstream w;
    w << "even the best class (" << best->label
      << ") leaves chi2 = " << Fixed(best->chi2, 1) << " on " << nu
      << " degrees of freedom (p = " << r.best_chi2_p_value
      << "): the stated noise is too small or no candidate is the true form; the noise "
         "is "
         "scaled by sqrt("
      << Fixed(r.temperature, 2) << ") for the probabilities";
    r.warnings.push_back(w.str());
  }
  if (spec.evidence == "sampled") sample_all(r.temperature);
  Eigen::VectorXd scores(static_cast<Eigen::Index>(r.candidates.size()));
  Eigen::VectorXd prior(scores.size());
  const double levels = spec.max_effects >= 2 && num_pairs > 0 ? 3.0 : 2.0;
  for (std::size_t i = 0; i < r.candidates.size(); ++i) {
    const auto& c = r.candidates[i];
    scores[static_cast<Eigen::Index>(i)] = c.score;
    const double share = c.kinds.empty()       ? 1.0
                         : c.kinds.size() == 1 ? 1.0 / num_singles
                                               : 1.0 / num_pairs;
    // Stated weights: "none"'s, a family's, a pair's the product of its two.
    double weight = c.kinds.empty() ? spec.priors.Weight("none") : 1.0;
    for (const std::string& k : c.kinds) weight *= spec.priors.Weight(k);
    prior[static_cast<Eigen::Index>(i)] = weight * share / levels;
  }
  const Eigen::VectorXd post = PosteriorProbabilities(scores, prior);
  for (std::size_t i = 0; i < r.candidates.size(); ++i)
    r.candidates[i].probability = post[static_cast<Eigen::Index>(i)];
  std::stable_sort(r.candidates.begin(), r.candidates.end(),
                   [](const DiagnosisCandidate& a, const DiagnosisCandidate& b) {
                     return a.probability > b.probability;
                   });
  std::vector<std::string> all_kinds{"none"};
  all_kinds.insert(all_kinds.end(), kinds.begin(), kinds.end());
  for (const auto& k : all_kinds) {
    double p = 0;
    for (const auto& c : r.candidates) {
      if ((k == "none" && c.kinds.empty()) ||
          std::find(c.kinds.begin(), c.kinds.end(), k) != c.kinds.end())
        p += c.probability;
    }
    r.kind_probabilities.emplace_back(k, p);
  }

  // Verdict.
  const DiagnosisCandidate& top = r.candidates.front();
  r.verdict_probability = top.probability;
  r.separated = top.probability >= spec.confidence;
  double cumulative = 0;
  for (const auto& c : r.candidates) {
    r.indistinguishable.push_back(c.label);
    cumulative += c.probability;
    if (cumulative >= spec.confidence) break;
  }
  if (r.separated) r.indistinguishable.clear();
  std::ostringstream v;
  if (top.kinds.empty()) {
    v << "no significant gap: the residual is within what the stated noise explains";
  } else {
    v << top.label;
  }
  v << " (P = " << Fixed(top.probability, 3) << ")";
  if (!r.separated) {
    v << "; the data cannot separate ";
    for (std::size_t i = 0; i < r.indistinguishable.size(); ++i) {
      const auto& c = *std::find_if(
          r.candidates.begin(), r.candidates.end(),
          [&](const DiagnosisCandidate& x) { return x.label == r.indistinguishable[i]; });
      v << (i == 0                                ? ""
            : i + 1 == r.indistinguishable.size() ? " and "
                                                  : ", ")
        << c.label << " (" << Fixed(c.probability, 2) << ")";
    }
  }
  r.verdict = v.str();

  // Where: one element at a time.
  if (spec.localise) {
    const double chi2_nominal =
        EffectResiduals(r.fitted_data, r.nominal_fitted).squaredNorm();
    for (std::size_t e = 0; e + 1 < nominal.node_heights.size(); ++e) {
      ElementIndicator ind;
      ind.element = static_cast<int>(e + 1);
      ind.x0 = nominal.node_heights[e];
      ind.x1 = nominal.node_heights[e + 1];
      for (bool stiffness : {true, false}) {
        const ElementChange change(stiffness, ind.x0, ind.x1);
        int runs = 0;
        const FitOutcome fit =
            FitClass(r.fitted_data, {&change}, change.Starts(nominal), *solver, &runs);
        const double drop = fit.ok ? std::max(0.0, chi2_nominal - fit.chi2) : 0.0;
        const double factor = fit.ok ? fit.theta[0] : NAN;
        (stiffness ? ind.stiffness_chi2_drop : ind.mass_chi2_drop) = drop;
        (stiffness ? ind.stiffness_factor : ind.mass_factor) = factor;
      }
      r.localisation.push_back(ind);
    }
  }
  return r;
}

void WriteDiagnosisOutputs(const DiagnosisResult& r, bool plots, OutputDir* out,
                           std::vector<std::string>* warnings) {
  using json_util::Number;
  nlohmann::json j;
  j["femup_version"] = "0.1.0";
  j["command"] = "diagnose";
  j["study"] = r.study_name;
  j["length"] = r.length;
  j["verdict"] = {{"text", r.verdict},
                  {"kind", r.candidates.front().label},
                  {"kinds", r.candidates.front().kinds},
                  {"probability", r.verdict_probability},
                  {"separated", r.separated},
                  {"confidence", r.confidence},
                  {"indistinguishable", r.indistinguishable}};
  j["noise"] = {{"frequency", r.frequency_noise},
                {"shape", r.shape_noise},
                {"mesh_error", r.mesh_error},
                {"form_error", r.form_error},
                {"form_error_fraction", r.form_error_fraction},
                {"temperature", r.temperature},
                {"best_chi2_p_value", r.best_chi2_p_value},
                {"degrees_of_freedom", r.degrees_of_freedom}};
  nlohmann::json kp = nlohmann::json::object();
  for (const auto& [k, p] : r.kind_probabilities) kp[k] = p;
  j["kind_probabilities"] = kp;
  const GapSummary before = Summarise(r, r.nominal_fitted, r.nominal_held_out);
  j["effects"] = nlohmann::json::array();
  for (std::size_t i = 0; i < r.candidates.size(); ++i) {
    const DiagnosisCandidate& c = r.candidates[i];
    nlohmann::json cj = {{"rank", i + 1},
                         {"kind", c.label},
                         {"kinds", c.kinds},
                         {"probability", c.probability},
                         {"score", c.score},
                         {"log_evidence", c.evidence.log_evidence},
                         {"log_occam", c.evidence.log_occam},
                         {"basins", c.basins},
                         {"chi2", c.chi2},
                         {"held_out_chi2", c.held_out_chi2},
                         {"held_out_log_predictive", c.held_out_log_predictive},
                         {"evidence_method", c.evidence_method},
                         {"laplace_score", c.laplace_score},
                         {"evidence_draws", c.evidence_draws},
                         {"evidence_effective_draws", c.evidence_effective_draws},
                         {"evidence_standard_error", c.evidence_standard_error},
                         {"converged", c.converged},
                         {"fits", c.starts}};
    nlohmann::json params = nlohmann::json::object();
    for (std::size_t p = 0; p < c.names.size(); ++p) {
      const auto k = static_cast<Eigen::Index>(p);
      params[c.names[p]] = {
          {"value", Number(c.theta[k])},
          {"sigma", c.evidence.sigma.size() > k ? Number(c.evidence.sigma[k])
                                                : nlohmann::json(nullptr)}};
    }
    cj["parameters"] = params;
    cj["components"] = nlohmann::json::array();
    for (std::size_t e = 0; e < c.kinds.size(); ++e) {
      nlohmann::json mag = nlohmann::json::object();
      for (const auto& m : c.magnitudes[e])
        mag[m.name] = {{"value", Number(m.value)}, {"unit", m.unit}};
      cj["components"].push_back({{"kind", c.kinds[e]},
                                  {"location", LocationJson(c.locations[e])},
                                  {"magnitude", mag}});
    }
    if (c.kinds.size() == 1) {
      cj["location"] = cj["components"][0]["location"];
      cj["magnitude"] = cj["components"][0]["magnitude"];
    }
    cj["gap_before"] = GapJson(before);
    cj["gap_after"] = GapJson(Summarise(r, c.fitted, c.held_out));
    j["effects"].push_back(cj);
  }
  // Mode by mode, before and after the top class.
  const DiagnosisCandidate& top = r.candidates.front();
  nlohmann::json modes = nlohmann::json::array();
  auto add_modes = [&](const EffectFitData& data, const std::vector<PredictedState>& nom,
                       const std::vector<PredictedState>& upd, bool held_out) {
    for (std::size_t s = 0; s < data.states.size(); ++s) {
      for (std::size_t k = 0; k < data.states[s].modes.size(); ++k) {
        const ObservedMode& m = data.states[s].modes[k];
        const PredictedMode& a = nom[s].modes[k];
        const PredictedMode& b = upd[s].modes[k];
        const bool shape = m.shape.size() > 0;
        modes.push_back(
            {{"state", data.states[s].state},
             {"mode", m.number},
             {"held_out", held_out},
             {"measured_hz", m.frequency_hz},
             {"nominal_hz", a.frequency_hz},
             {"updated_hz", b.frequency_hz},
             {"nominal_error", a.frequency_hz / m.frequency_hz - 1},
             {"updated_error", b.frequency_hz / m.frequency_hz - 1},
             {"nominal_mac", shape ? Number(a.mac) : nlohmann::json(nullptr)},
             {"updated_mac", shape ? Number(b.mac) : nlohmann::json(nullptr)}});
      }
    }
  };
  add_modes(r.fitted_data, r.nominal_fitted, top.fitted, false);
  if (!r.held_out_data.states.empty())
    add_modes(r.held_out_data, r.nominal_held_out, top.held_out, true);
  j["gap"] = {{"class", top.label}, {"modes", modes}};
  j["localisation"] = nlohmann::json::array();
  for (const auto& e : r.localisation) {
    j["localisation"].push_back({{"element", e.element},
                                 {"x0", e.x0},
                                 {"x1", e.x1},
                                 {"stiffness_factor", Number(e.stiffness_factor)},
                                 {"stiffness_chi2_drop", e.stiffness_chi2_drop},
                                 {"mass_factor", Number(e.mass_factor)},
                                 {"mass_chi2_drop", e.mass_chi2_drop}});
  }
  j["warnings"] = r.warnings;
  j["stated_priors"] = StatedPriorsJson(r.priors);
  out->WriteText("diagnosis.json", j.dump(2) + "\n");
  if (!plots) return;

  // Where: chi2 drop per element along the structure.
  if (!r.localisation.empty()) {
    Plot p;
    p.title = "Where: chi2 removed by changing one element (verdict: " +
              r.candidates.front().label + ")";
    p.x_label = "height above the support (m)";
    p.y_label = "chi2 drop";
    PlotSeries ks{"bending stiffness of the element",
                  PlotSeries::Style::kLinesPoints,
                  {},
                  {},
                  {},
                  {}};
    PlotSeries ms{
        "mass added to the element", PlotSeries::Style::kLinesPoints, {}, {}, {}, {}};
    double top_drop = 0;
    for (const auto& e : r.localisation) {
      const double mid = 0.5 * (e.x0 + e.x1);
      ks.x.push_back(mid);
      ks.y.push_back(e.stiffness_chi2_drop);
      ms.x.push_back(mid);
      ms.y.push_back(e.mass_chi2_drop);
      top_drop = std::max({top_drop, e.stiffness_chi2_drop, e.mass_chi2_drop});
    }
    p.series = {ks, ms};
    PlotSeries where{
        "located by the top class", PlotSeries::Style::kPoints, {}, {}, {}, {}};
    for (const auto& l : top.locations) {
      for (double x : {l.depth, l.x, l.x0, l.x1}) {
        if (std::isfinite(x)) {
          where.x.push_back(x);
          where.y.push_back(top_drop);
        }
      }
    }
    if (!where.x.empty()) p.series.push_back(where);
    Figure f;
    f.panels = {p};
    RenderStaged(f, "localisation", out, warnings);
  }
  // Which: probabilities of the leading classes.
  {
    Plot p;
    p.title = "Which effect: posterior probability of each class";
    p.y_label = "probability";
    PlotSeries bars{"posterior", PlotSeries::Style::kBars, {}, {}, {}, {}};
    const std::size_t shown = std::min<std::size_t>(10, r.candidates.size());
    for (std::size_t i = 0; i < shown; ++i) {
      bars.x.push_back(static_cast<double>(i + 1));
      bars.y.push_back(r.candidates[i].probability);
      p.x_tick_labels.push_back(r.candidates[i].label);
    }
    p.series = {bars};
    Figure f;
    f.panels = {p};
    f.width_px = 1100;
    RenderStaged(f, "effects", out, warnings);
  }
  // How far it shrinks: frequency error per mode before and after.
  {
    Plot p;
    p.title = "Frequency error before and after " + top.label + " (* held out)";
    p.y_label = "|f_model / f_measured - 1| (%)";
    p.log_y = true;
    PlotSeries b{"nominal model", PlotSeries::Style::kLinesPoints, {}, {}, {}, {}};
    PlotSeries a{"with " + top.label, PlotSeries::Style::kLinesPoints, {}, {}, {}, {}};
    int x = 0;
    for (const auto& m : modes) {
      ++x;
      b.x.push_back(x);
      a.x.push_back(x);
      b.y.push_back(std::max(1e-4, 100 * std::abs(m["nominal_error"].get<double>())));
      a.y.push_back(std::max(1e-4, 100 * std::abs(m["updated_error"].get<double>())));
      p.x_tick_labels.push_back(m["state"].get<std::string>() + " " +
                                std::to_string(m["mode"].get<int>()) +
                                (m["held_out"].get<bool>() ? "*" : ""));
    }
    p.series = {b, a};
    Figure f;
    f.panels = {p};
    RenderStaged(f, "gap", out, warnings);
  }
}

std::string DiagnosisReport(const DiagnosisResult& r) {
  std::ostringstream o;
  o << "femup diagnose: " << r.study_name << "\n";
  o << "  data: " << r.fitted_data.states.size() << " state(s), " << r.degrees_of_freedom
    << " informative residuals fitted";
  int held = 0;
  for (const auto& s : r.held_out_data.states) held += static_cast<int>(s.modes.size());
  o << ", " << held << " mode(s) held out\n";
  o << "  noise: frequency " << 100 * r.frequency_noise << " %, shape "
    << 100 * r.shape_noise << " %";
  if (r.form_error_fraction > 0)
    o << ", form error " << 100 * r.form_error_fraction << " % of the nominal misfit";
  if (r.temperature > 1) o << " (scaled by sqrt(" << Fixed(r.temperature, 2) << "))";
  o << "\n";
  if (!r.priors.empty()) o << "  stated priors: " << StatedPriorsLine(r.priors) << "\n";
  o << "\n  verdict: " << r.verdict << "\n\n";
  o << "  rank  class                                    P       chi2   held-out  "
       "where\n";
  const std::size_t shown = std::min<std::size_t>(8, r.candidates.size());
  for (std::size_t i = 0; i < shown; ++i) {
    const auto& c = r.candidates[i];
    std::ostringstream where;
    for (std::size_t e = 0; e < c.locations.size(); ++e) {
      const auto& l = c.locations[e];
      if (e) where << "; ";
      if (std::isfinite(l.depth)) {
        where << "depth " << Fixed(l.depth, 2) << " m";
      } else if (std::isfinite(l.x) && std::isfinite(l.x0)) {
        where << "x " << Fixed(l.x0, 2) << "-" << Fixed(l.x1, 2) << " m";
      } else if (std::isfinite(l.x)) {
        where << "x " << Fixed(l.x, 2) << " m";
      } else {
        where << "everywhere";
      }
    }
    o << "  " << std::setw(4) << i + 1 << "  " << std::left << std::setw(40) << c.label
      << std::right << std::setw(6) << Fixed(c.probability, 3) << std::setw(11)
      << Fixed(c.chi2, 1) << std::setw(10) << Fixed(c.held_out_chi2, 1) << "  "
      << where.str() << "\n";
  }
  const auto& top = r.candidates.front();
  o << "\n  gap (" << top.label
    << "): mode, measured Hz, nominal error %, updated error %\n";
  auto list = [&](const EffectFitData& d, const std::vector<PredictedState>& nom,
                  const std::vector<PredictedState>& upd, const char* tag) {
    for (std::size_t s = 0; s < d.states.size(); ++s) {
      for (std::size_t k = 0; k < d.states[s].modes.size(); ++k) {
        const auto& m = d.states[s].modes[k];
        o << "    " << d.states[s].state << " " << m.number << tag << "  "
          << Fixed(m.frequency_hz, 3) << "  "
          << Fixed(100 * (nom[s].modes[k].frequency_hz / m.frequency_hz - 1), 3) << "  "
          << Fixed(100 * (upd[s].modes[k].frequency_hz / m.frequency_hz - 1), 3) << "\n";
      }
    }
  };
  list(r.fitted_data, r.nominal_fitted, top.fitted, "");
  if (!r.held_out_data.states.empty())
    list(r.held_out_data, r.nominal_held_out, top.held_out, " (held out)");
  for (const auto& w : r.warnings) o << "  warning: " << w << "\n";
  return o.str();
}

}  // namespace femup
