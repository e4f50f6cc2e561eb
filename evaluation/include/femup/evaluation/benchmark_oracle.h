// The blind benchmark's Bayes oracle: for a case of the single-effect suite,
// the posterior probability of each class (none, or one effect of each kind)
// under the generator's own prior and truth model: its 60-element mesh, its
// effects' exact forms (a mass with rotary inertia between nodes, damage of
// its width, springs in rotation and translation, ...), the ranges it draws
// their properties from, the way it sets their sizes, and its noise model.
//
// No diagnosis can beat the classifier that picks this posterior's most
// probable class (it is the Bayes-optimal decision for the generator's
// distribution); what it gets wrong is lost to every method, whatever its
// families and priors. So the oracle's accuracy bounds what the benchmark's
// top-1 target can demand. It reads only what `femup diagnose` reads: the case's
// study file (model, measured modes, stated noise), plus the generator's
// settings (BenchmarkOptions: suite, sizes, meshes), never the truth file.
//
// The evidence of each class is the integral of the likelihood over the
// generator's prior, split into sub-classes where the generator makes a
// discrete choice (fade or not, springs in rotation and translation or rotation
// only, the sign of an E error, an effect at the noise level or above it),
// each integrated by importance sampling over the unit cube of the
// generator's uniform draws (sampled_evidence.h). An effect's strength for a
// drawn size comes from the same calibration as the generator's, solved on the
// bending matrices, which are affine in the strength (in 1 / strength for
// the support springs), with the banded eigensolver (banded_eigen.h).
//
// Likelihood (the generator's noise): frequency f_meas = f (1 + sigma_f n),
// shape entries (largest entry of the truth's shape scaled to 1) plus
// sigma_s n, n standard normal; the sign of each shape is unknown (equal
// weights on both).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "femup/core/invalid.h"
#include "femup/evaluation/blind_benchmark.h"
#include "femup/studies/study.h"

namespace femup {

struct OracleOptions {
  int samples = 1000;  // importance-sampling draws per sub-class, >= 50
  std::uint64_t seed = 20261125;
  // The effect kinds whose classes are integrated (with "none" always); empty:
  // all five. With fewer, the probabilities are those of the classes given,
  // their priors renormalised.
  std::vector<std::string> kinds;
  Invalid Validate() const;  // ok, or the field and what is wrong
};

struct OracleClass {
  std::string label;  // "none" or a kind
  double prior = 0;
  // log p(data | class), the constants common to every class left out.
  double log_evidence = 0;
  // Its standard error from the importance sampling (delta method; 0 for
  // "none", which has no parameters).
  double log_standard_error = 0;
  // Kish's effective number of draws of the sub-class that carries most of
  // the class's evidence.
  double effective_samples = 0;
  double probability = 0;
};

struct OracleResult {
  std::vector<OracleClass> classes;  // most probable first
  int evaluations = 0;               // truth-model evaluations
  // The largest relative difference between an eigenvalue of the affine
  // strength model and of the model assembled directly at the same strength
  // (checked once per sub-class): the affine shortcut's own check.
  double affine_error = 0;
  double seconds = 0;
};

// The posterior over the generator's classes for one case. Throws InputError
// for invalid options, a suite other than "single" (the mixed suite's pairs
// are not modelled), or a study that is not a benchmark case of `generator`
// (not a cantilever with generator.diagnosis_elements elements, one measured
// state, no stated noise, sensors off the ux DOFs).
OracleResult BayesOracle(const Study& study, const BenchmarkOptions& generator,
                         const OracleOptions& options = {});

}  // namespace femup
