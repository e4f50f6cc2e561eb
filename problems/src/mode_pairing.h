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

// Before pairing by MAC: each repeated eigenvalue's eigenspace turned to the
// state's measured shapes at the sensors (femup::AlignRepeatedModes, modal.h);
// nothing where the state has no measured shapes.
void AlignRepeatedModes(const StateTerms& st, Modes* modes);

// Model modes whose shape misfits against a measured mode differ by less than
// this (3 noise standard deviations of a chi-square difference) are alike to
// the sensors: the frequency decides which is paired.
constexpr double kPairingTie = 9.0;

}  // namespace femup::output_error
