#include "femup/core/sysid/frf_impulse.h"

#include <cmath>
#include <complex>
#include <sstream>
#include <unsupported/Eigen/FFT>
#include <vector>

#include "femup/core/errors.h"

namespace femup {

FrfImpulseResponse ImpulseResponseFromFrf(const Eigen::MatrixXcd& frf,
                                          double frequency_step_hz) {
  if (!(frequency_step_hz > 0) || !std::isfinite(frequency_step_hz)) {
    std::ostringstream msg;
    msg << "must be positive and finite, got " << frequency_step_hz;
    throw InputError("frf.frequency_step_hz", msg.str());
  }
  if (frf.rows() < 1 || frf.cols() < 2) {
    std::ostringstream msg;
    msg << "is " << frf.rows() << " x " << frf.cols()
        << "; expected at least one channel (row) and two frequency lines (columns)";
    throw InputError("frf.lines", msg.str());
  }
  if (!frf.allFinite()) throw InputError("frf.lines", "has a NaN or infinite entry");
  const Eigen::Index lines = frf.cols();
  const Eigen::Index length = 2 * (lines - 1);
  FrfImpulseResponse out;
  out.sample_rate_hz = static_cast<double>(length) * frequency_step_hz;
  out.data.resize(frf.rows(), length);
  Eigen::FFT<double> fft;  // scaled inverse: includes 1 / L
  std::vector<std::complex<double>> half(lines);
  std::vector<double> record(length);
  for (Eigen::Index i = 0; i < frf.rows(); ++i) {
    for (Eigen::Index k = 0; k < lines; ++k) half[k] = frf(i, k);
    half.front().imag(0.0);
    half.back().imag(0.0);
    // Real inverse from the half spectrum (N = L/2 + 1 lines).
    fft.inv(record.data(), half.data(), length);
    for (Eigen::Index n = 0; n < length; ++n)
      out.data(i, n) = out.sample_rate_hz * record[n];
  }
  return out;
}

}  // namespace femup
