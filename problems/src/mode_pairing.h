// Private to femup_problems: how the output-error engine (eigen_sensitivity.cc)
// scales a model shape against a measured one, and pairs measured modes with
// model modes.
#pragma once

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "femup/core/linalg/modal.h"
#include "output_error_context.h"

namespace femup::output_error {

// The factor c the residuals apply to a model shape s at the sensors before
// comparing it with measured mode j's target: the fitted N / D ("fit"),
// sign / ||s|| ("unit") or the sign ("mass"), sign making s' target >= 0; and
// c's derivative, linear in the shape's: dc = dc_ds' ds. s must not be zero;
// a "fit" with zero weights at every sensor gives c = 0 and dc_ds = 0.
struct ShapeScale {
  double c = 1;
  Eigen::VectorXd dc_ds;
};
ShapeScale ScaleShape(const StateTerms& st, Eigen::Index j, const Eigen::VectorXd& s);

// Measured mode j's shape misfit against a model shape s at the sensors, as
// the residuals weigh it: the squared norm of its shape rows with s scaled by
// ScaleShape. Infinite where s is zero.
double ShapeMisfit(const StateTerms& st, Eigen::Index j, const Eigen::VectorXd& s);

// The model mode paired with each measured mode of the state: in order where
// the state does not pair by MAC; otherwise by MAC at the sensors, modes the
// sensors see alike (shape misfits within kPairingTie of each other) by their
// frequency (PairModesByMacAndMisfit). False, with why, where a measured mode
// has no model mode left with MAC >= c.min_mac.
bool PairMeasuredModes(const Context& c, const StateTerms& st, const Modes& modes,
                       std::vector<int>* pairing, std::string* why);

// Model eigenvalues this close (relative) are one repeated eigenvalue: a
// symmetric structure's pairs (a square jacket's sway modes in x and y) come out
// of the eigensolver equal to about 1e-12, with eigenvectors in an arbitrary
// rotation of their eigenspace that changes from one solve to the next.
constexpr double kRepeatedEigenvalueTolerance = 1e-6;

// The last mode of the repeated eigenvalue that starts at mode `first`
// (`first` itself where the next eigenvalue is not within
// kRepeatedEigenvalueTolerance of it).
Eigen::Index LastOfRepeated(const Modes& modes, Eigen::Index first);

// Before pairing by MAC: within each repeated eigenvalue's eigenspace, the
// eigensolver's vectors are replaced by the M-orthonormal combinations that
// best match, at the sensors, the measured shapes that eigenspace reproduces
// best (at least as well as any single mode outside it, up to its dimension),
// the rest of the eigenspace completing the set. Without this, measured modes
// are paired against an arbitrary rotation of each pair (MAC about 0.5 each at
// 45 degrees) and go to other modes. An eigenspace that may extend beyond the
// modes solved (it holds the last one) is left as it is, as is every one where
// the state has no measured shapes.
void AlignRepeatedModes(const StateTerms& st, Modes* modes);

// Model modes whose shape misfits against a measured mode differ by less than
// this (3 noise standard deviations of a chi-square difference) are alike to
// the sensors: the frequency decides which is paired.
constexpr double kPairingTie = 9.0;

}  // namespace femup::output_error
