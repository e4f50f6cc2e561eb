// The fits of a diagnosis (diagnose_study_steps.h): one class's multi-start fit
// with the stated priors' residuals, and every candidate class fitted with its
// predictions of the fitted and held-out modes, locations and magnitudes.
#include <map>

#include "diagnose_study_steps.h"
#include "femup/core/errors.h"
#include "femup/problems/effect_priors.h"

namespace femup::diagnose_steps {

std::vector<const Effect*> Pointers(const std::vector<std::unique_ptr<Effect>>& effects) {
  std::vector<const Effect*> out;
  for (const auto& e : effects) out.push_back(e.get());
  return out;
}

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

void FitClasses(const std::vector<std::vector<std::string>>& classes,
                const CantileverSpec& nominal, const EffectFactory& make_effect,
                const NonlinearSolver& solver, DiagnosisResult* result) {
  DiagnosisResult& r = *result;
  std::string why;
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
      const FitOutcome fit = FitClass(r.fitted_data, ptrs, starts, solver, &c.starts);
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
}

}  // namespace femup::diagnose_steps
