// Fitting unmodelled effects (effects.h) to measured modes: the output-error
// problem over the effects' parameters, for any NonlinearSolver.
//
// The model: a vertical cantilever (BuildCantilever) whose bending DOFs (ux, rz)
// do not couple with the axial ones, so the bending eigenproblem is solved on
// its own (the coupling is checked; axial modes never enter the pairing).
// Sensors are DOF labels ("n7:ux"), so effects that add DOFs (support springs
// free the base) keep the sensors where they are.
//
// Residuals, per state and observed mode (measured mode number k, 1-based among
// the structure's bending modes), paired with model bending mode (f, phi):
//   frequency:  (f / f_meas - 1) / sigma_k, sigma_k the mode's relative
//               frequency uncertainty (noise and model error together);
//   shape (when the mode has one and use_shapes), one per sensor:
//               (c s_i - t_i) / sigma_i, t = psi / max |psi|, s = phi at the
//               sensors, c = s't / s's (the modal scale factor), sigma_i the
//               mode's own per-sensor sigma where it has one, else shape_sigma.
// Pairing: with shapes, among the lowest (highest observed number +
// extra_modes) bending modes, in order (PairModesInOrder: the measured modes and
// the state's companions, in ascending frequency, take model modes in ascending
// order with the largest sum of MACs at the sensors; a cantilever's bending
// modes never swap order); without shapes, mode k is the k-th bending mode.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "femup/core/fe/builders.h"
#include "femup/core/invalid.h"
#include "femup/core/sysid/measurement.h"
#include "femup/problems/effects.h"
#include "femup/problems/nonlinear_problem.h"

namespace femup {

struct ObservedMode {
  int number = 1;              // 1-based bending mode number (ascending frequency)
  double frequency_hz = 0;     // > 0
  double frequency_sigma = 0;  // relative standard deviation, > 0
  Eigen::VectorXd shape;       // at the state's sensors, or empty
  // Per sensor, relative to the shape's largest entry (noise and model error
  // together); empty: EffectFitData::shape_sigma for every entry.
  Eigen::VectorXd shape_sigma;
};

struct ObservedState {
  std::string state;
  Immersion immersion = Immersion::kDry;
  std::vector<std::string> sensors;  // DOF labels (or names) of the shape rows
  // Sensors between nodes (femup/sensor.h): sensor i reads the sum of weight *
  // phi[label] over sensor_terms[i] (a point on an element reads both ends' ux
  // and rz). Empty: sensor i is the DOF labelled sensors[i].
  std::vector<std::vector<std::pair<std::string, double>>> sensor_terms;
  std::vector<ObservedMode> modes;
  // The state's other measured modes (those held out of this data set, or
  // fitted when this set is the held-out one). With shapes they take part in the
  // pairing, so every measured mode of the state gets a distinct model mode
  // whichever set it is in; they add no residuals. Only number, frequency (for
  // the order; finite, >= 0) and shape are read; companions without a shape are
  // left out of the pairing.
  std::vector<ObservedMode> companions;
};

struct EffectFitData {
  CantileverSpec nominal;
  std::vector<ObservedState> states;
  double shape_sigma = 0.02;  // of an entry, relative to the shape's largest entry
  bool use_shapes = true;
  int extra_modes = 4;
  // Added mass acts in wet states only (true when any state is wet).
  bool wet_only_added_mass = false;
  // Ok when valid, else the field and what is wrong.
  Invalid Validate() const;
};

// The model's answer for one state: per observed mode, the paired bending mode.
struct PredictedMode {
  int model_mode = -1;  // 1-based bending mode number paired
  double frequency_hz = 0;
  double mac = 0;         // at the sensors (0 without a measured shape)
  Eigen::VectorXd shape;  // at the sensors, scaled to the measured one (or max 1)
};
struct PredictedState {
  std::vector<PredictedMode> modes;
};

// The bending modes of the nominal model changed by `effects` with parameters
// `theta` (their parameter vectors concatenated), paired with the observed
// ones. Returns false with *why when the model cannot be evaluated (mass not
// positive definite, a sensor label the model lacks, bending coupled to axial).
bool PredictEffectModes(const EffectFitData& data,
                        const std::vector<const Effect*>& effects,
                        const Eigen::VectorXd& theta, std::vector<PredictedState>* out,
                        std::string* why);

// The lowest `count` bending modes of `spec` as it is (no effects): their
// frequencies and, at the `sensors` (DOF labels; may be empty; or names with
// `terms` as ObservedState::sensor_terms), their shapes scaled to a largest
// entry of 1. Returns false with *why when the model cannot be solved or has
// fewer bending modes.
bool BendingModesAtSensors(
    const CantileverSpec& spec, const std::vector<std::string>& sensors, int count,
    Eigen::VectorXd* frequencies_hz, Eigen::MatrixXd* shapes, std::string* why,
    const std::vector<std::vector<std::pair<std::string, double>>>& terms = {});

// The bending (ux, rz) stiffness and mass of `spec` as dense matrices, rows in
// the model's DOF order with the axial DOFs left out, and their DOF labels
// ("n3:ux"). Their bandwidth is 3 (two DOFs per node, numbered along the beam).
// Returns false with *why when the model cannot be built or bending couples
// with the axial DOFs.
bool AssembleBendingMatrices(const CantileverSpec& spec, Eigen::MatrixXd* stiffness,
                             Eigen::MatrixXd* mass, std::vector<std::string>* labels,
                             std::string* why);

// Whitened residuals of the observed modes for predictions `predicted`.
Eigen::VectorXd EffectResiduals(const EffectFitData& data,
                                const std::vector<PredictedState>& predicted);
int NumEffectResiduals(const EffectFitData& data);
// Residuals that carry information: one per frequency and (sensors - 1) per
// shape (the modal scale factor takes one).
int EffectDegreesOfFreedom(const EffectFitData& data);

// The parameters of several effects, concatenated, with their prior ranges.
std::vector<EffectParameter> EffectSetParameters(
    const EffectFitData& data, const std::vector<const Effect*>& effects);

// The fit over the effects' parameters (bounds = the prior ranges), starting at
// `start`; names "<kind>.<parameter>". Jacobian semi-analytic: the bending
// matrices' derivatives by forward differences of 1e-6 of each range (backward
// at the upper bound), then exact eigenvalue and eigenvector derivatives on the
// model's full set of bending modes (one eigen-solution per Jacobian instead of
// one per parameter), the pairing held; differences of the residuals where that
// cannot apply (a step that changes the DOFs, eigenvalues too close). The
// effects must outlive the problem. Throws InputError when the data are invalid or
// `start` has the wrong size or lies outside the ranges.
NonlinearProblem BuildEffectFitProblem(const EffectFitData& data,
                                       const std::vector<const Effect*>& effects,
                                       const Eigen::VectorXd& start);

}  // namespace femup
