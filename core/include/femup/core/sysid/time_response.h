// Simulated time response of a finite element model to an impulse, by modal
// superposition with viscous modal damping. Used to make synthetic vibration
// records (impulse hammer tests, free decays) for system identification.
//
// With mass-normalised modes phi_j (K phi_j = w_j^2 M phi_j, phi_j' M phi_j = 1)
// and a damping matrix that the modes diagonalise, the response to a force
// f(t) = F delta(t) is x(t) = sum_j phi_j (phi_j' F) h_j(t), where h_j is the
// unit-impulse response of the modal oscillator
//   q'' + 2 zeta_j w_j q' + w_j^2 q = delta(t),   q(0-) = q'(0-) = 0,
// i.e. q(0+) = 0, q'(0+) = 1. Each h_j is evaluated in closed form (under-,
// critically or over-damped), so the samples carry no time-stepping error.
//
// Sampling: t_k = k / sample_rate_hz, k = 0 .. num_samples-1, and the value at
// t_0 = 0 is the limit t -> 0+ (just after the impulse). Displacement starts at
// 0, velocity at M^-1 F restricted to the modes used, and acceleration at
// -sum_j phi_j (phi_j' F) 2 zeta_j w_j: the Dirac part M^-1 F delta(t) of the
// acceleration is not a sample value and is left out.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "femup/core/fe/model.h"
#include "femup/core/invalid.h"
#include "femup/core/linalg/modal.h"

namespace femup {

enum class ResponseQuantity { kDisplacement, kVelocity, kAcceleration };
const char* ToString(ResponseQuantity quantity);  // "displacement", ...

enum class DampingModel {
  kModal,     // one ratio per mode (damping_ratios) or the same for all (damping_ratio)
  kRayleigh,  // C = alpha M + beta K: zeta_j = alpha / (2 w_j) + beta w_j / 2
};
const char* ToString(DampingModel model);  // "modal", "rayleigh"

struct TimeResponseOptions {
  double sample_rate_hz = 0;  // > 0
  double duration_s = 0;      // > 0; num_samples = round(duration_s * sample_rate_hz)
  // Model DOFs (0-based) recorded, one channel each, in this order; empty = all.
  std::vector<int> sensor_dofs;
  ResponseQuantity quantity = ResponseQuantity::kAcceleration;

  DampingModel damping = DampingModel::kModal;
  double damping_ratio = 0.02;         // kModal, used when damping_ratios is empty
  std::vector<double> damping_ratios;  // kModal: one per mode used, in mode order
  double rayleigh_alpha = 0;           // kRayleigh, 1/s
  double rayleigh_beta = 0;            // kRayleigh, s

  // Modes used in the superposition (the model overloads solve them with this).
  // The default (all modes, dense) suits small models; for large models set
  // eigen.num_modes to the band of interest.
  EigenOptions eigen;

  // Additive Gaussian noise: channel i gets N(0, (noise_level * rms_i)^2) per
  // sample, rms_i the root mean square of the noise-free channel. 0 = none.
  double noise_level = 0;
  std::uint64_t noise_seed = 1;  // seeds a std::mt19937_64

  int NumSamples() const;
  // Ok when valid, else the field and what is wrong. Checks what can be checked
  // without the model (sensor DOF ranges and the damping ratio count are
  // checked against the model when simulating).
  Invalid Validate() const;
};

struct TimeResponse {
  ResponseQuantity quantity = ResponseQuantity::kAcceleration;
  double sample_rate_hz = 0;
  std::vector<int> sensor_dofs;  // model DOF of each channel (row)
  Eigen::MatrixXd data;          // channels x samples (noise included)
  Eigen::VectorXd noise_std;     // per channel, the noise standard deviation added
  // The modal model used: natural frequencies (Hz, undamped) and damping ratios
  // (c_j / (2 w_j); +inf for a rigid-body mode with Rayleigh alpha > 0).
  Eigen::VectorXd frequencies_hz;
  Eigen::VectorXd damping_ratios;

  int num_channels() const { return static_cast<int>(data.rows()); }
  int num_samples() const { return static_cast<int>(data.cols()); }
  Eigen::VectorXd Times() const;  // t_k = k / sample_rate_hz, seconds
};

// Response to a unit impulse (1 N s) at model DOF `input_dof`. Solves the modes
// of (K, M) with options.eigen. Throws InputError on invalid options, a DOF
// outside the model, or a damping ratio count that differs from the modes used.
TimeResponse SimulateImpulseResponse(const SparseMatrix& stiffness,
                                     const SparseMatrix& mass, int input_dof,
                                     const TimeResponseOptions& options);

// Response to the impulse vector F (N s, one entry per model DOF).
TimeResponse SimulateImpulseResponse(const SparseMatrix& stiffness,
                                     const SparseMatrix& mass,
                                     const Eigen::VectorXd& impulse,
                                     const TimeResponseOptions& options);

// Same, from modes already solved (M-normalised shapes, eigenvalues w^2);
// options.eigen is not used.
TimeResponse SimulateImpulseResponse(const Modes& modes, const Eigen::VectorXd& impulse,
                                     const TimeResponseOptions& options);

// Unit-impulse response of one modal oscillator q'' + c q' + k q = delta(t)
// (c = 2 zeta w, k = w^2, both >= 0) at time t >= 0 (t = 0 means 0+), and its
// first and second time derivatives. Exact for every damping (also k = 0).
struct OscillatorResponse {
  double displacement = 0, velocity = 0, acceleration = 0;
};
OscillatorResponse UnitImpulseResponse(double c, double k, double t);

}  // namespace femup
