// Impulse responses from measured frequency response functions (FRFs) by the
// inverse discrete Fourier transform, so that time-domain identification (ERA,
// femup/era.h) also serves FRF data.
//
// Convention: H(f) = integral h(t) exp(-2 pi i f t) dt (a response
// x(t) = Re(X exp(2 pi i f t)) to a force Re(F exp(2 pi i f t)) has X = H F).
// Given the one-sided FRF at N lines f_k = k df, k = 0 .. N-1 (0 Hz to the
// Nyquist frequency f_{N-1} = fs / 2), the record has L = 2 (N - 1) samples at
// fs = 2 (N - 1) df and
//   h[n] = df * sum_{k=-(N-2)}^{N-1} H(f_k) exp(2 pi i k n / L),  H(f_-k) = conj H(f_k),
// i.e. fs times the inverse DFT of the Hermitian-extended spectrum. The
// imaginary parts of the 0 Hz and Nyquist lines cannot belong to a real record
// and are ignored. The result is the impulse response wrapped with period
// 1 / df (time aliasing); for a sum of damped exponentials the wrapped record is
// again a sum of the same exponentials, so poles identified from it are
// unchanged. Uses Eigen's FFT module (kissfft).
#pragma once

#include <Eigen/Core>

namespace femup {

struct FrfImpulseResponse {
  Eigen::MatrixXd data;       // channels x 2 (N - 1) samples, FRF units x Hz
  double sample_rate_hz = 0;  // 2 (N - 1) df
};

// frf: channels x N complex lines from 0 Hz in steps of frequency_step_hz
// (N >= 2). Throws InputError on fewer than two lines, no channel, a
// non-finite entry or a non-positive step.
FrfImpulseResponse ImpulseResponseFromFrf(const Eigen::MatrixXcd& frf,
                                          double frequency_step_hz);

}  // namespace femup
