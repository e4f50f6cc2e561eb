#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "effect_ranking_steps.h"
#include "femup/core/errors.h"
#include "femup/problems/effect_priors.h"
#include "femup/problems/model_effect_pair.h"
#include "femup/problems/model_effect_pencil.h"

namespace femup::effect_ranking_steps {

Fit FitInstance(const std::shared_ptr<const Structure>& structure,
                const std::shared_ptr<const ModelEffect>& effect,
                const std::vector<ModalData>& states,
                const EigenSensitivityOptions& options, const NonlinearSolver& solver,
                bool ritz) {
  Fit best;
  double best_misfit = 0;
  const std::vector<EffectParameter> params = effect->Parameters();
  // Besides the effect's starts, one from its first start with every
  // parameter nested at its lower bound held there (EffectParameter::
  // nested_at_lower: the effect is then a simpler one, a point mass without
  // its rotary inertia), so that the fit ends no worse than the simpler
  // effect's from that start: freeing such a parameter from its bound gives
  // the solver no gradient to follow (the inertia m r^2 is flat in ln r there).
  struct Start {
    Eigen::VectorXd x;
    bool nested = false;  // the nested parameters held at their lower bounds
  };
  std::vector<Start> starts;
  for (const Eigen::VectorXd& x : effect->Starts()) starts.push_back({x, false});
  if (!starts.empty()) {
    Start nested{starts.front().x, true};
    bool any = false;
    for (std::size_t i = 0; i < params.size(); ++i) {
      if (!params[i].nested_at_lower) continue;
      nested.x[static_cast<Eigen::Index>(i)] = params[i].lower;
      any = true;
    }
    if (any) starts.push_back(nested);
  }
  auto solve = [&](const Start& start, const EigenSensitivityOptions& o,
                   NonlinearSolution* sol) {
    const NonlinearProblem data =
        BuildModelEffectFitProblem(structure, {effect}, states, o, start.x);
    NonlinearProblem problem = WithPriorResiduals(data, params);
    for (std::size_t i = 0; start.nested && i < params.size(); ++i) {
      if (params[i].nested_at_lower)
        problem.fixed.emplace_back(static_cast<int>(i),
                                   start.x[static_cast<Eigen::Index>(i)]);
    }
    *sol = solver.Solve(problem);
    return sol->residual.size() == problem.num_residuals && sol->residual.allFinite() &&
                   sol->jacobian.rows() == problem.num_residuals
               ? data.num_residuals
               : -1;
  };
  if (ritz) {
    // The searches, on the reduced models; a start whose basis cannot be built
    // (its pencil does not solve) is searched on the full model.
    std::vector<std::pair<double, Start>> ends;
    std::vector<Start> unsearched;  // fitted on the full model as they are
    const ModelEffectPencil pencil(structure, {effect});
    // A search that ends where the reduced model no longer matches the full
    // one (their misfits differ by more than 1 + 1e-3 of it: the basis was
    // built too far away) is searched again on a basis built where it ended,
    // up to kRebases times; then the full fit takes over from there anyway.
    constexpr int kRebases = 3;
    const NonlinearProblem full_data = BuildModelEffectFitProblem(
        structure, {effect}, states, options, starts.front().x);
    const NonlinearProblem full = WithPriorResiduals(full_data, params);
    for (const Start& start : starts) {
      Start from = start;
      double misfit = 0;
      bool searched = false;
      for (int round = 0; round <= kRebases; ++round) {
        EigenSensitivityOptions reduced = options;
        try {
          reduced.ritz = BuildRitzBasis(pencil, states, options, from.x);
        } catch (const InputError&) {
          break;
        } catch (const NumericalError&) {
          break;
        }
        NonlinearSolution sol;
        if (solve(from, reduced, &sol) < 0) break;
        from.x = sol.x;
        misfit = sol.residual.squaredNorm();
        searched = true;
        Eigen::VectorXd r;
        std::string why;
        if (!full.evaluate(from.x, &r, nullptr, &why)) break;
        if (std::abs(r.squaredNorm() - misfit) <= 1 + 1e-3 * misfit) break;
        misfit = r.squaredNorm();
      }
      if (searched) {
        ends.emplace_back(misfit, from);
      } else {
        unsearched.push_back(from);
      }
    }
    std::stable_sort(ends.begin(), ends.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    starts.clear();
    for (const auto& [misfit, end] : ends) {
      if (!starts.empty() && misfit > ends.front().first + 10) break;
      bool same = false;
      for (const Start& s : starts)
        same = same || (s.nested == end.nested &&
                        (s.x - end.x).lpNorm<Eigen::Infinity>() <= 1e-3);
      if (!same) starts.push_back(end);
    }
    starts.insert(starts.end(), unsearched.begin(), unsearched.end());
  }
  for (const Start& start : starts) {
    NonlinearSolution sol;
    const int rows = solve(start, options, &sol);
    if (rows < 0) continue;
    const double misfit = sol.residual.squaredNorm();
    if (!best.ok || misfit < best_misfit) {
      const Eigen::VectorXd residual = sol.residual.head(rows);
      best = {true,     sol.summary.usable(),   sol.x, sol.jacobian.topRows(rows),
              residual, residual.squaredNorm(), true};
      best_misfit = misfit;
    }
  }
  return best;
}

Screen ScreenInstance(const std::shared_ptr<const Structure>& structure,
                      const std::shared_ptr<const ModelEffect>& effect,
                      const std::vector<ModalData>& states,
                      const EigenSensitivityOptions& options) {
  const std::vector<EffectParameter> params = effect->Parameters();
  Screen best;
  for (const Eigen::VectorXd& start : effect->Starts()) {
    const NonlinearProblem data =
        BuildModelEffectFitProblem(structure, {effect}, states, options, start);
    const NonlinearProblem problem = WithPriorResiduals(data, params);
    Eigen::VectorXd r;
    Eigen::MatrixXd j;
    std::string why;
    if (!problem.evaluate(start, &r, &j, &why) || !r.allFinite() || !j.allFinite())
      continue;
    // The fit problem's own ranges (the effect pencil's), kept by the priors.
    const Eigen::VectorXd step = j.completeOrthogonalDecomposition().solve(-r);
    const Eigen::VectorXd to =
        (start + step).cwiseMax(problem.lower).cwiseMin(problem.upper);
    const Eigen::VectorXd predicted = r + j * (to - start);
    const double misfit = std::min(r.squaredNorm(), predicted.squaredNorm());
    if (!(misfit < best.misfit)) continue;
    best.misfit = misfit;
    const bool stepped = predicted.squaredNorm() < r.squaredNorm();
    const Eigen::Index rows = data.num_residuals;
    const Eigen::VectorXd residual = (stepped ? predicted : r).head(rows);
    best.fit = {true,
                false,
                stepped ? to : start,
                j.topRows(rows),
                residual,
                residual.squaredNorm(),
                false};
  }
  return best;
}

Nominal NominalResidual(const Structure& structure, const std::vector<ModalData>& states,
                        const EigenSensitivityOptions& options) {
  const NonlinearProblem problem =
      NominalOutputErrorProblem(structure, {}, states, options);
  Eigen::VectorXd r;
  std::string why;
  if (!problem.evaluate(Eigen::VectorXd::Zero(1), &r, nullptr, &why)) {
    throw InputError("measurements",
                     "the nominal model cannot be compared with the data: " + why);
  }
  return Nominal{r, FrequencyRows(problem)};
}

double PlacesApart(const std::vector<std::shared_ptr<const ModelEffect>>& effects,
                   const std::vector<std::size_t>& effect_kind, std::size_t singles,
                   std::size_t k) {
  std::vector<const EffectRegion*> of;
  for (std::size_t e = 0; e < singles; ++e)
    if (effect_kind[e] == k) of.push_back(&effects[e]->region());
  double apart = 0;
  for (std::size_t i = 0; i < of.size(); ++i)
    for (std::size_t j = i + 1; j < of.size(); ++j)
      if (!RegionsOverlap(*of[i], *of[j])) apart += 1;
  return apart;
}

HeldOutCheck CheckOnHeldOutModes(
    const EffectRanking& ranking, const std::shared_ptr<const Structure>& structure,
    const std::vector<std::shared_ptr<const ModelEffect>>& effects,
    const std::vector<ModalData>& states, const std::vector<std::vector<char>>& held,
    const EigenSensitivityOptions& fit, const NonlinearSolver& solver, bool ritz) {
  HeldOutCheck check;
  const RankedClass* target = GapClass(ranking);
  const RankedClass* none = NoneClass(ranking);
  if (target == nullptr || none == nullptr) {
    check.why = "no effect to check";
    return check;
  }
  check.kind = target->kind;
  check.region = target->region;
  const auto effect = std::find_if(effects.begin(), effects.end(), [&](const auto& e) {
    return e->kind() == target->kind && e->region().name == target->region;
  });
  if (effect == effects.end()) {
    check.why = "the class's place is not among those fitted";
    return check;
  }
  auto is_held = [&](const PairedModeMisfit& m) {
    return held[static_cast<std::size_t>(m.state)][static_cast<std::size_t>(m.mode)] != 0;
  };
  for (const PairedModeMisfit& m : none->modes)
    if (is_held(m)) check.nominal.push_back(m);
  // The states without the held-out modes (a state left without a mode is
  // dropped).
  std::vector<ModalData> kept;
  for (std::size_t i = 0; i < states.size(); ++i) {
    std::vector<int> keep;
    for (int j = 0; j < states[i].num_modes(); ++j)
      if (!held[i][static_cast<std::size_t>(j)]) keep.push_back(j);
    if (keep.empty()) continue;
    ModalData d = states[i];
    d.frequencies_hz = states[i].frequencies_hz(keep);
    if (d.HasShapes()) d.shapes = states[i].shapes(Eigen::all, keep);
    kept.push_back(std::move(d));
  }
  const Fit f = FitInstance(structure, *effect, kept, fit, solver, ritz);
  if (!f.ok) {
    check.why = "the fit without the held-out modes failed";
    return check;
  }
  check.theta = f.theta;
  // Its predictions of every measured mode, paired as the ranking's fits are.
  const NonlinearProblem all =
      BuildModelEffectFitProblem(structure, {*effect}, states, fit, f.theta);
  Eigen::VectorXd r;
  if (!all.evaluate(f.theta, &r, nullptr, &check.why)) return check;
  for (const PairedModeMisfit& m : PairedModeMisfits(states, fit, r))
    if (is_held(m)) check.refit.push_back(m);
  check.ok = true;
  return check;
}

}  // namespace femup::effect_ranking_steps
