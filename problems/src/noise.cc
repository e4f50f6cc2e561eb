#include "femup/problems/noise.h"

#include <cmath>

#include "femup/core/enum_names.h"
#include "femup/core/errors.h"

namespace femup {

constexpr EnumName<NoiseDistribution> kNoiseDistributionNames[] = {
    {NoiseDistribution::kGaussian, "gaussian"},
    {NoiseDistribution::kUniform, "uniform"},
};

const char* ToString(NoiseDistribution d) {
  return NameIn(kNoiseDistributionNames, d, "gaussian");
}

bool NoiseDistributionFromString(const std::string& text, NoiseDistribution* d) {
  return ValueIn(kNoiseDistributionNames, text, d);
}

Invalid NoiseModel::Validate() const {
  // The messages name their field: callers show the message alone.
  if (!(level >= 0) || !std::isfinite(level))
    return {"level", "level must be finite and >= 0"};
  if (level >= 1) return {"level", "level must be below 1 (it is relative: 0.05 is 5 %)"};
  if (std::isnan(shape_level) || shape_level >= 1 || !std::isfinite(shape_level))
    return {"shape_level", "shape_level must be below 1 (negative: the same as level)"};
  return {};
}

namespace {

// `draw()` gives the next r of the noise model's distribution.
template <typename Draw>
void CorruptWith(const ModalData& data, const NoiseModel& noise, Draw draw,
                 ModalData* result) {
  if (const Invalid bad = noise.Validate()) throw InputError("noise", bad.message);
  *result = data;
  ModalData& out = *result;
  if (noise.eigenvalues) {
    for (Eigen::Index j = 0; j < out.frequencies_hz.size(); ++j) {
      const double factor = 1.0 + noise.level * draw();
      if (!(factor > 0)) {
        throw InputError("noise",
                         "a corrupted eigenvalue is not positive (level too high)");
      }
      out.frequencies_hz[j] *= std::sqrt(factor);  // lambda scales by factor
    }
  }
  if (noise.shapes) {
    const double shape_level = noise.shape_level < 0 ? noise.level : noise.shape_level;
    for (Eigen::Index j = 0; j < out.shapes.cols(); ++j) {
      const double peak = out.shapes.col(j).cwiseAbs().maxCoeff();  // before noise
      for (Eigen::Index i = 0; i < out.shapes.rows(); ++i) {
        if (noise.shape_scale == NoiseModel::ShapeScale::kPeak) {
          out.shapes(i, j) += shape_level * peak * draw();
        } else {
          out.shapes(i, j) *= 1.0 + shape_level * draw();
        }
      }
    }
  }
}

}  // namespace

ModalData Corrupt(const ModalData& data, const NoiseModel& noise, std::mt19937_64* rng) {
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const bool gaussian = noise.distribution == NoiseDistribution::kGaussian;
  ModalData out;
  CorruptWith(
      data, noise, [&] { return gaussian ? gauss(*rng) : uniform(*rng); }, &out);
  return out;
}

ModalData Corrupt(const ModalData& data, const NoiseModel& noise, CounterRng* rng) {
  ModalData out;
  Corrupt(data, noise, rng, &out);
  return out;
}

void Corrupt(const ModalData& data, const NoiseModel& noise, CounterRng* rng,
             ModalData* out) {
  const bool gaussian = noise.distribution == NoiseDistribution::kGaussian;
  CorruptWith(
      data, noise, [&] { return gaussian ? rng->Gaussian() : rng->Symmetric(); }, out);
}

}  // namespace femup
