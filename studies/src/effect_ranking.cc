#include "femup/studies/effect_ranking.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>
#include <memory>
#include <numeric>
#include <optional>

#include "effect_ranking_steps.h"
#include "femup/core/errors.h"
#include "femup/core/parallel.h"
#include "femup/problems/effect_priors.h"
#include "femup/problems/model_effect_pair.h"
#include "femup/problems/model_effect_pencil.h"
#include "femup/solvers/nonlinear_solver.h"
#include "model_form_error.h"
#include "observational_equivalence.h"

namespace femup {

using effect_ranking_steps::CheckOnHeldOutModes;
using effect_ranking_steps::Families;
using effect_ranking_steps::Fit;
using effect_ranking_steps::FitInstance;
using effect_ranking_steps::FitOptions;
using effect_ranking_steps::HeldOutModes;
using effect_ranking_steps::NoiseTemperatures;
using effect_ranking_steps::NoiseTemperaturesOf;
using effect_ranking_steps::Nominal;
using effect_ranking_steps::NominalResidual;
using effect_ranking_steps::PlacesApart;
using effect_ranking_steps::Probabilities;
using effect_ranking_steps::PutInOrder;
using effect_ranking_steps::Screen;
using effect_ranking_steps::ScreenInstance;
using effect_ranking_steps::TriedFamilies;

std::string ToString(EffectRankingOptions::FrequencyTemperature t) {
  switch (t) {
    case EffectRankingOptions::FrequencyTemperature::kMarginal:
      return "marginal";
    case EffectRankingOptions::FrequencyTemperature::kThreshold:
      return "threshold";
    case EffectRankingOptions::FrequencyTemperature::kAuto:
      break;
  }
  return "auto";
}

std::optional<EffectRankingOptions::FrequencyTemperature> FrequencyTemperatureNamed(
    const std::string& name) {
  if (name == "auto") return EffectRankingOptions::FrequencyTemperature::kAuto;
  if (name == "threshold") return EffectRankingOptions::FrequencyTemperature::kThreshold;
  if (name == "marginal") return EffectRankingOptions::FrequencyTemperature::kMarginal;
  return std::nullopt;
}

Invalid EffectRankingOptions::Validate() const {
  if (!(frequency_sigma > 0) || !std::isfinite(frequency_sigma))
    return {"frequency_sigma", "must be positive and finite"};
  if (!(shape_sigma > 0) || !std::isfinite(shape_sigma))
    return {"shape_sigma", "must be positive and finite"};
  if (threads < 0) return {"threads", "must be >= 0 (0: every core)"};
  if (max_members < -1) return {"max_members", "must be >= 0, or -1 for every member"};
  if (members_fitted < -1)
    return {"members_fitted", "must be >= 0, or -1 to fit every member"};
  if (bagging_copies < 0)
    return {"bagging_copies", "must be >= 0 (0: the Laplace posterior alone)"};
  if (max_effects < 1 || max_effects > 2)
    return {"max_effects", "expected 1 (single effects) or 2 (also pairs)"};
  if (pair_places < 2 && pair_places != -1)
    return {"pair_places", "expected at least 2, or -1 (every place)"};
  if (!(stiffness_uncertainty >= 0 && stiffness_uncertainty < 0.5))
    return {"stiffness_uncertainty",
            "a relative standard deviation: expected 0 <= value < 0.5"};
  if (!(mass_uncertainty >= 0 && mass_uncertainty < 0.5))
    return {"mass_uncertainty",
            "a relative standard deviation: expected 0 <= value < 0.5"};
  if (!(gap_confidence >= 0 && gap_confidence < 1))
    return {"gap_confidence", "must be in [0, 1) (0: the most probable family)"};
  if (!(gap_explained >= 0 && gap_explained < 1))
    return {
        "gap_explained",
        "must be in [0, 1) (0: the most probable family, however little it explains)"};
  const auto names = AvailableNonlinearSolvers();
  if (std::find(names.begin(), names.end(), solver) == names.end())
    return {"solver", "unknown nonlinear solver '" + solver + "'"};
  return priors.Validate();
}

EffectRanking RankModelEffects(const Structure& structure_in,
                               const std::vector<ModalData>& states,
                               const EffectRankingOptions& options) {
  ThrowIfInvalid(options.Validate(), "diagnosis");
  const std::vector<std::vector<char>> held = HeldOutModes(states, options.held_out);
  auto structure = std::make_shared<const Structure>(structure_in);
  const bool any_wet = std::any_of(states.begin(), states.end(), [](const ModalData& d) {
    return d.immersion == Immersion::kWet;
  });
  ModelEffectOptions effect_options;
  effect_options.wet_only_added_mass = any_wet;

  EffectRanking out;
  Families tried = TriedFamilies(*structure, options, effect_options, &out);
  const std::vector<std::string>& kinds = tried.kinds;
  std::vector<std::vector<std::unique_ptr<ModelEffect>>>& instances = tried.instances;

  const EigenSensitivityOptions fit = FitOptions(*structure, options);
  // The fits stop when the misfit changes by less than 1e-10 of itself: the
  // eigen-solver's tolerance (1e-10) puts a noise of about 1e-12 of the misfit
  // on every evaluation, so the solvers' default 1e-14 was never met and a
  // converged fit went on with some 15 rejected steps, each a full evaluation,
  // until its step fell below 1e-14 (docs/diagnosis.md, the 10^4-DOF jacket).
  // A change of 1e-10 of a misfit of 1e3 is 1e-7 of a chi2 unit.
  NonlinearSolverOptions solver_options;
  solver_options.function_tolerance = 1e-10;
  solver_options.verbose = std::getenv("FEMUP_VERBOSE_FITS") != nullptr;
  const auto solver = CreateNonlinearSolver(options.solver, solver_options);
  const bool ritz =
      options.ritz_min_dofs >= 0 &&
      structure->dof_labels.size() >= static_cast<std::size_t>(options.ritz_min_dofs);

  int shape_modes = 0;
  for (const ModalData& d : states)
    shape_modes += options.use_shapes && d.HasShapes() ? d.num_modes() : 0;
  // Each family's share of the prior: its weight over the sum of "none"'s and
  // every tried family's (1 each unless stated: 1 / (families + 1)). With
  // pairs (max_effects 2) the shares are set once the pairs are known, below.
  double total_weight = options.priors.Weight("none");
  for (const std::string& kind : kinds) total_weight += options.priors.Weight(kind);
  auto log_family_prior = [&](const std::string& kind) {
    return std::log(options.priors.Weight(kind)) - std::log(total_weight);
  };
  // The classes' kinds (the families, then any pairs), each one's log share of
  // the prior, and among how many places it is split.
  std::vector<std::string> class_kinds = kinds;
  std::vector<double> log_share, places;
  for (std::size_t k = 0; k < kinds.size(); ++k) {
    log_share.push_back(log_family_prior(kinds[k]));
    places.push_back(static_cast<double>(instances[k].size()));
  }

  // "none", then every instance of every family.
  RankedClass none;
  none.kind = "none";
  const Nominal nominal_fit = NominalResidual(*structure, states, fit);
  const Eigen::VectorXd& nominal = nominal_fit.residual;
  const std::vector<char>& is_frequency = nominal_fit.is_frequency;
  out.num_residuals = static_cast<int>(nominal.size());
  none.chi2 = nominal.squaredNorm();
  none.log_prior = log_family_prior("none");
  // Every instance's fit, in parallel (each writes its own slot), then the
  // classes in the families' and instances' order.
  std::vector<std::shared_ptr<const ModelEffect>> effects;
  std::vector<std::size_t> effect_kind;
  for (std::size_t k = 0; k < kinds.size(); ++k) {
    for (auto& instance : instances[k]) {
      effects.emplace_back(std::move(instance));
      effect_kind.push_back(k);
    }
  }
  // Members screened (EffectRankingOptions::members_fitted): the rest are
  // not fitted; their evidence is the Laplace one at the end of their screen's
  // linearised step, so the family keeps the weight of every member it has.
  std::vector<Fit> fits(effects.size());
  std::vector<int> to_fit(effects.size());
  std::iota(to_fit.begin(), to_fit.end(), 0);
  std::vector<int> members;
  for (std::size_t e = 0; e < effects.size(); ++e)
    if (effects[e]->region().member >= 0) members.push_back(static_cast<int>(e));
  int screened = 0, screened_parts = 0;  // places screened, of which parts
  if (options.members_fitted >= 0 &&
      static_cast<int>(members.size()) > options.members_fitted) {
    std::vector<Screen> screens(members.size());
    ParallelFor(static_cast<int>(members.size()), options.threads, [&](int i) {
      const auto m = static_cast<std::size_t>(i);
      screens[m] = ScreenInstance(
          structure, effects[static_cast<std::size_t>(members[m])], states, fit);
    });
    std::vector<std::size_t> order(members.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return screens[a].misfit < screens[b].misfit;
    });
    std::vector<char> dropped(effects.size(), 0);
    for (std::size_t k = static_cast<std::size_t>(options.members_fitted);
         k < order.size(); ++k) {
      const auto e = static_cast<std::size_t>(members[order[k]]);
      dropped[e] = 1;
      fits[e] = screens[order[k]].fit;
    }
    to_fit.clear();
    for (std::size_t e = 0; e < effects.size(); ++e)
      if (!dropped[e]) to_fit.push_back(static_cast<int>(e));
    screened = static_cast<int>(members.size());
    screened_parts =
        static_cast<int>(std::count_if(members.begin(), members.end(), [&](int e) {
          return effects[static_cast<std::size_t>(e)]->region().part >= 0;
        }));
  }
  ParallelFor(static_cast<int>(to_fit.size()), options.threads, [&](int i) {
    const auto e = static_cast<std::size_t>(to_fit[static_cast<std::size_t>(i)]);
    fits[e] = FitInstance(structure, effects[e], states, fit, *solver, ritz);
  });

  // Pairs of effects (max_effects 2): the best-fitting place of each of two
  // families; and of one family, every two of its pair_places best-fitting
  // places that lie apart (regions sharing no element or DOF). Each is fitted
  // from where its two places' fits ended.
  if (options.max_effects >= 2) {
    const std::size_t pair_places = options.pair_places < 0
                                        ? effects.size()
                                        : static_cast<std::size_t>(options.pair_places);
    // Kind k's fitted instances, the least chi2 first.
    const auto ranked = [&](std::size_t k) {
      std::vector<int> r;
      for (std::size_t e = 0; e < effects.size(); ++e)
        if (effect_kind[e] == k && fits[e].ok && fits[e].fitted)
          r.push_back(static_cast<int>(e));
      std::stable_sort(r.begin(), r.end(), [&](int a, int b) {
        return fits[static_cast<std::size_t>(a)].chi2 <
               fits[static_cast<std::size_t>(b)].chi2;
      });
      return r;
    };
    std::vector<std::vector<int>> by_fit(kinds.size());
    for (std::size_t k = 0; k < kinds.size(); ++k) by_fit[k] = ranked(k);
    const std::size_t singles = effects.size();
    int num_pairs = 0;  // pairs of families (one family twice included)
    std::vector<std::vector<std::string>> pair_families;
    for (std::size_t k1 = 0; k1 < kinds.size(); ++k1) {
      for (std::size_t k2 = k1; k2 < kinds.size(); ++k2) {
        std::vector<std::pair<int, int>> combos;
        if (k1 != k2 && !by_fit[k1].empty() && !by_fit[k2].empty()) {
          combos.emplace_back(by_fit[k1][0], by_fit[k2][0]);
        } else if (k1 == k2) {
          const std::size_t n = std::min(pair_places, by_fit[k1].size());
          for (std::size_t i = 0; i < n; ++i) {
            for (std::size_t j = i + 1; j < n; ++j) {
              const int a = by_fit[k1][i], b = by_fit[k1][j];
              if (!RegionsOverlap(effects[static_cast<std::size_t>(a)]->region(),
                                  effects[static_cast<std::size_t>(b)]->region()))
                combos.emplace_back(a, b);
            }
          }
        }
        if (combos.empty()) continue;
        ++num_pairs;
        const std::size_t class_index = class_kinds.size();
        for (const auto& [b1, b2] : combos) {
          const Fit& f1 = fits[static_cast<std::size_t>(b1)];
          const Fit& f2 = fits[static_cast<std::size_t>(b2)];
          Eigen::VectorXd from(f1.theta.size() + f2.theta.size());
          from << f1.theta, f2.theta;
          effects.emplace_back(PairOfModelEffects(effects[static_cast<std::size_t>(b1)],
                                                  effects[static_cast<std::size_t>(b2)],
                                                  {from}));
          effect_kind.push_back(class_index);
        }
        class_kinds.push_back(effects.back()->kind());
        pair_families.push_back({kinds[k1], kinds[k2]});
        log_share.push_back(0);  // set below, once the pairs are counted
        // Among how many combinations of places its share is split: every
        // place of one family with every place of the other; of one family,
        // every two of its places that lie apart (a member and its own parts
        // never form a pair, so they take no share).
        places.push_back(
            k1 == k2 ? std::max(1.0, PlacesApart(effects, effect_kind, singles, k1))
                     : places[k1] * places[k2]);
      }
    }
    // One third each on none, one effect and two (two levels where no pair
    // could be formed), equal within a level, times the stated weights.
    for (std::size_t k = 0; k < class_kinds.size(); ++k) {
      const std::vector<std::string> families = k < kinds.size()
                                                    ? std::vector<std::string>{kinds[k]}
                                                    : pair_families[k - kinds.size()];
      log_share[k] = std::log(LevelPrior(options.priors, families, kinds.size(),
                                         static_cast<std::size_t>(num_pairs)));
    }
    none.log_prior = std::log(LevelPrior(options.priors, {}, kinds.size(),
                                         static_cast<std::size_t>(num_pairs)));
    fits.resize(effects.size());
    ParallelFor(static_cast<int>(effects.size() - singles), options.threads, [&](int i) {
      const std::size_t e = singles + static_cast<std::size_t>(i);
      fits[e] = FitInstance(structure, effects[e], states, fit, *solver, ritz);
    });
  }

  // The model's own form error (Structure::form_variants, model_form_error.h):
  // the noise of the frequencies (and of the shapes, form_error_on_shapes)
  // becomes I + sum_j u_j u_j', one standard deviation of model-form error
  // along each variant's change u_j, and every class's residuals and Jacobian
  // rows are whitened by it. A change the
  // model's own formulation can make (all modes softer alike, for shear
  // deformation) then costs little, and no family is named for it alone.
  // What the user states of the model's overall stiffness and mass joins them
  // as variants of its own (StatedUncertaintyVariants), with or without the
  // builder's.
  std::vector<FormVariant> variants;
  if (options.formulation_error) variants = structure->form_variants;
  // The temperature's use, kAuto resolved by whether the structure's own form
  // variants are allowed for (not the stated uncertainty's).
  out.frequency_temperature = options.frequency_temperature;
  if (out.frequency_temperature == EffectRankingOptions::FrequencyTemperature::kAuto) {
    out.frequency_temperature =
        variants.empty() ? EffectRankingOptions::FrequencyTemperature::kMarginal
                         : EffectRankingOptions::FrequencyTemperature::kThreshold;
  }
  for (FormVariant& v : StatedUncertaintyVariants(
           *structure, options.stiffness_uncertainty, options.mass_uncertainty))
    variants.push_back(std::move(v));
  const ModelFormError form = ModelFormError::Measure(
      *structure, variants, states, fit, is_frequency, options.form_error_on_shapes,
      options.frequency_sigma, &out.form_errors);
  const bool whitened = form.Active();
  // Each fitted class's fit to the whitened misfit's mode (form_fit), kept per
  // instance, and done again only where the instance's raw fit changed (a
  // refit round).
  std::vector<std::optional<WhitenedModeFit>> in_form(effects.size());

  // The classes and their probabilities, from the fits. Screened places whose
  // linearised step comes out more probable than every fitted place of their
  // family are then fitted (the most probable first, members_fitted of them
  // per round, up to kRefitRounds rounds) and everything is ranked again: a
  // step's prediction is a lower bound of the misfit only to first order, and
  // on a jacket it was optimistic for a hundred places or more at once.
  constexpr int kRefitRounds = 2;
  const bool step_in_form = options.form_step;
  const bool fit_in_form_to_mode = step_in_form && options.form_fit;
  int refitted = 0;
  std::vector<RankedClass> classes;
  std::vector<Eigen::MatrixXd> jacobians, raw_jacobians;
  std::vector<Eigen::VectorXd> residuals;
  // Each class's data residuals at the fit it is reported at, unwhitened: what
  // it predicts, mode by mode (RankedClass::modes).
  std::vector<Eigen::VectorXd> raw_residuals;
  std::map<std::string, double> by_kind;
  Eigen::VectorXd row_scale;  // 1 / sqrt(noise temperature) per residual
  for (int round = 0;; ++round) {
    classes = {none};
    jacobians = {Eigen::MatrixXd(out.num_residuals, 0)};
    residuals = {nominal};
    std::vector<std::size_t> class_effect = {effects.size()};  // none: no effect
    std::vector<ClassPriors> priors = {{}};  // box and local normal priors
    for (std::size_t e = 0; e < effects.size(); ++e) {
      const std::size_t k = effect_kind[e];
      const std::string& kind = class_kinds[k];
      const double log_prior = log_share[k] - std::log(places[k]);
      const std::shared_ptr<const ModelEffect>& effect = effects[e];
      const Fit& f = fits[e];
      if (!f.ok) continue;
      RankedClass c;
      c.kind = kind;
      c.region = effect->region().name;
      for (const EffectParameter& p : effect->Parameters()) c.names.push_back(p.name);
      c.theta = f.theta;
      c.chi2 = f.chi2;
      c.log_prior = log_prior;
      c.converged = f.converged;
      c.fitted = f.fitted;
      c.location = effect->Location(f.theta);
      c.magnitudes = effect->Magnitudes(f.theta);
      ClassPriors cp;
      cp.lower.resize(static_cast<Eigen::Index>(c.names.size()));
      cp.upper.resize(static_cast<Eigen::Index>(c.names.size()));
      const auto params = effect->Parameters();
      for (std::size_t i = 0; i < params.size(); ++i) {
        cp.lower[static_cast<Eigen::Index>(i)] = params[i].lower;
        cp.upper[static_cast<Eigen::Index>(i)] = params[i].upper;
      }
      LocalNormalPriors(params, f.theta, &cp.mean, &cp.sigma);
      classes.push_back(std::move(c));
      jacobians.push_back(f.jacobian);
      residuals.push_back(f.residual);
      priors.push_back(std::move(cp));
      class_effect.push_back(e);
    }
    raw_jacobians = jacobians;
    raw_residuals = residuals;
    if (whitened) {
      // The fitted classes' whitened fits, in parallel, where not yet done
      // from the same raw fit.
      std::vector<std::size_t> to_move;
      for (std::size_t i = 1; i < classes.size(); ++i) {
        if (!fit_in_form_to_mode || !classes[i].fitted || classes[i].theta.size() == 0)
          continue;
        const std::optional<WhitenedModeFit>& done = in_form[class_effect[i]];
        if (!done || done->from != classes[i].theta) to_move.push_back(i);
      }
      std::vector<double> from_misfit(to_move.size());
      for (std::size_t k = 0; k < to_move.size(); ++k) {
        const std::size_t i = to_move[k];
        Eigen::VectorXd r = residuals[i];
        form.Whiten(&r, nullptr);
        from_misfit[k] = r.squaredNorm() + priors[i].Misfit(classes[i].theta);
      }
      ParallelFor(static_cast<int>(to_move.size()), options.threads, [&](int k) {
        const std::size_t i = to_move[static_cast<std::size_t>(k)];
        const std::size_t e = class_effect[i];
        in_form[e] =
            FitToWhitenedMode(form, structure, effects[e], states, fit, *solver,
                              classes[i].theta, from_misfit[static_cast<std::size_t>(k)]);
      });
      for (std::size_t i = 0; i < classes.size(); ++i) {
        const Eigen::VectorXd raw = residuals[i];
        form.Whiten(&residuals[i], &jacobians[i]);
        const Eigen::MatrixXd& j = jacobians[i];
        if (j.cols() == 0 || !step_in_form) continue;
        RankedClass& c = classes[i];
        const ModelEffect& effect = *effects[class_effect[i]];
        if (fit_in_form_to_mode && c.fitted) {
          const std::optional<WhitenedModeFit>& moved = in_form[class_effect[i]];
          if (!moved || !moved->ok) continue;
          residuals[i] = moved->residual;
          raw_residuals[i] = moved->raw_residual;
          jacobians[i] = moved->jacobian;
          raw_jacobians[i] = moved->raw_jacobian;
          c.chi2 = moved->raw_residual.squaredNorm();
          c.theta = moved->theta;
          c.location = effect.Location(c.theta);
          c.magnitudes = effect.Magnitudes(c.theta);
          LocalNormalPriors(effect.Parameters(), c.theta, &priors[i].mean,
                            &priors[i].sigma);
          continue;
        }
        // One Gauss-Newton step on the whitened misfit (the stated normal
        // priors' rows with it), kept in range (every class without
        // form_fit; a screened one, one linearised step's end, with it).
        const std::optional<Eigen::VectorXd> to =
            GaussNewtonStepInForm(c.theta, residuals[i], j, priors[i]);
        if (!to) continue;
        const Eigen::VectorXd d = *to - c.theta;
        residuals[i] = residuals[i] + j * d;
        raw_residuals[i] = raw + raw_jacobians[i] * d;
        c.chi2 = raw_residuals[i].squaredNorm();
        c.theta = *to;
        c.location = effect.Location(c.theta);
        c.magnitudes = effect.Magnitudes(c.theta);
        LocalNormalPriors(effect.Parameters(), c.theta, &priors[i].mean,
                          &priors[i].sigma);
      }
    }

    // Noise temperatures from the best fit (NoiseTemperaturesOf). A screened
    // class's residual is a linear prediction, not a fit: not used.
    std::size_t best = 0;
    for (std::size_t i = 1; i < classes.size(); ++i)
      if (classes[i].fitted && residuals[i].squaredNorm() < residuals[best].squaredNorm())
        best = i;
    const NoiseTemperatures noise =
        NoiseTemperaturesOf(residuals[best], static_cast<int>(classes[best].theta.size()),
                            is_frequency, shape_modes);
    out.best_chi2_p_value = noise.best_chi2_p_value;
    const int num_frequencies = noise.num_frequencies;
    const double t_f = noise.frequency, t_s = noise.shape;
    out.temperature = t_f;
    out.shape_temperature = t_s;
    row_scale.resize(out.num_residuals);
    for (int r = 0; r < out.num_residuals; ++r)
      row_scale[r] = 1.0 / std::sqrt(is_frequency[r] ? t_f : t_s);

    const bool marginal = out.frequency_temperature ==
                              EffectRankingOptions::FrequencyTemperature::kMarginal &&
                          num_frequencies > 0;
    by_kind = Probabilities(residuals, jacobians, priors, is_frequency, noise, row_scale,
                            marginal, options.bagging_copies, &classes);
    out.bagging_copies = options.bagging_copies;

    if (round == kRefitRounds) break;
    std::map<std::string, double> most_fitted;
    for (const RankedClass& c : classes)
      if (c.fitted) most_fitted[c.kind] = std::max(most_fitted[c.kind], c.probability);
    std::vector<std::size_t> above;  // classes
    for (std::size_t i = 0; i < classes.size(); ++i)
      if (!classes[i].fitted && classes[i].probability > most_fitted[classes[i].kind])
        above.push_back(i);
    if (above.empty()) break;
    std::stable_sort(above.begin(), above.end(), [&](std::size_t a, std::size_t b) {
      return classes[a].probability > classes[b].probability;
    });
    above.resize(std::min(above.size(),
                          static_cast<std::size_t>(std::max(1, options.members_fitted))));
    ParallelFor(static_cast<int>(above.size()), options.threads, [&](int i) {
      const std::size_t e = class_effect[above[static_cast<std::size_t>(i)]];
      Fit f = FitInstance(structure, effects[e], states, fit, *solver, ritz);
      // A place none of whose starts can be fitted keeps its screen.
      if (f.ok) fits[e] = std::move(f);
    });
    refitted += static_cast<int>(above.size());
  }
  if (screened > 0) {
    std::string which;
    if (options.members_fitted > 0) {
      which = "the " + std::to_string(options.members_fitted) +
              " that one linearised step from their starts predicted to fit best";
    }
    if (refitted > 0) {
      which += (which.empty() ? "the " : ", and the ") + std::to_string(refitted) +
               " whose step came out more probable than every fitted place";
    }
    out.notes.push_back(
        "stiffness_loss was fitted on " +
        std::to_string(options.members_fitted + refitted) + " of its " +
        std::to_string(members.size()) + " places on single members (" +
        std::to_string(members.size() - static_cast<std::size_t>(screened_parts)) +
        " members and " + std::to_string(screened_parts) + " of their finite elements)" +
        (which.empty() ? std::string() : ": " + which) +
        " (the others' evidence is one linearised step's from their starts); set "
        "diagnosis.members_fitted to -1 to fit them all");
  }
  // What the data cannot tell apart (observational_equivalence.h): classes
  // that predict the data alike along the same directions, and classes that
  // change the data only as the model's own form error does (equivalent to
  // none).
  NameEquivalentClasses(residuals, jacobians, &classes);
  // How much of the nominal misfit beyond the noise each class removes, at the
  // stated noise, in the misfit the classes were ranked in: the raw one, or
  // where the model's form error is allowed for the whitened one (the form
  // error is not part of the gap to explain). Where none's misfit is within
  // the noise's expectation and the most probable class gains less than
  // kNoiseGain over it, there is no gap, and no class explains any of it. A
  // class that gains more has found a gap that sits in a few rows (a
  // frequency shifted by 5 sigma among a hundred shape entries) and hides in
  // the spread of the noise's chi2 (sqrt(2 n)): the gap's shares are then
  // not defined, and every class is taken to explain it.
  constexpr double kNoiseGain = 9;  // 3 noise standard deviations
  out.noise_misfit = static_cast<double>(out.num_residuals - shape_modes);
  out.nominal_misfit = residuals.front().squaredNorm();
  std::size_t top = 0;  // the most probable effect (none is class 0)
  for (std::size_t i = 1; i < classes.size(); ++i)
    if (top == 0 || classes[i].probability > classes[top].probability) top = i;
  out.gap_within_noise =
      !(out.nominal_misfit > out.noise_misfit) &&
      !(top > 0 && out.nominal_misfit - residuals[top].squaredNorm() >= kNoiseGain);
  const double gap_chi2 = out.nominal_misfit - out.noise_misfit;
  for (std::size_t i = 0; i < classes.size(); ++i) {
    classes[i].modes = PairedModeMisfits(states, fit, raw_residuals[i]);
    if (i == 0 || out.gap_within_noise) continue;  // none explains nothing
    const double left = residuals[i].squaredNorm() -
                        (out.noise_misfit - static_cast<double>(classes[i].theta.size()));
    classes[i].explained =
        gap_chi2 > 0 ? std::clamp(1 - std::max(0.0, left) / gap_chi2, 0.0, 1.0) : 1.0;
  }
  if (whitened) {
    const std::string note =
        NameFormErrorAlikeAsNone(form, residuals, raw_jacobians, row_scale, &classes);
    if (!note.empty()) out.notes.push_back(note);
  }
  PutInOrder(std::move(classes), by_kind, options, &out);
  if (!options.held_out.empty())
    out.held_out =
        CheckOnHeldOutModes(out, structure, effects, states, held, fit, *solver, ritz);
  return out;
}

const RankedClass* GapClass(const EffectRanking& ranking) {
  for (const RankedClass& c : ranking.classes)
    if (c.kind != "none")
      return ranking.classes.front().kind == "none" ? &c : &ranking.classes.front();
  return nullptr;
}

const RankedClass* NoneClass(const EffectRanking& ranking) {
  for (const RankedClass& c : ranking.classes)
    if (c.kind == "none") return &c;
  return nullptr;
}

std::vector<std::string> FamiliesOf(const std::string& kind) {
  const std::size_t plus = kind.find('+');
  if (plus == std::string::npos) return {kind};
  std::string first = kind.substr(0, plus), second = kind.substr(plus + 1);
  if (first == second) return {first};  // two places of one family
  return {first, second};
}

std::vector<std::pair<std::string, double>> FamilyPresence(const EffectRanking& ranking) {
  std::vector<std::pair<std::string, double>> presence;
  for (const auto& [kind, p] : ranking.kind_probabilities) {
    for (const std::string& family : FamiliesOf(kind)) {
      auto it = std::find_if(presence.begin(), presence.end(),
                             [&](const auto& e) { return e.first == family; });
      if (it == presence.end()) it = presence.insert(presence.end(), {family, 0.0});
      it->second += p;
    }
  }
  std::stable_sort(presence.begin(), presence.end(),
                   [](const auto& a, const auto& b) { return a.second > b.second; });
  return presence;
}

double KindProbability(const EffectRanking& ranking, const std::string& kind) {
  for (const auto& [name, p] : ranking.kind_probabilities)
    if (name == kind) return p;
  return 0;
}

double RmsFrequencyError(const RankedClass& c) {
  if (c.modes.empty()) return std::numeric_limits<double>::quiet_NaN();
  double sum = 0;
  for (const PairedModeMisfit& m : c.modes)
    sum += std::pow(m.model_hz / m.measured_hz - 1, 2);
  return std::sqrt(sum / static_cast<double>(c.modes.size()));
}

}  // namespace femup
