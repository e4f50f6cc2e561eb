// The Eigensystem Realization Algorithm (ERA; Juang & Pappa, "An eigensystem
// realization algorithm for modal parameter identification and model
// reduction", J. Guidance, Control and Dynamics 8(5), 1985): natural
// frequencies, damping ratios and mode shapes from impulse responses or free
// decays, with the consistency indicators of Pappa, Elliott & Schenk
// ("Consistent-mode indicator for the eigensystem realization algorithm",
// JGCD 16(5), 1993), and a stabilisation analysis over model orders.
//
// Data: `records` are Markov parameters sampled at `sample_rate_hz`. For one
// reference (one impulse location, or one free decay) they are a channels x
// samples matrix; for several references a list of such matrices of equal size,
// one per reference. Sample k of reference j is Y_k(:, j), the response at
// t = k / sample_rate_hz.
//
// Method. From Y_k, k = k0, k0+1, ... (k0 = options.first_sample) build the
// block Hankel matrices (r block rows, s block columns)
//   H(0) = [Y_k0 ... Y_k0+s-1; ...; Y_k0+r-1 ... Y_k0+r+s-2],
//   H(1) = the same shifted one sample later,
// take the SVD H(0) = U S V', keep the first n singular triplets and realise
//   A = S_n^-1/2 U_n' H(1) V_n S_n^-1/2,  C = first block row of U_n S_n^1/2,
//   B = first block column of S_n^1/2 V_n'.
// Each eigenvalue z of A gives the continuous-time pole lambda = ln(z) * fs,
// natural frequency |lambda| / 2 pi (Hz) and damping ratio -Re(lambda)/|lambda|;
// the shape at the sensors is C psi (psi the eigenvector). Complex-conjugate
// pairs are reported once (Im lambda > 0).
//
// Indicators (each in [0, 1], 1 = ideal):
//  * MPC, modal phase collinearity (Pappa & Elliott; as used by Pappa, Elliott &
//    Schenk 1993): how close a complex shape is to a real (monophase) vector
//    times a complex constant. With x = Re(phi), y = Im(phi), the eigenvalues
//    l1 >= l2 of [x'x x'y; x'y y'y] give MPC = ((l1 - l2) / (l1 + l2))^2, which
//    equals |phi^T phi|^2 / (phi^H phi)^2. A shape is converted to a real normal
//    mode by the rotation e^{i theta} that maximises the norm of its real part
//    (theta = -arg(phi^T phi) / 2); the real part is kept.
//  * EMAC, extended modal amplitude coherence (Pappa, Elliott & Schenk 1993):
//    temporal consistency. The identified modal observability matrix
//    U_n S_n^1/2 psi holds, in block row k, the shape times z^k. For each
//    sensor the value in the last block row is compared with the first block
//    row extrapolated by z^(r-1): amplitude ratio R (smaller over larger) times
//    a phase weight W = max(0, 1 - |phase error| / (pi/4)). Sensor values are
//    averaged with weights |phi_i|^2 (output EMAC). The same with the modal
//    controllability matrix psi^-1 S_n^1/2 V_n' over the block columns gives
//    the input EMAC; EMAC = output EMAC x input EMAC. Noise modes, which do not
//    persist through the record, get low EMAC.
//  * Modal contribution: the share of mode j in the reconstructed response,
//    E_j / sum_l E_l with E_j = sum_k ||Y_k^(j)||_F^2 over the samples the
//    Hankel spans and Y_k^(j) = 2 Re(c_j z_j^k b_j^T) the mode's part of the
//    realised Markov parameters (c_j = C psi_j, b_j^T = row j of psi^-1 B). Cross
//    terms between modes are left out, so the shares sum to 1 over all poles of
//    the realisation (accepted or not).
#pragma once

#include <Eigen/Core>
#include <complex>
#include <string>
#include <vector>

#include "femup/core/invalid.h"

namespace femup {

enum class PoleStatus {
  kAccepted,
  kNotOscillatory,    // real eigenvalue of A (no conjugate pair)
  kNegativeDamping,   // damping ratio < 0: a growing, non-physical pole
  kExcessiveDamping,  // damping ratio > EraOptions::max_damping_ratio
  kOutOfBand,         // natural frequency not in (0, Nyquist)
  kLowEmac,           // EMAC < EraOptions::min_emac
  kLowMpc,            // MPC < EraOptions::min_mpc
};
// "accepted", "not_oscillatory", "negative_damping", "excessive_damping",
// "out_of_band", "low_emac", "low_mpc".
const char* ToString(PoleStatus status);

struct EraOptions {
  int order = 0;  // model order n (states): 2 per mode; >= 1, usually even
  // Hankel block rows r and block columns s; 0 = automatic: the samples from
  // first_sample on are shared so that H(0) is about square (r * channels ~
  // s * references), with at most max_hankel_size rows and columns.
  int block_rows = 0;
  int block_columns = 0;
  int max_hankel_size = 400;
  // First sample used as a Markov parameter. 1 skips Y_0, the direct term of an
  // acceleration impulse response (for FRF-derived impulse responses the
  // sample that carries the spike); 0 uses every sample, e.g. for free decays.
  int first_sample = 1;
  double max_damping_ratio = 0.2;  // poles more damped than this are rejected
  // Poles with EMAC (or MPC) below these are rejected. Physical modes of clean
  // records have EMAC near 1 and noise poles near 0, hence the default 0.5; MPC
  // is off by default because non-proportionally damped modes are complex.
  double min_emac = 0.5;
  double min_mpc = 0.0;
  Invalid Validate() const;  // ok when valid, else the field and what is wrong
};

struct IdentifiedMode {
  PoleStatus status = PoleStatus::kAccepted;
  std::complex<double> pole;  // continuous-time lambda (rad/s), Im >= 0
  double frequency_hz = 0;    // undamped natural frequency |lambda| / 2 pi
  double damping_ratio = 0;   // -Re(lambda) / |lambda|
  // C psi at the sensors, rotated to maximise its real part and scaled to unit
  // norm; `shape` is its real part, rescaled to unit norm, with the entry of
  // largest magnitude positive (complex_shape carries the same sign).
  Eigen::VectorXcd complex_shape;
  Eigen::VectorXd shape;
  double mpc = 0;
  double emac = 0;
  double contribution = 0;
};

struct EraResult {
  int order = 0;
  double sample_rate_hz = 0;
  int block_rows = 0;
  int block_columns = 0;
  Eigen::VectorXd singular_values;       // all singular values of H(0), descending
  Eigen::MatrixXd a, b, c;               // discrete-time realisation (order n)
  std::vector<IdentifiedMode> modes;     // accepted poles, ascending frequency
  std::vector<IdentifiedMode> rejected;  // the other poles, ascending frequency
};

// ERA at one model order. Throws InputError on invalid options, empty or
// non-finite records, records of unequal sizes, too few samples for the Hankel,
// or an order above the Hankel's rank bound min(r * channels, s * references).
EraResult RunEra(const Eigen::MatrixXd& records, double sample_rate_hz,
                 const EraOptions& options);
EraResult RunEra(const std::vector<Eigen::MatrixXd>& references, double sample_rate_hz,
                 const EraOptions& options);

// Stabilisation analysis: ERA at orders min_order, min_order + order_step, ...,
// max_order from one SVD of H(0). Each accepted pole is compared with the
// accepted pole of the previous order nearest in frequency: stable in frequency
// when |df| / f <= frequency_tolerance, in damping when |dzeta| / zeta <=
// damping_tolerance, in shape when MAC >= mac_tolerance. The defaults (1 %, 5 %,
// MAC 0.98) are the values commonly used for stabilisation diagrams.
struct StabilisationOptions {
  EraOptions era;  // Hankel sizes and pole rejection; era.order is not used
  int min_order = 2;
  int max_order = 40;
  int order_step = 2;
  double frequency_tolerance = 0.01;
  double damping_tolerance = 0.05;
  double mac_tolerance = 0.98;
  Invalid Validate() const;  // ok when valid, else the field and what is wrong
};

struct DiagramPole {
  IdentifiedMode mode;  // status says whether the pole was accepted
  // Against the previous order (false at the first order and for rejected poles).
  int previous = -1;  // index of the matched pole in the previous order, or -1
  bool stable_frequency = false;
  bool stable_damping = false;
  bool stable_shape = false;
  // Number of consecutive orders, ending at this one, through which this pole's
  // chain of matches is stable in all three: 1 for an accepted pole that is not
  // stable against the previous order, 0 for a rejected pole.
  int stable_run = 0;
  bool stable() const { return stable_frequency && stable_damping && stable_shape; }
};

struct DiagramOrder {
  int order = 0;
  std::vector<DiagramPole> poles;  // every oscillatory pole, ascending frequency
};

// The data a stabilisation diagram plots.
struct StabilisationDiagram {
  double sample_rate_hz = 0;
  int block_rows = 0;
  int block_columns = 0;
  Eigen::VectorXd singular_values;  // of H(0), descending
  std::vector<DiagramOrder> orders;
};

StabilisationDiagram BuildStabilisationDiagram(const Eigen::MatrixXd& records,
                                               double sample_rate_hz,
                                               const StabilisationOptions& options);
StabilisationDiagram BuildStabilisationDiagram(
    const std::vector<Eigen::MatrixXd>& references, double sample_rate_hz,
    const StabilisationOptions& options);

struct StableMode {
  IdentifiedMode mode;  // the representative: the pole with the longest stable run
                        // (the highest order among equals)
  int order = 0;        // model order of the representative
  int stable_run = 0;   // its run of consecutive stable orders
  int num_poles = 0;    // poles in the group (stable for min_consecutive orders)
  // Spread of the group: standard deviations of frequency (Hz) and damping.
  double frequency_std_hz = 0;
  double damping_std = 0;
};

// Physical modes: accepted poles stable over at least `min_consecutive`
// consecutive orders (stable_run >= min_consecutive), grouped when within the
// diagram's frequency tolerance of each other with MAC >= its MAC tolerance; one
// per group, ascending frequency. `options` should be the diagram's.
std::vector<StableMode> PickStableModes(const StabilisationDiagram& diagram,
                                        const StabilisationOptions& options,
                                        int min_consecutive = 5);

}  // namespace femup
