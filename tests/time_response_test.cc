// Simulated impulse responses (core/include/femup/core/sysid/time_response.h), checked
// against the closed-form impulse response of a single-DOF oscillator and
// against the matrix exponential of the first-order (state-space) equations
// with the damping matrix built explicitly.
#include "femup/core/sysid/time_response.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <string>
#include <unsupported/Eigen/MatrixFunctions>
#include <vector>

#include "femup/core/errors.h"

namespace femup {
namespace {

SparseMatrix Sparse(const Eigen::MatrixXd& a) { return a.sparseView(); }

// x(t) of m x'' + c x' + k x = delta(t), written out for the under-damped case:
// x = exp(-zeta w t) sin(wd t) / (m wd) and its analytic derivatives.
struct Sdof {
  double m, k, zeta;
  double w() const { return std::sqrt(k / m); }
  double sigma() const { return zeta * w(); }
  double wd() const { return w() * std::sqrt(1 - zeta * zeta); }
  double x(double t) const {
    return std::exp(-sigma() * t) * std::sin(wd() * t) / (m * wd());
  }
  double v(double t) const {
    return std::exp(-sigma() * t) *
           (wd() * std::cos(wd() * t) - sigma() * std::sin(wd() * t)) / (m * wd());
  }
  double a(double t) const {
    const double s = sigma(), d = wd();
    return std::exp(-s * t) *
           ((s * s - d * d) * std::sin(d * t) - 2 * s * d * std::cos(d * t)) / (m * d);
  }
};

TimeResponseOptions Options(double rate, double duration, ResponseQuantity quantity) {
  TimeResponseOptions o;
  o.sample_rate_hz = rate;
  o.duration_s = duration;
  o.quantity = quantity;
  return o;
}

TEST(TimeResponse, SingleDofMatchesAnalyticImpulseResponse) {
  const Sdof sdof{2.0, 800.0, 0.05};  // w = 20 rad/s
  const SparseMatrix k = Sparse(Eigen::MatrixXd::Constant(1, 1, sdof.k));
  const SparseMatrix m = Sparse(Eigen::MatrixXd::Constant(1, 1, sdof.m));
  for (ResponseQuantity q : {ResponseQuantity::kDisplacement, ResponseQuantity::kVelocity,
                             ResponseQuantity::kAcceleration}) {
    TimeResponseOptions o = Options(200.0, 2.0, q);
    o.damping_ratio = sdof.zeta;
    const TimeResponse r = SimulateImpulseResponse(k, m, 0, o);
    ASSERT_EQ(r.num_channels(), 1);
    ASSERT_EQ(r.num_samples(), 400);
    EXPECT_NEAR(r.frequencies_hz[0], 20.0 / (2 * M_PI), 1e-12);
    EXPECT_NEAR(r.damping_ratios[0], 0.05, 1e-15);
    const Eigen::VectorXd t = r.Times();
    EXPECT_DOUBLE_EQ(t[399], 399 / 200.0);
    double peak = 0, err = 0;
    for (int s = 0; s < r.num_samples(); ++s) {
      const double ref = q == ResponseQuantity::kDisplacement ? sdof.x(t[s])
                         : q == ResponseQuantity::kVelocity   ? sdof.v(t[s])
                                                              : sdof.a(t[s]);
      peak = std::max(peak, std::abs(ref));
      err = std::max(err, std::abs(r.data(0, s) - ref));
    }
    EXPECT_LE(err, 1e-13 * peak) << ToString(q);
  }
}

TEST(TimeResponse, InitialValuesAfterTheImpulse) {
  // Just after a unit impulse: x = 0, v = 1/m, and the acceleration jumps from 0
  // to -c v / m = -2 zeta w / m (the Dirac part is not a sample).
  const Sdof sdof{4.0, 3600.0, 0.1};  // w = 30 rad/s
  const SparseMatrix k = Sparse(Eigen::MatrixXd::Constant(1, 1, sdof.k));
  const SparseMatrix m = Sparse(Eigen::MatrixXd::Constant(1, 1, sdof.m));
  TimeResponseOptions o = Options(1000.0, 0.01, ResponseQuantity::kDisplacement);
  o.damping_ratio = sdof.zeta;
  EXPECT_EQ(SimulateImpulseResponse(k, m, 0, o).data(0, 0), 0.0);
  o.quantity = ResponseQuantity::kVelocity;
  EXPECT_NEAR(SimulateImpulseResponse(k, m, 0, o).data(0, 0), 0.25, 1e-15);
  o.quantity = ResponseQuantity::kAcceleration;
  const TimeResponse a = SimulateImpulseResponse(k, m, 0, o);
  EXPECT_NEAR(a.data(0, 0), -2 * 0.1 * 30.0 / 4.0, 1e-14);
  // One sample later the acceleration follows the equation of motion.
  EXPECT_NEAR(a.data(0, 1), sdof.a(1e-3), 1e-12);
}

TEST(TimeResponse, CriticalAndOverDampedOscillators) {
  // q'' + c q' + k q = delta: critical h = t e^{-w t}; over-damped
  // h = (e^{r1 t} - e^{r2 t}) / (r1 - r2) with r1,2 the real roots.
  const double k = 25.0;
  for (double t : {0.0, 0.05, 0.3, 2.0, 40.0}) {
    const OscillatorResponse crit = UnitImpulseResponse(10.0, k, t);
    EXPECT_NEAR(crit.displacement, t * std::exp(-5 * t), 1e-15);
    EXPECT_NEAR(crit.velocity, (1 - 5 * t) * std::exp(-5 * t), 1e-15);
    EXPECT_NEAR(crit.acceleration, (25 * t - 10) * std::exp(-5 * t), 1e-14);
    const double r1 = -1.0, r2 = -25.0;  // s^2 + 26 s + 25
    const OscillatorResponse over = UnitImpulseResponse(26.0, k, t);
    EXPECT_NEAR(over.displacement, (std::exp(r1 * t) - std::exp(r2 * t)) / (r1 - r2),
                1e-15);
    EXPECT_NEAR(over.velocity,
                (r1 * std::exp(r1 * t) - r2 * std::exp(r2 * t)) / (r1 - r2), 1e-14);
  }
  // A free mass (k = 0, c = 0): h = t.
  EXPECT_DOUBLE_EQ(UnitImpulseResponse(0, 0, 3.0).displacement, 3.0);
}

// Reference: the first-order system z' = S z with z = [x; v], S = [0 I; -M^-1 K
// -M^-1 C], z(0+) = [0; M^-1 F], solved by the matrix exponential.
Eigen::MatrixXd StateSpaceResponse(const Eigen::MatrixXd& k, const Eigen::MatrixXd& m,
                                   const Eigen::MatrixXd& c, const Eigen::VectorXd& f,
                                   double rate, int samples, ResponseQuantity q) {
  const int n = static_cast<int>(k.rows());
  const Eigen::MatrixXd minv = m.inverse();
  Eigen::MatrixXd s = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  s.topRightCorner(n, n).setIdentity();
  s.bottomLeftCorner(n, n) = -minv * k;
  s.bottomRightCorner(n, n) = -minv * c;
  const Eigen::MatrixXd step = (s / rate).exp();
  Eigen::VectorXd z = Eigen::VectorXd::Zero(2 * n);
  z.tail(n) = minv * f;
  Eigen::MatrixXd out(n, samples);
  for (int i = 0; i < samples; ++i) {
    const Eigen::VectorXd dz = s * z;
    if (q == ResponseQuantity::kDisplacement) {
      out.col(i) = z.head(n);
    } else if (q == ResponseQuantity::kVelocity) {
      out.col(i) = z.tail(n);
    } else {
      out.col(i) = dz.tail(n);
    }
    z = step * z;
  }
  return out;
}

Eigen::MatrixXd ChainStiffness() {
  Eigen::MatrixXd k(3, 3);
  k << 7e4, -3e4, 0, -3e4, 5e4, -2e4, 0, -2e4, 2e4;
  return k;
}

TEST(TimeResponse, RayleighDampingMatchesStateSpaceAndStatedRatios) {
  const Eigen::MatrixXd k = ChainStiffness();
  const Eigen::MatrixXd m = Eigen::Vector3d(2.0, 1.5, 1.0).asDiagonal();
  const double alpha = 1.5, beta = 2e-4;
  TimeResponseOptions o = Options(500.0, 1.0, ResponseQuantity::kAcceleration);
  o.damping = DampingModel::kRayleigh;
  o.rayleigh_alpha = alpha;
  o.rayleigh_beta = beta;
  o.sensor_dofs = {2, 0};
  const Eigen::VectorXd f = Eigen::Vector3d(0.3, -0.2, 1.0);
  const TimeResponse r = SimulateImpulseResponse(Sparse(k), Sparse(m), f, o);
  // zeta_j = alpha / (2 w_j) + beta w_j / 2 at the natural frequencies of (K, M).
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(k, m);
  for (int j = 0; j < 3; ++j) {
    const double w = std::sqrt(es.eigenvalues()[j]);
    EXPECT_NEAR(r.frequencies_hz[j], w / (2 * M_PI), 1e-12 * w);
    EXPECT_NEAR(r.damping_ratios[j], alpha / (2 * w) + beta * w / 2, 1e-14);
  }
  const Eigen::MatrixXd ref = StateSpaceResponse(k, m, alpha * m + beta * k, f, 500.0,
                                                 500, ResponseQuantity::kAcceleration);
  ASSERT_EQ(r.num_samples(), 500);
  const double peak = ref.cwiseAbs().maxCoeff();
  EXPECT_LE((r.data.row(0) - ref.row(2)).cwiseAbs().maxCoeff(), 1e-9 * peak);
  EXPECT_LE((r.data.row(1) - ref.row(0)).cwiseAbs().maxCoeff(), 1e-9 * peak);
}

TEST(TimeResponse, PerModeDampingMatchesStateSpace) {
  // C = M Phi diag(2 zeta_j w_j) Phi' M has the given modal ratios.
  const Eigen::MatrixXd k = ChainStiffness();
  const Eigen::MatrixXd m = Eigen::Vector3d(2.0, 1.5, 1.0).asDiagonal();
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(k, m);
  const std::vector<double> zeta = {0.02, 0.05, 0.01};
  Eigen::Vector3d c_modal;
  for (int j = 0; j < 3; ++j) c_modal[j] = 2 * zeta[j] * std::sqrt(es.eigenvalues()[j]);
  const Eigen::MatrixXd phi = es.eigenvectors();
  const Eigen::MatrixXd c = m * phi * c_modal.asDiagonal() * phi.transpose() * m;
  TimeResponseOptions o = Options(400.0, 0.5, ResponseQuantity::kVelocity);
  o.damping_ratios = zeta;
  const TimeResponse r = SimulateImpulseResponse(Sparse(k), Sparse(m), 1, o);
  const Eigen::MatrixXd ref = StateSpaceResponse(k, m, c, Eigen::Vector3d(0, 1, 0), 400.0,
                                                 200, ResponseQuantity::kVelocity);
  ASSERT_EQ(r.num_channels(), 3);
  EXPECT_LE((r.data - ref).cwiseAbs().maxCoeff(), 1e-9 * ref.cwiseAbs().maxCoeff());
}

TEST(TimeResponse, SeededNoiseIsReproducibleAndScaledToChannelRms) {
  const Eigen::MatrixXd k = ChainStiffness();
  const Eigen::MatrixXd m = Eigen::Vector3d(2.0, 1.5, 1.0).asDiagonal();
  TimeResponseOptions o = Options(1000.0, 4.0, ResponseQuantity::kAcceleration);
  const TimeResponse clean = SimulateImpulseResponse(Sparse(k), Sparse(m), 2, o);
  o.noise_level = 0.05;
  o.noise_seed = 42;
  const TimeResponse a = SimulateImpulseResponse(Sparse(k), Sparse(m), 2, o);
  const TimeResponse b = SimulateImpulseResponse(Sparse(k), Sparse(m), 2, o);
  EXPECT_EQ(a.data, b.data);  // bit for bit
  o.noise_seed = 43;
  const TimeResponse other = SimulateImpulseResponse(Sparse(k), Sparse(m), 2, o);
  EXPECT_GT((other.data - a.data).cwiseAbs().maxCoeff(), 0.0);
  for (int i = 0; i < 3; ++i) {
    const double rms = std::sqrt(clean.data.row(i).squaredNorm() / clean.num_samples());
    EXPECT_NEAR(a.noise_std[i], 0.05 * rms, 1e-12 * rms);
    // 4000 draws: the sample standard deviation is within ~4 sigma (sigma ~ 1.1 %).
    const Eigen::VectorXd noise = (a.data.row(i) - clean.data.row(i)).transpose();
    const double mean = noise.mean();
    const double sd =
        std::sqrt((noise.array() - mean).square().sum() / (noise.size() - 1));
    EXPECT_NEAR(sd / (0.05 * rms), 1.0, 0.05) << "channel " << i;
    EXPECT_LE(std::abs(mean), 4 * 0.05 * rms / std::sqrt(4000.0));
  }
}

std::string WhereOf(const SparseMatrix& k, const SparseMatrix& m, int dof,
                    const TimeResponseOptions& o) {
  try {
    SimulateImpulseResponse(k, m, dof, o);
  } catch (const InputError& e) {
    return e.where();
  }
  return "(no error)";
}

TEST(TimeResponse, BadInputNamesTheField) {
  const SparseMatrix k = Sparse(ChainStiffness());
  const SparseMatrix m = Sparse(Eigen::MatrixXd::Identity(3, 3));
  const TimeResponseOptions good = Options(100.0, 1.0, ResponseQuantity::kAcceleration);
  EXPECT_EQ(good.Validate().ToString(), "");
  EXPECT_EQ(WhereOf(k, m, 0, good), "(no error)");

  TimeResponseOptions o = good;
  o.sample_rate_hz = 0;
  EXPECT_EQ(o.Validate().field, "sample_rate_hz") << o.Validate().ToString();
  EXPECT_EQ(WhereOf(k, m, 0, o), "time_response.sample_rate_hz");
  o = good;
  o.duration_s = std::nan("");
  EXPECT_EQ(WhereOf(k, m, 0, o), "time_response.duration_s");
  o = good;
  o.duration_s = 1e-4;  // rounds to no sample
  EXPECT_EQ(WhereOf(k, m, 0, o), "time_response.duration_s");
  o = good;
  o.damping_ratio = -0.01;
  EXPECT_EQ(WhereOf(k, m, 0, o), "time_response.damping_ratio");
  o = good;
  o.damping_ratios = {0.01, 0.02};  // the model has three modes
  EXPECT_EQ(WhereOf(k, m, 0, o), "time_response.damping_ratios");
  o = good;
  o.damping = DampingModel::kRayleigh;
  o.rayleigh_beta = -1;
  EXPECT_EQ(WhereOf(k, m, 0, o), "time_response.rayleigh_beta");
  o = good;
  o.noise_level = -0.1;
  EXPECT_EQ(WhereOf(k, m, 0, o), "time_response.noise_level");
  o = good;
  o.sensor_dofs = {0, 3};
  EXPECT_EQ(WhereOf(k, m, 0, o), "time_response.sensor_dofs");
  o = good;
  o.eigen.num_modes = 0;
  EXPECT_EQ(WhereOf(k, m, 0, o), "time_response.eigen.num_modes");
  EXPECT_EQ(WhereOf(k, m, 3, good), "time_response.input_dof");
  EXPECT_THROW(SimulateImpulseResponse(k, m, Eigen::VectorXd::Ones(2), good), InputError);
}

}  // namespace
}  // namespace femup
