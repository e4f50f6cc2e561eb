// Measurement noise for simulated studies. The paper's corruption model
// (method.md section 4): each measured eigenvalue and each mode-shape entry is
// multiplied by (1 + level * r), r an independent draw per entry. Optionally the
// shape noise is additive with one size per shape: psi_i + level * max|psi| * r
// (sensor noise that does not shrink with the entry).
#pragma once

#include <random>
#include <string>

#include "femup/core/counter_rng.h"
#include "femup/core/invalid.h"
#include "femup/core/sysid/measurement.h"

namespace femup {

enum class NoiseDistribution {
  kGaussian,  // r ~ N(0, 1): level is the relative standard deviation
  kUniform,   // r ~ U(-1, 1): level is the largest relative error
};
const char* ToString(NoiseDistribution d);  // "gaussian", "uniform"
bool NoiseDistributionFromString(const std::string& text, NoiseDistribution* d);

struct NoiseModel {
  double level = 0;  // Nl, relative (0.05 = 5 %)
  NoiseDistribution distribution = NoiseDistribution::kGaussian;
  bool eigenvalues = true;  // corrupt lambda = (2 pi f)^2
  bool shapes = true;       // corrupt every mode-shape entry
  // Level for the shape entries; negative = the same as `level`.
  double shape_level = -1;
  // Shape noise relative to each entry (the paper's) or to the shape's largest
  // entry (additive, the same size on every sensor).
  enum class ShapeScale { kEntry, kPeak };
  ShapeScale shape_scale = ShapeScale::kEntry;
  Invalid Validate() const;  // ok when valid; the message names the field
};

// A corrupted copy of `data`. Draws eigenvalues first (mode order), then shape
// entries (column-major), so a given generator state gives one result. Throws
// InputError if a corrupted eigenvalue would be <= 0.
ModalData Corrupt(const ModalData& data, const NoiseModel& noise, std::mt19937_64* rng);
// The same with a counter-based generator (one per draw of a parallel study).
ModalData Corrupt(const ModalData& data, const NoiseModel& noise, CounterRng* rng);
// The same into *out, reusing its storage (a draw loop's buffer; out may be
// &data).
void Corrupt(const ModalData& data, const NoiseModel& noise, CounterRng* rng,
             ModalData* out);

}  // namespace femup
