#include "femup/studies/noise_study.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <iomanip>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "femup/core/counter_rng.h"
#include "femup/core/errors.h"
#include "femup/core/linalg/modal.h"
#include "femup/core/parallel.h"
#include "femup/problems/correction_system.h"
#include "femup/problems/noise.h"
#include "femup/studies/factor_solve.h"

namespace femup {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

RmStatistics Summarise(std::vector<double> v) {
  RmStatistics s;
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return !std::isfinite(x); }),
          v.end());
  if (v.empty()) return {kNaN, kNaN, kNaN, kNaN};
  double sum = 0;
  for (double x : v) sum += x;
  s.mean = sum / v.size();
  double ss = 0;
  for (double x : v) ss += (x - s.mean) * (x - s.mean);
  s.std_dev = v.size() > 1 ? std::sqrt(ss / (v.size() - 1)) : 0.0;
  // Linear interpolation between the order statistics around q (n - 1):
  // selection, not a full sort.
  auto quantile = [&](double q) {
    const double pos = q * (v.size() - 1);
    const std::size_t lo = static_cast<std::size_t>(std::floor(pos));
    std::nth_element(v.begin(), v.begin() + lo, v.end());
    const double low = v[lo];
    const double high =
        lo + 1 < v.size() ? *std::min_element(v.begin() + lo + 1, v.end()) : low;
    return low + (pos - lo) * (high - low);
  };
  s.median = quantile(0.5);
  s.p90 = quantile(0.9);
  return s;
}

}  // namespace

Invalid NoiseRunOptions::Validate() const {
  if (threads < 1)
    return {"threads", "expected at least 1, got " + std::to_string(threads)};
  return {};
}

NoiseStudyResult RunNoiseStudy(const Study& study, const NoiseRunOptions& options) {
  ThrowIfInvalid(options.Validate(), "noise");
  if (!study.noise_study) {
    throw InputError(study.path, "noise_study: the study has no noise_study section");
  }
  if (!study.truth)
    throw InputError(study.path, "truth: a noise study needs preset factors");
  const NoiseStudySpec& spec = *study.noise_study;
  if (spec.levels.empty())
    throw InputError(study.path, "noise_study.levels: expected at least one level");
  if (spec.draws < 1 || spec.draws > std::numeric_limits<int>::max() /
                                         static_cast<int>(spec.levels.size())) {
    throw InputError(study.path, "noise_study.draws: expected between 1 and " +
                                     std::to_string(std::numeric_limits<int>::max() /
                                                    spec.levels.size()) +
                                     " draws per level");
  }
  NoiseStudyResult r;
  r.study_name = study.name;
  r.spec = spec;
  r.parameter_names = study.model.ParameterNames();
  r.preset = *study.truth;
  r.added_mass_indices = study.model.ParametersOfKind(ParameterKind::kAddedMass);
  if (r.added_mass_indices.empty()) {
    throw InputError(study.path,
                     "noise_study: the model has no added-mass factor to score");
  }
  for (int k : r.added_mass_indices) {
    if (r.preset[k] == 0) {
      throw InputError(study.path, "truth." + r.parameter_names[k] +
                                       ": Rm divides by the preset added-mass factor; it "
                                       "must not be 0");
    }
  }

  const Modes fem = FemModesFor(study);
  const std::vector<ModalData> clean = MeasuredStates(study);
  const std::vector<SolverSpec> variants =
      spec.compare.empty() ? std::vector<SolverSpec>{study.solver} : spec.compare;
  // Only the factors and whether they are usable are scored: no row labels,
  // identifiability analysis or covariance per draw, and what does not change
  // between draws is prepared once per solver.
  std::vector<std::unique_ptr<PreparedFactorSolve>> prepared;
  for (const SolverSpec& v : variants)
    prepared.push_back(std::make_unique<PreparedFactorSolve>(study, v, fem));
  r.comparison.resize(variants.size());
  for (std::size_t v = 0; v < variants.size(); ++v)
    r.comparison[v].label = variants[v].label;

  // The level shown in the estimated-vs-preset figure: the nearest one.
  std::size_t figure_index = 0;
  for (std::size_t l = 0; l < spec.levels.size(); ++l) {
    if (std::abs(spec.levels[l] - spec.figure_level) <
        std::abs(spec.levels[figure_index] - spec.figure_level)) {
      figure_index = l;
    }
  }
  r.figure_level = spec.levels[figure_index];
  const int np = study.model.num_parameters();
  Eigen::MatrixXd figure_estimates(np, spec.draws);
  const std::size_t num_levels = spec.levels.size();
  std::vector<NoiseModel> noise(num_levels);
  for (std::size_t l = 0; l < num_levels; ++l) {
    noise[l].level = spec.levels[l];
    noise[l].shape_level = spec.levels[l] * spec.shape_level_ratio;
    noise[l].shape_scale = spec.shape_noise == "peak" ? NoiseModel::ShapeScale::kPeak
                                                      : NoiseModel::ShapeScale::kEntry;
    noise[l].distribution = spec.distribution;
  }

  // Every (level, draw) is solved into its own slot, in parallel; the slots are
  // then reduced in level and draw order, so nothing depends on the threads.
  // A slot keeps only what the statistics read (Rm of each added-mass factor;
  // the whole estimate at the figure level): large fresh arrays cost page
  // faults, which on a virtual machine are a large part of a short study.
  const int draws = spec.draws;
  const int total = static_cast<int>(num_levels) * draws;
  const std::size_t nv = variants.size();
  const std::size_t na = r.added_mass_indices.size();
  // Per variant and level: Rm (%) of every added-mass factor (rows) in every
  // draw (columns); NaN when, and only when, the draw is not usable.
  std::vector<std::vector<Eigen::MatrixXd>> rm_draws(
      nv, std::vector<Eigen::MatrixXd>(num_levels));
  for (auto& by_level : rm_draws) {
    for (Eigen::MatrixXd& m : by_level) m.resize(static_cast<Eigen::Index>(na), draws);
  }
  // Draws go to the workers in chunks of a level (fewer hand-outs, and no two
  // threads writing next to each other on every draw).
  constexpr int kChunk = 32;
  const int chunks_per_level = (draws + kChunk - 1) / kChunk;
  const int chunks = static_cast<int>(num_levels) * chunks_per_level;
  // Work space per worker thread: the corrupted modes, each solver's scratch
  // and estimate, and its solve time.
  struct WorkerSpace {
    std::vector<ModalData> noisy;
    std::vector<PreparedFactorSolve::Workspace> solvers;
    Eigen::VectorXd x;
    std::vector<double> seconds;  // per variant
  };
  std::vector<WorkerSpace> work(
      static_cast<std::size_t>(ParallelWorkers(chunks, options.threads)));
  for (WorkerSpace& w : work) {
    w.noisy = clean;
    w.solvers.resize(nv);
    w.x.resize(np);
    w.seconds.assign(nv, 0.0);
  }
  std::atomic<int> drawn{0};
  ParallelForWorkers(chunks, options.threads, [&](int chunk, int worker) {
    const std::size_t l = static_cast<std::size_t>(chunk / chunks_per_level);
    const int first = (chunk % chunks_per_level) * kChunk;
    const int last = std::min(draws, first + kChunk);
    WorkerSpace& w = work[static_cast<std::size_t>(worker)];
    for (int draw = first; draw < last; ++draw) {
      CounterRng rng(static_cast<std::uint64_t>(spec.seed), l,
                     static_cast<std::uint64_t>(draw));
      for (std::size_t s = 0; s < clean.size(); ++s)
        Corrupt(clean[s], noise[l], &rng, &w.noisy[s]);
      for (std::size_t v = 0; v < nv; ++v) {
        const PreparedFactorSolve::Outcome solved =
            prepared[v]->Solve(w.noisy, &w.solvers[v], w.x);
        w.seconds[v] += solved.seconds;
        for (std::size_t k = 0; k < na; ++k) {
          const int i = r.added_mass_indices[k];
          rm_draws[v][l](static_cast<Eigen::Index>(k), draw) =
              solved.usable
                  ? std::abs(w.x[i] - r.preset[i]) / std::abs(r.preset[i]) * 100.0
                  : kNaN;
        }
        if (v == 0 && l == figure_index) {
          if (solved.usable) {
            figure_estimates.col(draw) = w.x;
          } else {
            figure_estimates.col(draw).setConstant(kNaN);
          }
        }
      }
    }
    if (options.progress) options.progress(drawn += last - first, total);
  });
  for (const WorkerSpace& w : work) {
    for (std::size_t v = 0; v < nv; ++v) r.comparison[v].seconds += w.seconds[v];
  }

  for (std::size_t l = 0; l < num_levels; ++l) {
    std::vector<std::vector<double>> rm(na);
    std::vector<std::vector<double>> draw_average(variants.size());
    std::vector<int> usable_by(variants.size(), 0);
    int usable = 0;
    for (int draw = 0; draw < draws; ++draw) {
      for (std::size_t v = 0; v < variants.size(); ++v) {
        const bool ok = std::isfinite(rm_draws[v][l](0, draw));
        usable_by[v] += ok ? 1 : 0;
        double sum = 0;
        for (std::size_t k = 0; k < na; ++k) {
          const double e = rm_draws[v][l](static_cast<Eigen::Index>(k), draw);
          sum += e;
          if (v == 0) rm[k].push_back(e);
        }
        draw_average[v].push_back(sum / na);
        if (v == 0) usable += ok ? 1 : 0;
      }
    }
    for (std::size_t v = 0; v < variants.size(); ++v) {
      const RmStatistics st = Summarise(draw_average[v]);
      r.comparison[v].rm_average.push_back(st.mean);
      r.comparison[v].rm_median.push_back(st.median);
      r.comparison[v].usable_draws.push_back(usable_by[v]);
    }
    std::vector<RmStatistics> stats;
    double average = 0;
    for (const auto& v : rm) {
      stats.push_back(Summarise(v));
      average += stats.back().mean;
    }
    r.rm.push_back(stats);
    r.rm_average.push_back(average / rm.size());
    r.usable_draws.push_back(usable);
  }
  r.figure_mean.resize(np);
  r.figure_std.resize(np);
  for (int i = 0; i < np; ++i) {
    std::vector<double> row(spec.draws);
    for (int d = 0; d < spec.draws; ++d) row[d] = figure_estimates(i, d);
    const RmStatistics s = Summarise(row);
    r.figure_mean[i] = s.mean;
    r.figure_std[i] = s.std_dev;
  }
  r.figure_first_draw = figure_estimates.col(0);
  return r;
}

}  // namespace femup
