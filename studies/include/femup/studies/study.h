// A study file (YAML; JSON is accepted, being YAML) describes one job: the
// model, its correction factors, the measured states, the linear system and
// the solver, and optional noise and output settings. LoadStudy reads and
// checks all of it before any work is done; every error names the file, the
// line and the field.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "femup/core/fe/builders.h"
#include "femup/core/fe/model.h"
#include "femup/core/fe/structure.h"
#include "femup/core/io/uff_modes.h"
#include "femup/core/sysid/expansion.h"
#include "femup/core/sysid/measurement.h"
#include "femup/problems/correction_system.h"
#include "femup/problems/effect_priors.h"
#include "femup/problems/eigen_sensitivity.h"
#include "femup/problems/noise.h"
#include "femup/solvers/linear_solver.h"
#include "femup/solvers/nonlinear_solver.h"
#include "femup/studies/effect_ranking.h"
#include "femup/studies/identify_study.h"

namespace femup {

// Where a measured state's modes come from: simulated from the truth, given in
// the study file, identified from a record file (UFF 58 / CSV) by ERA, read
// from the modes.json that `femup identify` wrote, or read from the mode shapes
// (dataset 55) of a UFF file. Shapes known at sensors only can be expanded to
// every model DOF before the factors are found.
struct MeasurementSpec {
  std::string state;  // "air", "water"
  Immersion immersion = Immersion::kDry;
  int simulate_modes = 0;  // > 0: simulate this many modes from `truth`
  ModalData data;          // given modes (no simulate_modes, identify or modes_file)

  std::optional<IdentifyOptions> identify;  // ERA on this record file
  std::string modes_file;  // or modes.json of `femup identify`, or UFF 55 modes
  // A UFF modes_file (.uff, .unv): which model DOF each node component is
  // (uff_dofs; geometry_file, geometry_tolerance, uff_directions). Its
  // `geometry` is read with the modes (PrepareMeasurements).
  std::optional<UffDofMap> uff_map;
  // Identified modes used, 1-based in ascending frequency; empty = all.
  std::vector<int> use_modes;
  // Per record channel: the model DOF it measures (-1: channel not used) and a
  // sign (-1 when the sensor points against the DOF). Set with identify and
  // modes_file; the shapes' rows follow the used channels.
  std::vector<int> channel_dofs;
  std::vector<double> channel_signs;

  std::optional<ExpansionOptions> expansion;  // expand sensor shapes to all DOFs
  std::string field;  // "measurements[2]", for messages at run time
};

// A measured state ready for the solvers, with where it came from.
struct PreparedState {
  ModalData data;        // what the factors are fitted to (expanded if asked)
  ModalData at_sensors;  // as measured, before expansion (== data without it)
  std::optional<IdentifyResult> identified;  // when identified from a record file
  std::optional<UffModes> uff;               // when read from UFF dataset 55
  std::vector<int> identified_modes;         // 1-based indices of the modes used
  std::string source;                        // file the modes came from, if any
  // Expansion quality per mode (empty without expansion).
  std::string expansion_method;
  int expansion_modes = 0;
  Eigen::VectorXd expansion_sensor_mac, expansion_condition;
};

// How the factors are found: the paper's linear method (Z d = F) on a linear
// solver, or iterative eigen-sensitivity updating on a nonlinear one.
struct SolverSpec {
  std::string label;              // for comparisons ("linear", "nonlinear + prior")
  std::string method = "linear";  // "linear" or "sensitivity"
  std::string name = "lstsq";     // a linear solver, or ceres / ipopt for sensitivity
  LinearSolverOptions linear;
  NonlinearSolverOptions nonlinear;
  EigenSensitivityOptions sensitivity;  // prior_sigma there is per parameter
  // Linear method: the regularisation prior x0 per parameter (empty = zero).
  Eigen::VectorXd prior_mean;
};

struct NoiseStudySpec {
  std::vector<double> levels;  // relative corruption levels (0.05 = 5 %)
  // Shape entries are corrupted at level * shape_level_ratio (eigenvalues at level).
  double shape_level_ratio = 1.0;
  // Shape noise relative to each entry ("entry", the paper's) or to the shape's
  // largest entry ("peak": additive, the same size on every sensor).
  std::string shape_noise = "entry";
  // Solvers compared draw by draw on the same noisy data; empty = the study's solver.
  std::vector<SolverSpec> compare;
  int draws = 200;  // random draws per level
  unsigned long long seed = 1;
  NoiseDistribution distribution = NoiseDistribution::kGaussian;
  double figure_level = 0.05;  // level shown in the estimated-vs-preset figure
};

// Water on a vertical cantilever by strip theory (femup/strip_theory.h): a
// transverse added mass per length from the section, over the wet length.
struct StripTheoryWater {
  double depth = 0;             // m above the base
  double fluid_density = 1000;  // kg/m^3
  double width = 0;             // section side normal to the motion (m)
  double thickness = 0;         // section side along the motion (m)
  double coefficient = 0;       // C_A; 0 = from the rectangle table
  double fade = 0;              // m below the surface over which it fades to 0
};

// Simulated test records of the structure described by the study (its model
// with the `truth` factors: the "real" structure), one file per state.
struct RecordStateSpec {
  std::string state;
  Immersion immersion = Immersion::kDry;
  // Modal damping ratios of the lowest modes; the last one holds for the rest.
  std::vector<double> damping_ratios{0.01};
  std::optional<StripTheoryWater> water;  // extra added mass in this state
  std::string file;                       // .uff or .csv, in the output folder
};

struct RecordsSpec {
  double sample_rate_hz = 0;
  double duration_s = 0;
  std::vector<int> sensor_dofs;  // one channel each
  int impulse_dof = -1;
  double impulse = 1.0;  // N s
  double noise = 0;      // relative to each channel's RMS
  // Modes above this frequency are left out, as an ideal anti-aliasing filter
  // would remove them; 0 = 0.4 x the sample rate (80 % of Nyquist).
  double cutoff_hz = 0;
  unsigned long long seed = 1;
  std::vector<RecordStateSpec> states;
};

// How `femup diagnose` looks for the sim-to-real gap (diagnose_study.h).
struct DiagnosisSpec {
  // Which diagnosis runs: "model_effects" (effects as changes of the model,
  // effect_ranking.h; every model type, the default) or "cantilever" (the
  // cantilever's own pipeline, diagnose_study.h; a cantilever model only,
  // kept for comparison and for `femup benchmark`). Empty: "model_effects".
  std::string engine;
  // The engine that runs: engine, or the default. (A cantilever's default
  // was its own pipeline until session 59.)
  std::string Engine() const { return engine.empty() ? "model_effects" : engine; }
  double frequency_noise = 0.002;       // relative standard deviation of a frequency
  double shape_noise = 0.02;            // of a shape entry, relative to its largest
  std::vector<std::string> candidates;  // effect kinds tried; empty = all
  // 1: single effects only; 2: also pairs; 0 (unstated): the engine's default.
  // The cantilever's own pipeline: 2. The one engine: 2 where the study
  // measured two or more states (a test in air and in water, where an effect
  // of the wet state alone and a model error of both are expected together),
  // 1 otherwise (on the one-state blind cantilever suite pairs named a pair in
  // single-effect cases and lost more verdicts than they gained:
  // docs/diagnosis.md, "The whole cantilever suite again, and with pairs").
  int max_effects = 0;
  int MaxEffectsFor(bool own_pipeline, std::size_t measured_states) const {
    if (max_effects > 0) return max_effects;
    return own_pipeline || measured_states >= 2 ? 2 : 1;
  }
  // With pairs on the one engine: among how many of a family's best-fitting
  // places its pairs of places are formed (EffectRankingOptions::pair_places;
  // -1: every place).
  int pair_places = 10;
  // Held-out modes: "auto" (the highest mode of each state with 3 or more),
  // "none", or the listed (state, 1-based measured mode) pairs.
  std::string held_out = "auto";
  std::vector<std::pair<std::string, int>> held_out_modes;
  bool use_shapes = true;
  bool mesh_error = true;  // add the discretisation error to the noise
  // Allow for the model's own form error where its builder knows a richer
  // formulation (a plane frame's members with shear deformation;
  // effect_ranking.h). Not used by the cantilever's own pipeline.
  bool formulation_error = true;
  // Allow for it on the mode shapes too, not the frequencies alone.
  // EffectRankingOptions::form_error_on_shapes.
  bool form_error_on_shapes = true;
  // Where the form error is allowed for, each class moved to the mode of the
  // misfit its evidence is taken on; false: at its raw fit (for comparison).
  // EffectRankingOptions::form_step. Not used by the cantilever's own pipeline.
  bool form_step = true;
  // With form_step, each fitted class moved by a fit of that misfit to its
  // mode rather than by one Gauss-Newton step. EffectRankingOptions::form_fit.
  bool form_fit = false;
  // Where the model's builder made it on a finer mesh too (a plane frame:
  // FormVariant::model) and that mesh moves one of the measured modes by more
  // than 3 frequency noise standard deviations, diagnose on the finer mesh
  // (its nodes and candidates named as the model's); false: on the model's,
  // with the finer mesh allowed for as a form error. Off by default: on the
  // plane-frame suite it named 2 cases right that the model's mesh had wrong
  // and 7 wrong that it had right (docs/diagnosis.md, "Diagnosing on the finer
  // mesh"). Not used by the cantilever's own pipeline.
  bool refine_mesh = false;
  // What the user knows of the nominal model's overall stiffness and mass
  // (`model_uncertainty: {stiffness: 0.02, mass: 0.01}`, relative standard
  // deviations; 0: nothing stated), allowed for as the model's form error
  // rather than named a gap (EffectRankingOptions::stiffness_uncertainty).
  // The one engine only: refused with engine: cantilever.
  double stiffness_uncertainty = 0;
  double mass_uncertainty = 0;
  // Bootstrap copies the structures' probabilities are averaged over (a
  // bagged posterior, effect_ranking.h); 0: the Laplace posterior alone. Not
  // used by the cantilever's own pipeline.
  int bagging_copies = 400;
  // Stiffness loss on each member of a group where the model has at most this
  // many (-1: every member); EffectRankingOptions::max_members.
  int max_members = 200;
  // Of more members than this, only the ones a linearised screen ranks best
  // are fitted (-1: all); EffectRankingOptions::members_fitted.
  int members_fitted = 12;
  // Attached masses carry a fitted rotary inertia (a radius of gyration, from
  // a negligible one to 0.1 of the structure's extent) where the model has
  // rotations and node coordinates; false: translational point masses only.
  // EffectRankingOptions::rotary_inertia; on a cantilever,
  // EffectOptions::rotary_inertia.
  bool rotary_inertia = true;
  // The candidate families' form error, as a fraction of the nominal model's
  // misfit per frequency and shape entry, added to the noise in quadrature: a
  // family of a few parameters describes a real effect only to some fraction
  // of the change it makes (docs/diagnosis.md, "Form error").
  double form_error = 0.05;
  bool localise = true;  // the per-element scan
  std::string solver = "ceres";
  double confidence = 0.9;  // a verdict below this lists what it cannot separate
  // Other models: a gap is named only where its probability (1 - P(none))
  // reaches this; 0 (the default): the most probable family, whatever its
  // probability. EffectRankingOptions::gap_confidence.
  double gap_confidence = 0;
  // Other models: an effect is named the gap's cause only where it removes at
  // least this share of the nominal misfit beyond the noise; 0: the most
  // probable family however little it explains. EffectRankingOptions::
  // gap_explained.
  double gap_explained = 1.0 / 3;
  // How the frequencies' noise temperature enters the evidence
  // (EffectRankingOptions::frequency_temperature): "auto" (the default),
  // "threshold" or "marginal".
  EffectRankingOptions::FrequencyTemperature frequency_temperature =
      EffectRankingOptions::FrequencyTemperature::kAuto;
  // Each class's evidence: "laplace" (Laplace's approximation at the best fit)
  // or "sampled" (importance sampling over its prior, sampled_evidence.h, where
  // its standard error is small; Laplace's elsewhere). docs/diagnosis.md has the
  // two compared on the blind benchmark.
  std::string evidence = "laplace";
  int evidence_samples = 2000;  // draws per class when sampled
  // What the user knows of the families (`priors` and `weights`;
  // docs/diagnosis.md, "Stated priors"): ranges or normal priors on their
  // physical quantities, the regions where they may act, their relative prior
  // weights. Checked against the model when the study is read. Empty: the
  // families' defaults.
  StatedPriors priors;
};

struct Study {
  std::string path;  // the study file
  std::string name;
  std::string description;
  Structure structure;
  std::optional<CantileverSpec> cantilever;  // when the model is a cantilever
  ParametrisedModel model;
  std::optional<Eigen::VectorXd> truth;  // preset factors (model order), if given
  std::map<std::string, double> fixed;   // known factor values by name
  // Bounds per parameter (model order; -inf / +inf where none; empty = none) and
  // linear equalities C d = e over the factors.
  Eigen::VectorXd lower, upper;
  Eigen::MatrixXd equality_matrix;
  Eigen::VectorXd equality_rhs;
  std::vector<MeasurementSpec> measurements;
  CorrectionSystemOptions system;
  SolverSpec solver;
  std::optional<NoiseStudySpec> noise_study;
  std::optional<RecordsSpec> records;      // for `femup simulate`
  std::optional<DiagnosisSpec> diagnosis;  // for `femup diagnose`
  bool plots = true;
};

// Reads and checks a study file. Throws InputError naming file, line and field
// for a missing file, a syntax error, an unknown key, a wrong type or size, a
// NaN, a non-positive-definite mass, shapes that do not match the sensors, or
// a name that matches no parameter.
Study LoadStudy(const std::string& path);
// The same for a study's text already in memory. `path` stands for the file in
// messages, and file names in the study are relative to its folder.
Study ParseStudy(std::string_view text, const std::string& path);
// A study's model and factors alone: text with `model` and optionally
// `parameters`, `truth`, `name` and `description` (any other key is an error),
// read and checked as ParseStudy reads them, without measurements (what the
// Python module's model_from_dict needs). The Study has its structure, model,
// fixed values, bounds, equalities and truth; nothing else is set.
Study ParseStudyModel(std::string_view text, const std::string& path);

// The measured states: given ones as they are, simulated ones from the truth,
// identified ones from their files, UFF 55 modes at the DOFs their map gives
// (femup/uff_modes.h); expanded where the study asks. Throws InputError naming
// the file and field for unreadable records, too few identified modes,
// channel/sensor count mismatches, UFF nodes that do not map, or a failed
// expansion.
std::vector<PreparedState> PrepareMeasurements(const Study& study);
// The `data` of each prepared state.
std::vector<ModalData> MeasuredStates(const Study& study);

}  // namespace femup
