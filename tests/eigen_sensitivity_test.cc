// The eigen-sensitivity updating problem (problems/eigen_sensitivity.h), checked
// against: zero residuals at the paper chain's known factors, residuals computed
// by hand from SolveModes, central finite differences of its own residuals for
// the Jacobian, the known common-scaling null space (method.md section 3), and
// a Gauss-Newton loop written here that must recover the known factors.
#include "femup/problems/eigen_sensitivity.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "femup/core/errors.h"
#include "femup/core/fe/builders.h"
#include "femup/core/fe/sensor.h"
#include "femup/core/fe/space_frame.h"
#include "femup/core/fe/structure.h"
#include "femup/core/linalg/modal.h"
#include "femup/problems/noise.h"
#include "femup/problems/paper_chain.h"
#include "structure_specs.h"

namespace femup {
namespace {

// Noise-free measurements: the lowest modes of the model at its true factors,
// shapes at every DOF.
std::vector<ModalData> TrueData(const PaperChainScenario& s, int air_modes,
                                int water_modes) {
  return {PredictModes(s.model, s.preset, Immersion::kDry, air_modes, "air"),
          PredictModes(s.model, s.preset, Immersion::kWet, water_modes, "water")};
}

// `data` (shapes on every DOF) seen only by the sensors on `dofs`.
ModalData AtSensors(ModalData data, const std::vector<int>& dofs) {
  data.shapes = Eigen::MatrixXd(data.shapes(dofs, Eigen::all));
  data.sensor_dofs = dofs;
  return data;
}

void SwapModes(ModalData* data, int a, int b) {
  std::swap(data->frequencies_hz[a], data->frequencies_hz[b]);
  data->shapes.col(a).swap(data->shapes.col(b));
}

Eigen::VectorXd Residuals(const NonlinearProblem& p, const Eigen::VectorXd& x) {
  Eigen::VectorXd r;
  std::string why;
  EXPECT_TRUE(p.evaluate(x, &r, nullptr, &why)) << why;
  EXPECT_EQ(r.size(), p.num_residuals);
  return r;
}

// 2 air + 2 water modes with 2 % noise (seed 42); water seen at x1, x2, x4.
std::vector<ModalData> NoisyWaterAtThreeSensors(const PaperChainScenario& s) {
  std::mt19937_64 rng(42);
  NoiseModel noise;
  noise.level = 0.02;
  std::vector<ModalData> data = TrueData(s, 2, 2);
  for (ModalData& d : data) d = Corrupt(d, noise, &rng);
  data[1] = AtSensors(data[1], {0, 1, 3});
  return data;
}

int Row(const NonlinearProblem& p, const std::string& label) {
  const auto it = std::find(p.residual_labels.begin(), p.residual_labels.end(), label);
  EXPECT_NE(it, p.residual_labels.end()) << label;
  return static_cast<int>(it - p.residual_labels.begin());
}

// max |J - J_fd| / max |J|, J_fd from central differences with steps h and h/2
// combined by Richardson extrapolation (error O(h^4)).
double JacobianError(const NonlinearProblem& p, const Eigen::VectorXd& x, double h) {
  Eigen::VectorXd r;
  Eigen::MatrixXd jac;
  std::string why;
  EXPECT_TRUE(p.evaluate(x, &r, &jac, &why)) << why;
  EXPECT_EQ(jac.rows(), p.num_residuals);
  EXPECT_EQ(jac.cols(), p.num_parameters());
  Eigen::MatrixXd fd(jac.rows(), jac.cols());
  for (int i = 0; i < p.num_parameters(); ++i) {
    Eigen::VectorXd central[2];
    for (int level = 0; level < 2; ++level) {
      const double step = level == 0 ? h : h / 2;
      Eigen::VectorXd xp = x, xm = x;
      xp[i] += step;
      xm[i] -= step;
      central[level] = (Residuals(p, xp) - Residuals(p, xm)) / (2 * step);
    }
    fd.col(i) = (4 * central[1] - central[0]) / 3;
  }
  return (jac - fd).cwiseAbs().maxCoeff() / jac.cwiseAbs().maxCoeff();
}

// The Jacobian's modes computed in parallel give the same bits as one thread,
// on a model large enough for the sparse eigen-solver (a small space frame).
TEST(EigenSensitivity, JacobianDoesNotDependOnTheThreadCount) {
  SpaceFrameSpec spec = fixtures::SpaceFrame(6, 1, 1, 3);
  spec.water_depth = 25;
  const ParametrisedModel model = BuildSpaceFrame(spec);
  ASSERT_GT(model.num_dofs(), 1500);  // the sparse path of SolveModes
  Eigen::VectorXd truth = Eigen::VectorXd::Zero(model.num_parameters());
  for (int k : model.ParametersOfKind(ParameterKind::kAddedMass)) truth[k] = 0.3;
  std::vector<ModalData> data = {PredictModes(model, truth, Immersion::kDry, 4, "air"),
                                 PredictModes(model, truth, Immersion::kWet, 4, "water")};
  const std::vector<int> sensors = {0, 7, 13, 40, 101, 222, 333, 444, 555, 666};
  for (ModalData& d : data) d = AtSensors(d, sensors);
  Eigen::VectorXd x = Eigen::VectorXd::Constant(model.num_parameters(), 0.01);
  EigenSensitivityOptions one;
  EigenSensitivityOptions three;
  three.threads = 3;
  Eigen::VectorXd r1, r3;
  Eigen::MatrixXd j1, j3;
  std::string why;
  ASSERT_TRUE(BuildEigenSensitivityProblem(model, data, one).evaluate(x, &r1, &j1, &why))
      << why;
  ASSERT_TRUE(
      BuildEigenSensitivityProblem(model, data, three).evaluate(x, &r3, &j3, &why))
      << why;
  EXPECT_EQ(r1, r3);
  EXPECT_EQ(j1, j3);
  EXPECT_GT(j1.cwiseAbs().maxCoeff(), 0.0);
  three.threads = 0;
  EXPECT_NE(three.Validate().ToString().find("threads"), std::string::npos);
}

// A square frame's sway modes in x and y share one eigenvalue, and the
// eigensolver returns them in an arbitrary rotation of their eigenspace. The
// model's pair is rotated to the measured pair: at the true factors the shape
// residuals vanish whatever the measured rotation, and the Jacobian column of
// a parameter that keeps the symmetry (a level's mass) is close to its finite
// difference.
TEST(EigenSensitivity, RepeatedEigenvaluesAreRotatedToTheMeasuredShapes) {
  SpaceFrameSpec spec = fixtures::SpaceFrame(3, 1, 1, 2);
  const ParametrisedModel model = BuildSpaceFrame(spec);
  const Eigen::VectorXd truth = Eigen::VectorXd::Zero(model.num_parameters());
  const ModalData exact = PredictModes(model, truth, Immersion::kDry, 4, "air");
  ASSERT_NEAR(exact.frequencies_hz[1] / exact.frequencies_hz[0], 1.0, 1e-9)
      << "the model is not symmetric";
  std::vector<int> sensors;
  for (int i = 0; i < model.num_dofs(); i += 5) sensors.push_back(i);
  const int mass_level2 = model.FindParameter("mass[l2]");
  ASSERT_GE(mass_level2, 0);
  for (double angle : {0.0, 0.4, 1.1}) {
    ModalData data = exact;
    const Eigen::VectorXd a = data.shapes.col(0), b = data.shapes.col(1);
    data.shapes.col(0) = std::cos(angle) * a + std::sin(angle) * b;
    data.shapes.col(1) = -std::sin(angle) * a + std::cos(angle) * b;
    data = AtSensors(data, sensors);
    const NonlinearProblem p = BuildEigenSensitivityProblem(model, {data}, {});
    EXPECT_LT(Residuals(p, truth).cwiseAbs().maxCoeff(), 1e-6) << angle;
    Eigen::VectorXd x = truth;
    x[mass_level2] = 0.05;
    Eigen::VectorXd r;
    Eigen::MatrixXd jac;
    std::string why;
    ASSERT_TRUE(p.evaluate(x, &r, &jac, &why)) << why;
    const double h = 1e-5;
    Eigen::VectorXd xp = x, xm = x;
    xp[mass_level2] += h;
    xm[mass_level2] -= h;
    const Eigen::VectorXd fd = (Residuals(p, xp) - Residuals(p, xm)) / (2 * h);
    // Approximate: the Jacobian leaves out how the fitted rotation turns as the
    // eigenspace moves at the sensors (measured: 5.3-5.5 % of the column's
    // largest entry here, against 1e-5 for the columns of distinct modes).
    EXPECT_LT((jac.col(mass_level2) - fd).cwiseAbs().maxCoeff(),
              0.1 * fd.cwiseAbs().maxCoeff())
        << angle;
  }
}

// A square jacket (12 m x 12 m, X-braced, 3 levels) read at its 12 leg
// joints (ux, uy), "measured" on the Timoshenko twin of 4 elements per member
// with E 1.5 % low: x and y sway modes in pairs of equal frequency in model
// and truth alike. Any rotation of a measured pair is as good a measurement;
// the eigensolver's own rotation of the model's pair is arbitrary. Measured
// modes are paired with the model's pair turned to them first
// (AlignRepeatedModes), so the misfit does not depend on either rotation.
// Sweeping the measured pair's angle sweeps its angle to the solver's: paired
// against the solver's rotation, the first pair's misfit at the nominal model
// was 1.5e6 at some angles (the two measured sway modes went to other model
// modes) and 453 at others (session 41, by turning the solver's pair).
TEST(EigenSensitivity, EqualPairsArePairedWhateverTheirRotation) {
  SpaceFrameSpec spec = fixtures::SpaceFrame(3, 1, 1, 2, 10, 12, 12);
  spec.blocks_per_level = 1;
  spec.bracing = FaceBracing::kX;
  const ParametrisedModel model = BuildSpaceFrame(spec);
  SpaceFrameSpec truth_spec = spec;
  truth_spec.theory = BeamTheory::kTimoshenko;
  truth_spec.elements_per_member = 4;
  const ParametrisedModel truth = BuildSpaceFrame(truth_spec);
  Eigen::VectorXd e = Eigen::VectorXd::Zero(truth.num_parameters());
  for (int p = 0; p < truth.num_parameters(); ++p)
    if (truth.parameter(p).kind == ParameterKind::kStiffness) e[p] = -0.015;
  const ModalData exact = PredictModes(truth, e, Immersion::kDry, 6, "air");
  ASSERT_NEAR(exact.frequencies_hz[1] / exact.frequencies_hz[0], 1.0, 1e-9);
  std::vector<int> truth_dofs, model_dofs;
  for (int node = 1; node <= 12; ++node) {
    for (const char* c : {":ux", ":uy"}) {
      const std::string label = "n" + std::to_string(node) + c;
      truth_dofs.push_back(truth.FindDof(label));
      model_dofs.push_back(model.FindDof(label));
      ASSERT_GE(model_dofs.back(), 0) << label;
    }
  }
  std::vector<double> misfits;
  for (int step = 0; step < 8; ++step) {
    const double angle = step * M_PI / 8;
    ModalData data = AtSensors(exact, truth_dofs);
    data.sensor_dofs = model_dofs;
    const Eigen::VectorXd a = data.shapes.col(0), b = data.shapes.col(1);
    data.shapes.col(0) = std::cos(angle) * a + std::sin(angle) * b;
    data.shapes.col(1) = -std::sin(angle) * a + std::cos(angle) * b;
    const NonlinearProblem p = BuildEigenSensitivityProblem(model, {data}, {});
    misfits.push_back(
        Residuals(p, Eigen::VectorXd::Zero(model.num_parameters())).squaredNorm());
  }
  // Within 7e-6 of each other (measured; 1517 noise units squared): the
  // model's pair is turned to the measured shapes' least-squares combinations,
  // each normalised, by their polar factor, which follows a rotation of the
  // measured pair only where the combinations are orthogonal and alike in
  // norm; the truth's pair at the sensors is not the model's.
  for (int step = 1; step < 8; ++step)
    EXPECT_NEAR(misfits[step], misfits[0], 1e-4 * misfits[0]) << step;
  EXPECT_LT(misfits[0], 2000);
}

TEST(EigenSensitivity, LabelsNamesAndShape) {
  const PaperChainScenario s = PaperChain(3);
  std::vector<ModalData> data = TrueData(s, 2, 3);
  data[0] = AtSensors(data[0], {0, 2, 4});
  const NonlinearProblem p = BuildEigenSensitivityProblem(s.model, data, {});
  // Air: 2 x (1 + 3 sensors); water: 3 x (1 + 5 DOFs).
  EXPECT_EQ(p.num_residuals, 8 + 18);
  ASSERT_EQ(p.residual_labels.size(), 26u);
  EXPECT_EQ(p.residual_labels[0], "air mode 1 lambda");
  EXPECT_EQ(p.residual_labels[2], "air mode 1 shape x3");
  EXPECT_EQ(p.residual_labels[8], "water mode 1 lambda");
  EXPECT_EQ(p.residual_labels[8 + 6 + 3], "water mode 2 shape x3");
  EXPECT_EQ(p.names, s.model.ParameterNames());
  ASSERT_EQ(p.groups.size(), 13u);
  EXPECT_EQ(p.groups[0], "mass");
  EXPECT_EQ(p.groups[5], "stiffness");
  EXPECT_EQ(p.groups[12], "added_mass");
  EXPECT_TRUE(p.residuals_whitened);
  EXPECT_TRUE(p.fixed.empty());
  EXPECT_EQ(p.initial, Eigen::VectorXd::Zero(13));
  const NonlinearProblem started =
      BuildEigenSensitivityProblem(s.model, data, {}, s.preset);
  EXPECT_EQ(started.initial, s.preset);

  EigenSensitivityOptions frequencies_only;
  frequencies_only.use_shapes = false;
  const NonlinearProblem q =
      BuildEigenSensitivityProblem(s.model, data, frequencies_only);
  EXPECT_EQ(q.num_residuals, 5);
  EXPECT_EQ(q.residual_labels[4], "water mode 3 lambda");
}

TEST(EigenSensitivity, ZeroResidualsAtTheTrueFactors) {
  const PaperChainScenario s = PaperChain(3);
  std::vector<ModalData> data = TrueData(s, 3, 3);
  data[0] = AtSensors(data[0], {1, 3, 4});
  data[1].shapes.col(1) *= -2.5;  // any scaling and sign of the data
  const NonlinearProblem p = BuildEigenSensitivityProblem(s.model, data, {});
  EXPECT_LT(Residuals(p, s.preset).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_GT(Residuals(p, Eigen::VectorXd::Zero(13)).norm(), 10.0);
}

// "mass": mass-normalised data are compared as they are, so any other scaling of
// the data shows, and the common scaling of mass and stiffness is no longer free.
TEST(EigenSensitivity, MassScaledShapesCarryTheScale) {
  const PaperChainScenario s = PaperChain(3);
  std::vector<ModalData> data = TrueData(s, 2, 2);  // mass-normalised shapes
  data[1].shapes.col(1) *= -1;                      // the sign stays free
  EigenSensitivityOptions options;
  options.shape_scaling = "mass";
  options.shape_noise = "entry";
  const NonlinearProblem p = BuildEigenSensitivityProblem(s.model, data, options);
  EXPECT_LT(Residuals(p, s.preset).cwiseAbs().maxCoeff(), 1e-9);
  data[1].shapes.col(1) *= 1.1;
  const NonlinearProblem scaled = BuildEigenSensitivityProblem(s.model, data, options);
  // 10 % larger data, each entry 2 % noise relative to itself: 5 sigma per entry.
  EXPECT_NEAR(std::abs(Residuals(scaled, s.preset)[Row(scaled, "water mode 2 shape x3")]),
              0.1 / 1.1 / 0.02, 1e-6);

  Eigen::VectorXd r;
  Eigen::MatrixXd jac;
  std::string why;
  ASSERT_TRUE(p.evaluate(s.preset, &r, &jac, &why)) << why;
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(jac);
  EXPECT_GT(svd.singularValues()[12], 1e-4 * svd.singularValues()[0]);
}

// "fit": the measured shape scaled so that its largest-magnitude entry is +-1,
// the model shape by the scale that minimises the weighted residuals of the
// mode, here found by a one-dimensional least-squares fit written out.
TEST(EigenSensitivity, FittedScaleResidualsFollowTheirDefinition) {
  const PaperChainScenario s = PaperChain(3);
  const std::vector<ModalData> data = NoisyWaterAtThreeSensors(s);
  EigenSensitivityOptions options;
  options.shape_sigma = 0.05;
  options.shape_noise = "entry";
  const NonlinearProblem p = BuildEigenSensitivityProblem(s.model, data, options);
  const Eigen::VectorXd x = 0.5 * s.preset;
  const Eigen::VectorXd r = Residuals(p, x);

  const Modes wet = SolveModes(s.model.UpdatedStiffness(x), s.model.UpdatedWetMass(x));
  const Eigen::VectorXd measured =
      data[1].shapes.col(1) / data[1].shapes.col(1).cwiseAbs().maxCoeff();
  const Eigen::VectorXd model = wet.shapes.col(1)(data[1].sensor_dofs);
  const Eigen::VectorXd w = (0.05 * measured.cwiseAbs()).cwiseInverse();
  const Eigen::VectorXd a = w.cwiseProduct(model), b = w.cwiseProduct(measured);
  const double c = a.colPivHouseholderQr().solve(b)[0];
  const std::vector<std::string> dofs = {"x1", "x2", "x4"};
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(r[Row(p, "water mode 2 shape " + dofs[i])],
                (c * model[i] - measured[i]) / (0.05 * std::abs(measured[i])), 1e-9);
  }
}

// "unit", computed another way: the measured shape scaled so that its
// largest-magnitude entry is +-1, the model shape scaled to the same Euclidean
// norm and sign.
TEST(EigenSensitivity, UnitScaledResidualsFollowTheirDefinition) {
  const PaperChainScenario s = PaperChain(3);
  const std::vector<ModalData> data = NoisyWaterAtThreeSensors(s);
  EigenSensitivityOptions options;
  options.frequency_sigma = 0.01;
  options.shape_sigma = 0.05;
  options.shape_scaling = "unit";
  const NonlinearProblem p = BuildEigenSensitivityProblem(s.model, data, options);
  const Eigen::VectorXd x = 0.5 * s.preset;
  const Eigen::VectorXd r = Residuals(p, x);

  const Modes wet = SolveModes(s.model.UpdatedStiffness(x), s.model.UpdatedWetMass(x));
  const double lambda_meas = std::pow(2 * M_PI * data[1].frequencies_hz[1], 2);
  EXPECT_NEAR(r[Row(p, "water mode 2 lambda")],
              (wet.eigenvalues[1] / lambda_meas - 1) / 0.01, 1e-9);
  const Eigen::VectorXd measured =
      data[1].shapes.col(1) / data[1].shapes.col(1).cwiseAbs().maxCoeff();
  Eigen::VectorXd model = wet.shapes.col(1)(data[1].sensor_dofs);
  model *= measured.norm() / model.norm();
  if (model.dot(measured) < 0) model = -model;
  const std::vector<std::string> dofs = {"x1", "x2", "x4"};
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(r[Row(p, "water mode 2 shape " + dofs[i])],
                (model[i] - measured[i]) / 0.05, 1e-9);
  }
}

TEST(EigenSensitivity, JacobianMatchesFiniteDifferences) {
  const PaperChainScenario s = PaperChain(3);
  std::mt19937_64 rng(3);
  NoiseModel noise;
  noise.level = 0.01;
  std::vector<ModalData> data = TrueData(s, 2, 3);
  for (ModalData& d : data) d = Corrupt(d, noise, &rng);
  data[0] = AtSensors(data[0], {0, 2, 3, 4});
  data[1].shapes.col(2) *= -1;  // exercises the sign alignment
  EigenSensitivityOptions options;
  options.prior_sigma = Eigen::VectorXd::Zero(13);
  options.prior_sigma.tail(3).setConstant(0.1);  // a prior on the added mass only
  options.prior_mean = Eigen::VectorXd::Constant(13, 0.01);
  options.tikhonov_lambda = 0.5;
  options.tikhonov_operator = Eigen::MatrixXd::Zero(2, 13);
  options.tikhonov_operator(0, 0) = 1;
  options.tikhonov_operator(0, 1) = -1;
  options.tikhonov_operator(1, 5) = 1;
  options.tikhonov_operator(1, 6) = -1;
  for (const char* scaling : {"fit", "unit", "mass"}) {
    for (const char* noise_model : {"max", "entry"}) {
      options.shape_scaling = scaling;
      options.shape_noise = noise_model;
      const NonlinearProblem p = BuildEigenSensitivityProblem(s.model, data, options);
      for (const Eigen::VectorXd& x : {Eigen::VectorXd(Eigen::VectorXd::Zero(13)),
                                       Eigen::VectorXd(0.7 * s.preset)}) {
        EXPECT_LT(JacobianError(p, x, 1e-4), 1e-8) << scaling << " " << noise_model;
      }
    }
  }
}

// The paper's cantilever (10 elements, water to 1.5 m) with factors drawn
// from `seed`, and 3 air + 3 water modes seen by the ten transverse sensors
// with 1 % noise.
struct NoisyCantilever {
  ParametrisedModel model;
  Eigen::VectorXd truth;
  std::vector<ModalData> data;
};
NoisyCantilever PaperCantileverData(unsigned seed) {
  CantileverSpec spec;
  spec.node_heights = UniformHeights(1.9, 10);
  spec.section = BeamSection{206e9, 8.8e-4, 8.53e-8, 7850};
  spec.water_depth = 1.5;
  spec.added_mass_basis = AddedMassBasis::kTransverse;
  NoisyCantilever out{BuildModel(BuildCantilever(spec), PaperParameterPlan()), {}, {}};
  const ParametrisedModel& model = out.model;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-0.05, 0.15);
  Eigen::VectorXd& truth = out.truth;
  truth.resize(model.num_parameters());
  for (int i = 0; i < truth.size(); ++i) truth[i] = u(rng);
  // Ten transverse sensors, as in the paper's experiment.
  std::vector<int> sensors;
  for (int node = 1; node <= 10; ++node) {
    sensors.push_back(model.FindDof("n" + std::to_string(node) + ":ux"));
  }
  NoiseModel noise;
  noise.level = 0.01;
  out.data = {
      AtSensors(PredictModes(model, truth, Immersion::kDry, 3, "air"), sensors),
      AtSensors(PredictModes(model, truth, Immersion::kWet, 3, "water"), sensors)};
  for (ModalData& d : out.data) d = Corrupt(d, noise, &rng);
  return out;
}

TEST(EigenSensitivity, CantileverJacobianMatchesFiniteDifferences) {
  const NoisyCantilever c = PaperCantileverData(9);
  const ParametrisedModel& model = c.model;
  const NonlinearProblem p = BuildEigenSensitivityProblem(model, c.data, {});
  EXPECT_EQ(p.residual_labels[1], "air mode 1 shape n1:ux");
  // Larger steps than for the chain: the eigensolver's rounding on this stiff
  // pencil enters the differences as 1/h.
  const double error =
      JacobianError(p, Eigen::VectorXd::Zero(model.num_parameters()), 1e-2);
  EXPECT_LT(error, 1e-6);  // measured: 1.7e-7
}

// Sensors between nodes (sensor.h): the paper's cantilever seen at points
// that are not nodes, read through the elements' shape functions. At the true
// factors the noise-free residuals vanish; the Jacobian (C times Nelson's
// eigenvector derivative) matches central differences.
TEST(EigenSensitivity, SensorsBetweenNodesGiveZeroResidualsAndTheirJacobian) {
  CantileverSpec spec;
  spec.node_heights = UniformHeights(1.9, 10);
  spec.section = BeamSection{206e9, 8.8e-4, 8.53e-8, 7850};
  spec.water_depth = 1.5;
  spec.added_mass_basis = AddedMassBasis::kTransverse;
  const Structure structure = BuildCantilever(spec);
  const ParametrisedModel model = BuildModel(structure, PaperParameterPlan());
  std::vector<SensorRow> rows;
  for (double x : {0.27, 0.61, 0.95, 1.33, 1.62, 1.87}) {
    SensorSpec at;
    at.has_x = true;
    at.x = x;
    SensorRow row;
    ASSERT_FALSE(LocateSensor(structure, at, &row));
    EXPECT_GT(row.weights.size(), 1u);  // between nodes: both ends' DOFs
    rows.push_back(row);
  }
  Eigen::VectorXd truth = Eigen::VectorXd::LinSpaced(model.num_parameters(), -0.04, 0.12);
  std::vector<ModalData> data;
  for (const auto& [immersion, name] :
       {std::pair(Immersion::kDry, "air"), std::pair(Immersion::kWet, "water")}) {
    ModalData d = PredictModes(model, truth, immersion, 3, name);
    d.shapes = ReadSensors(rows, d.shapes);
    d.sensor_weights = SensorMatrix(rows, model.num_dofs());
    for (const SensorRow& r : rows) d.sensor_names.push_back(r.name);
    data.push_back(d);
  }
  const NonlinearProblem p = BuildEigenSensitivityProblem(model, data, {});
  EXPECT_EQ(p.residual_labels[1], "air mode 1 shape x=0.27:ux");
  EXPECT_EQ(p.num_residuals, 2 * 3 * (1 + 6));
  EXPECT_LT(Residuals(p, truth).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_GT(Residuals(p, Eigen::VectorXd::Zero(model.num_parameters())).norm(), 1.0);
  const double error =
      JacobianError(p, Eigen::VectorXd::Zero(model.num_parameters()), 1e-2);
  EXPECT_LT(error, 1e-6);
}

// A Ritz basis that spans the whole space (every mode: the paper's cantilever
// has few DOFs) makes the reduced problem the full one: the same residuals,
// and a Jacobian by modal expansion over every mode that matches Nelson's
// (another formulation of the same derivative).
TEST(EigenSensitivity, RitzBasisOfTheWholeSpaceGivesTheFullProblem) {
  const NoisyCantilever c = PaperCantileverData(11);
  const ParametrisedModel& model = c.model;
  const std::vector<ModalData>& data = c.data;
  EigenSensitivityOptions options;
  options.extra_modes = model.num_dofs();  // the basis: every mode
  const ModelPencil pencil(model);
  const Eigen::VectorXd x0 = Eigen::VectorXd::Zero(model.num_parameters());
  EigenSensitivityOptions reduced = options;
  reduced.ritz = BuildRitzBasis(pencil, data, options, x0);
  ASSERT_EQ(reduced.ritz->dry.cols(), model.num_dofs());
  ASSERT_EQ(reduced.ritz->wet.cols(), model.num_dofs());
  options.extra_modes = 4;
  reduced.extra_modes = 4;
  const NonlinearProblem full = BuildEigenSensitivityProblem(model, data, options);
  const NonlinearProblem ritz = BuildEigenSensitivityProblem(model, data, reduced);
  for (const Eigen::VectorXd& x : {x0, Eigen::VectorXd(0.5 * c.truth)}) {
    Eigen::VectorXd rf, rr;
    Eigen::MatrixXd jf, jr;
    std::string why;
    ASSERT_TRUE(full.evaluate(x, &rf, &jf, &why)) << why;
    ASSERT_TRUE(ritz.evaluate(x, &rr, &jr, &why)) << why;
    EXPECT_LT((rf - rr).cwiseAbs().maxCoeff(), 1e-7 * rf.cwiseAbs().maxCoeff());
    EXPECT_LT((jf - jr).cwiseAbs().maxCoeff(), 1e-6 * jf.cwiseAbs().maxCoeff());
  }
}

// On a space frame too large for the whole space, the basis of the lowest
// modes and their static corrections at the nominal model follows a 40 %
// stiffness loss of one brace group: the reduced residuals at the damaged
// state are those of the full model to a small part of a standard deviation.
TEST(EigenSensitivity, RitzBasisFollowsALargeChangeOfOneGroup) {
  // Not square in plan (12 m x 11 m): the x and y sways of a square frame are a
  // double eigenvalue, whose shapes any rotation within the pair represents
  // (round-off decides which, and the reduced and full models need not agree on
  // it).
  SpaceFrameSpec spec = fixtures::SpaceFrame(3, 1, 1, 3, 10, 12, 11);
  spec.blocks_per_level = 1;
  spec.bracing = FaceBracing::kX;
  const ParametrisedModel model = BuildSpaceFrame(spec);
  ASSERT_GT(model.num_dofs(), 500);
  Eigen::VectorXd truth = Eigen::VectorXd::Zero(model.num_parameters());
  const std::vector<std::string> names = model.ParameterNames();
  const auto it = std::find(names.begin(), names.end(), "stiffness[l2:braces1]");
  ASSERT_NE(it, names.end());
  truth[it - names.begin()] = -0.4;
  std::vector<int> sensors;
  for (int node = 1; node <= 12; ++node) {
    sensors.push_back(model.FindDof("n" + std::to_string(node) + ":ux"));
    sensors.push_back(model.FindDof("n" + std::to_string(node) + ":uy"));
  }
  const std::vector<ModalData> data = {
      AtSensors(PredictModes(model, truth, Immersion::kDry, 6, "air"), sensors)};
  EigenSensitivityOptions options;
  options.eigen.method = EigenOptions::Method::kSparseShiftInvert;
  EigenSensitivityOptions reduced = options;
  reduced.ritz = BuildRitzBasis(ModelPencil(model), data, options,
                                Eigen::VectorXd::Zero(model.num_parameters()));
  EXPECT_LT(reduced.ritz->dry.cols(), 200);
  const NonlinearProblem full = BuildEigenSensitivityProblem(model, data, options);
  const NonlinearProblem ritz = BuildEigenSensitivityProblem(model, data, reduced);
  Eigen::VectorXd rf, rr;
  Eigen::MatrixXd jf, jr;
  std::string why;
  ASSERT_TRUE(full.evaluate(truth, &rf, &jf, &why)) << why;
  ASSERT_TRUE(ritz.evaluate(truth, &rr, &jr, &why)) << why;
  EXPECT_LT(rf.cwiseAbs().maxCoeff(), 1e-6);  // the full model at its own truth
  // In standard deviations; measured 0.34. (On a square plan this was 0.106 on
  // one machine and 996 on another: the double sway eigenvalue.)
  EXPECT_LT(rr.cwiseAbs().maxCoeff(), 0.5);
  const int column = static_cast<int>(it - names.begin());
  EXPECT_LT((jf.col(column) - jr.col(column)).norm(), 0.05 * jf.col(column).norm());
}

// Mass and stiffness scaled together leave the data unchanged (method.md
// section 3): the Jacobian at the truth has exactly that null vector, and
// fixing mass 4 removes it.
TEST(EigenSensitivity, CommonScalingIsTheOnlyNullDirection) {
  const PaperChainScenario s = PaperChain(3);
  const NonlinearProblem p = BuildEigenSensitivityProblem(s.model, TrueData(s, 2, 2), {});
  Eigen::VectorXd r;
  Eigen::MatrixXd jac;
  std::string why;
  ASSERT_TRUE(p.evaluate(s.preset, &r, &jac, &why)) << why;
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(jac, Eigen::ComputeFullV);
  const Eigen::VectorXd sv = svd.singularValues();
  EXPECT_LT(sv[12], 1e-10 * sv[0]);
  EXPECT_GT(sv[11], 1e-4 * sv[0]);
  Eigen::VectorXd scaling = s.preset;
  scaling.head(10).array() += 1.0;
  EXPECT_GT(std::abs(svd.matrixV().col(12).dot(scaling.normalized())), 1 - 1e-10);
}

// Gauss-Newton written here (x -= (J'J)^-1 J'r over the free factors, by QR)
// from the nominal model, with mass 4 fixed at its true value as in the paper.
TEST(EigenSensitivity, GaussNewtonRecoversThePaperFactors) {
  for (int wet : {3, 2}) {
    const PaperChainScenario s = PaperChain(wet);
    std::vector<ModalData> data = TrueData(s, 2, 2);
    data[1] = AtSensors(data[1], {0, 1, 2, 4});
    const NonlinearProblem p = BuildEigenSensitivityProblem(s.model, data, {});
    const int fixed = s.model.FindParameter(s.fixed_parameter);
    std::vector<int> free;
    for (int i = 0; i < p.num_parameters(); ++i) {
      if (i != fixed) free.push_back(i);
    }
    Eigen::VectorXd x = p.initial;
    x[fixed] = s.preset[fixed];
    int iterations = 0;
    double step_norm = 1;
    // Until the step is 1e-11: quadratic convergence gets there in 5 steps;
    // below, steps of 1e-13 to 4e-13 are rounding (the residuals' floor is
    // 1e-12), so a tighter stop would count rounding, not convergence.
    while (step_norm > 1e-11 && iterations < 20) {
      Eigen::VectorXd r;
      Eigen::MatrixXd jac;
      std::string why;
      ASSERT_TRUE(p.evaluate(x, &r, &jac, &why)) << why;
      const Eigen::MatrixXd jf = jac(Eigen::all, free);
      const Eigen::VectorXd step = jf.colPivHouseholderQr().solve(r);
      x(free) -= step;
      step_norm = step.norm();
      ++iterations;
    }
    EXPECT_LE(iterations, 8) << "wet masses " << wet;  // measured: 5 and 5
    for (int i = 0; i < p.num_parameters(); ++i) {
      EXPECT_NEAR(x[i], s.preset[i], 1e-8) << p.names[i];
    }
    EXPECT_LT(Residuals(p, x).norm(), 1e-9);
  }
}

TEST(EigenSensitivity, PairingByMacFollowsSwappedModes) {
  const PaperChainScenario s = PaperChain(3);
  std::vector<ModalData> data = TrueData(s, 3, 3);
  std::vector<ModalData> swapped = data;
  SwapModes(&swapped[0], 0, 1);
  SwapModes(&swapped[1], 1, 2);
  const NonlinearProblem p = BuildEigenSensitivityProblem(s.model, swapped, {});
  EXPECT_LT(Residuals(p, s.preset).norm(), 1e-9);
  EigenSensitivityOptions by_order;
  by_order.pair_by_mac = false;
  EXPECT_GT(Residuals(BuildEigenSensitivityProblem(s.model, swapped, by_order), s.preset)
                .norm(),
            10.0);

  // With noise: the same residuals in another order, so the same norm.
  std::mt19937_64 rng(17);
  NoiseModel noise;
  noise.level = 0.02;
  for (ModalData& d : data) d = Corrupt(d, noise, &rng);
  swapped = data;
  SwapModes(&swapped[0], 0, 2);
  const double norm =
      Residuals(BuildEigenSensitivityProblem(s.model, data, {}), s.preset).norm();
  const double swapped_norm =
      Residuals(BuildEigenSensitivityProblem(s.model, swapped, {}), s.preset).norm();
  EXPECT_GT(norm, 1.0);
  EXPECT_NEAR(swapped_norm, norm, 1e-12 * norm);
}

TEST(EigenSensitivity, PairsAMeasuredModeOutOfOrder) {
  // Air modes 1 and 3 measured (mode 2 missed): mode 3 pairs with model mode 3.
  const PaperChainScenario s = PaperChain(3);
  std::vector<ModalData> data = TrueData(s, 3, 2);
  ModalData& air = data[0];
  air.frequencies_hz = Eigen::Vector2d(air.frequencies_hz[0], air.frequencies_hz[2]);
  air.shapes = Eigen::MatrixXd(air.shapes(Eigen::all, std::vector<int>{0, 2}));
  EXPECT_LT(Residuals(BuildEigenSensitivityProblem(s.model, data, {}), s.preset).norm(),
            1e-9);

  // Without extra model modes mode 3 can only pair with model mode 2: below
  // min_mac the evaluation fails (and does not throw).
  EigenSensitivityOptions options;
  options.extra_modes = 0;
  options.min_mac = 0.9;
  const NonlinearProblem p = BuildEigenSensitivityProblem(s.model, data, options);
  Eigen::VectorXd r;
  Eigen::MatrixXd jac;
  std::string why;
  EXPECT_FALSE(p.evaluate(s.preset, &r, &jac, &why));
  EXPECT_NE(why.find("air mode 2"), std::string::npos) << why;
  EXPECT_NE(why.find("MAC"), std::string::npos) << why;
}

TEST(EigenSensitivity, EvaluationFailuresAreReportedNotThrown) {
  const PaperChainScenario s = PaperChain(3);
  const NonlinearProblem p = BuildEigenSensitivityProblem(s.model, TrueData(s, 2, 2), {});
  Eigen::VectorXd r;
  Eigen::MatrixXd jac;
  std::string why;
  // Mass factors of -1.5 make M~ negative definite.
  Eigen::VectorXd x = Eigen::VectorXd::Zero(13);
  x.head(5).setConstant(-1.5);
  EXPECT_FALSE(p.evaluate(x, &r, &jac, &why));
  EXPECT_NE(why.find("positive definite"), std::string::npos) << why;
  why.clear();
  EXPECT_FALSE(p.evaluate(Eigen::VectorXd::Zero(4), &r, nullptr, &why));
  EXPECT_FALSE(why.empty());
  x.setZero();
  x[0] = std::nan("");
  EXPECT_FALSE(p.evaluate(x, &r, nullptr, &why));
}

TEST(EigenSensitivity, PriorAndTikhonovRows) {
  const PaperChainScenario s = PaperChain(3);
  EigenSensitivityOptions options;
  options.use_shapes = false;
  options.prior_mean = Eigen::VectorXd::Constant(13, 0.1);
  options.prior_sigma = Eigen::VectorXd::Zero(13);
  options.prior_sigma[2] = 0.5;
  options.prior_sigma[12] = 0.25;
  options.prior_sigma[7] = std::numeric_limits<double>::infinity();  // no prior
  options.tikhonov_lambda = 3;
  const NonlinearProblem p =
      BuildEigenSensitivityProblem(s.model, TrueData(s, 2, 2), options);
  ASSERT_EQ(p.num_residuals, 4 + 2 + 13);
  EXPECT_EQ(p.residual_labels[4], "prior mass[3]");
  EXPECT_EQ(p.residual_labels[5], "prior added_mass[3]");
  EXPECT_EQ(p.residual_labels[6], "tikhonov 1");
  Eigen::VectorXd r;
  Eigen::MatrixXd jac;
  std::string why;
  ASSERT_TRUE(p.evaluate(s.preset, &r, &jac, &why)) << why;
  EXPECT_NEAR(r[4], (s.preset[2] - 0.1) / 0.5, 1e-15);
  EXPECT_NEAR(r[5], (s.preset[12] - 0.1) / 0.25, 1e-15);
  EXPECT_NEAR(jac(4, 2), 2.0, 1e-15);
  EXPECT_EQ(jac.row(4).cwiseAbs().sum(), 2.0);
  const Eigen::VectorXd expected = 3 * (s.preset.array() - 0.1).matrix();
  EXPECT_LT((r.tail(13) - expected).norm(), 1e-14);
  EXPECT_EQ(jac.bottomRows(13), 3 * Eigen::MatrixXd::Identity(13, 13));
}

TEST(EigenSensitivity, BadInputNamesTheField) {
  const PaperChainScenario s = PaperChain(3);
  const std::vector<ModalData> data = TrueData(s, 2, 2);
  auto expect_error = [&](const std::vector<ModalData>& states,
                          const EigenSensitivityOptions& options,
                          const std::string& field, const Eigen::VectorXd& start = {}) {
    try {
      BuildEigenSensitivityProblem(s.model, states, options, start);
      ADD_FAILURE() << "no InputError for " << field;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  };
  const EigenSensitivityOptions ok;
  expect_error({}, ok, "states");
  std::vector<ModalData> bad = data;
  bad[1] = AtSensors(bad[1], {0, 1, 2});
  bad[1].sensor_dofs[2] = 7;  // the model has 5 DOFs
  expect_error(bad, ok, "water.sensors");
  bad = data;
  bad[0].frequencies_hz = Eigen::VectorXd::Constant(6, 30.0);
  bad[0].shapes = Eigen::MatrixXd();
  expect_error(bad, ok, "air.frequencies");
  bad = data;
  bad[0].frequencies_hz[1] = -3;
  expect_error(bad, ok, "air.frequencies");

  EigenSensitivityOptions o;
  o.frequency_sigma = 0;
  expect_error(data, o, "frequency_sigma");
  o = ok;
  o.shape_sigma = -1;
  expect_error(data, o, "shape_sigma");
  o = ok;
  o.shape_scaling = "peak";
  expect_error(data, o, "shape_scaling");
  o = ok;
  o.extra_modes = -1;
  expect_error(data, o, "extra_modes");
  o = ok;
  o.min_mac = 1.5;
  expect_error(data, o, "min_mac");
  o = ok;
  o.prior_mean = Eigen::VectorXd::Zero(12);
  expect_error(data, o, "prior_mean");
  o = ok;
  o.prior_sigma = Eigen::VectorXd::Ones(14);
  expect_error(data, o, "prior_sigma");
  o = ok;
  o.prior_sigma = Eigen::VectorXd::Ones(13);
  o.prior_sigma[3] = std::nan("");
  expect_error(data, o, "prior_sigma");
  o = ok;
  o.tikhonov_lambda = -1;
  expect_error(data, o, "tikhonov_lambda");
  o = ok;
  o.tikhonov_lambda = 1;
  o.tikhonov_operator = Eigen::MatrixXd::Identity(3, 3);
  expect_error(data, o, "tikhonov_operator");
  o = ok;
  o.eigen.tolerance = 0;
  expect_error(data, o, "eigen");
  expect_error(data, ok, "start", Eigen::VectorXd::Zero(5));

  const ParametrisedModel bare(s.model.stiffness(), s.model.mass(), s.model.dof_labels());
  try {
    BuildEigenSensitivityProblem(bare, data, ok);
    ADD_FAILURE() << "no InputError for a model without parameters";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("parameters"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace femup
