#include "femup/core/sysid/time_response.h"

#include <cmath>
#include <limits>
#include <random>
#include <sstream>

#include "femup/core/enum_names.h"
#include "femup/core/errors.h"

namespace femup {
namespace {

// Natural circular frequency of an eigenvalue; tiny negative eigenvalues of a
// rigid-body mode are rounding and count as 0.
double Omega(double eigenvalue) { return eigenvalue > 0 ? std::sqrt(eigenvalue) : 0.0; }

}  // namespace

constexpr EnumName<ResponseQuantity> kResponseQuantityNames[] = {
    {ResponseQuantity::kDisplacement, "displacement"},
    {ResponseQuantity::kVelocity, "velocity"},
    {ResponseQuantity::kAcceleration, "acceleration"},
};

const char* ToString(ResponseQuantity quantity) {
  return NameIn(kResponseQuantityNames, quantity, "?");
}

const char* ToString(DampingModel model) {
  return model == DampingModel::kRayleigh ? "rayleigh" : "modal";
}

int TimeResponseOptions::NumSamples() const {
  return static_cast<int>(std::lround(duration_s * sample_rate_hz));
}

Invalid TimeResponseOptions::Validate() const {
  std::ostringstream msg;
  if (!(sample_rate_hz > 0) || !std::isfinite(sample_rate_hz)) {
    msg << "must be positive and finite, got " << sample_rate_hz;
    return {"sample_rate_hz", msg.str()};
  }
  if (!(duration_s > 0) || !std::isfinite(duration_s)) {
    msg << "must be positive and finite, got " << duration_s;
    return {"duration_s", msg.str()};
  }
  if (duration_s * sample_rate_hz > 1e8) {
    msg << duration_s << " s at " << sample_rate_hz << " Hz is more than 1e8 samples";
    return {"duration_s", msg.str()};
  }
  if (NumSamples() < 1) {
    msg << duration_s << " s at " << sample_rate_hz << " Hz gives no sample";
    return {"duration_s", msg.str()};
  }
  for (std::size_t i = 0; i < sensor_dofs.size(); ++i) {
    if (sensor_dofs[i] < 0) {
      msg << "entry " << i + 1 << " is " << sensor_dofs[i]
          << "; DOF indices are 0-based and >= 0";
      return {"sensor_dofs", msg.str()};
    }
  }
  if (damping == DampingModel::kModal) {
    if (!(damping_ratio >= 0) || !std::isfinite(damping_ratio)) {
      msg << "must be finite and >= 0, got " << damping_ratio;
      return {"damping_ratio", msg.str()};
    }
    for (std::size_t j = 0; j < damping_ratios.size(); ++j) {
      if (!(damping_ratios[j] >= 0) || !std::isfinite(damping_ratios[j])) {
        msg << "mode " << j + 1 << " has " << damping_ratios[j]
            << "; expected finite and >= 0";
        return {"damping_ratios", msg.str()};
      }
    }
  } else {
    if (!(rayleigh_alpha >= 0) || !std::isfinite(rayleigh_alpha)) {
      msg << "must be finite and >= 0, got " << rayleigh_alpha;
      return {"rayleigh_alpha", msg.str()};
    }
    if (!(rayleigh_beta >= 0) || !std::isfinite(rayleigh_beta)) {
      msg << "must be finite and >= 0, got " << rayleigh_beta;
      return {"rayleigh_beta", msg.str()};
    }
  }
  if (const Invalid eig = eigen.Validate()) return eig.Under("eigen");
  if (!(noise_level >= 0) || !std::isfinite(noise_level)) {
    msg << "must be finite and >= 0 (a fraction of each channel's RMS), got "
        << noise_level;
    return {"noise_level", msg.str()};
  }
  return {};
}

Eigen::VectorXd TimeResponse::Times() const {
  Eigen::VectorXd t(data.cols());
  for (Eigen::Index k = 0; k < t.size(); ++k)
    t[k] = static_cast<double>(k) / sample_rate_hz;
  return t;
}

OscillatorResponse UnitImpulseResponse(double c, double k, double t) {
  const double sigma = 0.5 * c;
  const double disc = sigma * sigma - k;  // roots -sigma +- sqrt(disc)
  OscillatorResponse r;
  if (disc < 0) {
    // Under-damped: h = exp(-sigma t) sin(wd t) / wd.
    const double wd = std::sqrt(-disc);
    const double e = std::exp(-sigma * t), s = std::sin(wd * t), co = std::cos(wd * t);
    r.displacement = e * s / wd;
    r.velocity = e * (co - sigma * s / wd);
  } else if (disc == 0) {
    // Critically damped (also the undamped rigid-body mode, sigma = k = 0): h = t
    // e^{-sigma t}.
    const double e = std::exp(-sigma * t);
    r.displacement = t * e;
    r.velocity = e * (1 - sigma * t);
  } else {
    // Over-damped: h = exp(-sigma t) sinh(mu t) / mu.
    const double mu = std::sqrt(disc);
    if (mu * t < 20) {
      const double e = std::exp(-sigma * t), sh = std::sinh(mu * t),
                   ch = std::cosh(mu * t);
      r.displacement = e * sh / mu;
      r.velocity = e * (ch - sigma * sh / mu);
    } else {  // exp(-sigma t) sinh(mu t) would overflow in parts; the slow root dominates
      const double r1 = -sigma + mu, r2 = -sigma - mu;
      const double e1 = std::exp(r1 * t), e2 = std::exp(r2 * t);
      r.displacement = (e1 - e2) / (2 * mu);
      r.velocity = (r1 * e1 - r2 * e2) / (2 * mu);
    }
  }
  // The equation of motion for t > 0 (and its limit at 0+).
  r.acceleration = -c * r.velocity - k * r.displacement;
  return r;
}

TimeResponse SimulateImpulseResponse(const Modes& modes, const Eigen::VectorXd& impulse,
                                     const TimeResponseOptions& options) {
  ThrowIfInvalid(options.Validate(), "time_response");
  const int n = static_cast<int>(modes.shapes.rows());
  const int num_modes = modes.size();
  if (num_modes == 0 || modes.shapes.cols() != num_modes) {
    std::ostringstream msg;
    msg << modes.shapes.cols() << " shapes for " << num_modes
        << " eigenvalues; expected one shape per eigenvalue and at least one mode";
    throw InputError("time_response.modes", msg.str());
  }
  if (!modes.shapes.allFinite() || !modes.eigenvalues.allFinite()) {
    throw InputError("time_response.modes", "has a NaN or infinite entry");
  }
  if (impulse.size() != n) {
    std::ostringstream msg;
    msg << "has " << impulse.size() << " entries; expected one per model DOF (" << n
        << ")";
    throw InputError("time_response.impulse", msg.str());
  }
  if (!impulse.allFinite()) {
    throw InputError("time_response.impulse", "has a NaN or infinite entry");
  }
  std::vector<int> sensors = options.sensor_dofs;
  if (sensors.empty()) {
    for (int i = 0; i < n; ++i) sensors.push_back(i);
  }
  for (std::size_t i = 0; i < sensors.size(); ++i) {
    if (sensors[i] >= n) {
      std::ostringstream msg;
      msg << "entry " << i + 1 << " is DOF " << sensors[i] << ", outside the model's "
          << n << " DOFs";
      throw InputError("time_response.sensor_dofs", msg.str());
    }
  }

  // Modal damping: viscous coefficient c_j = 2 zeta_j w_j of each modal equation.
  Eigen::VectorXd omega(num_modes), c(num_modes), zeta(num_modes);
  for (int j = 0; j < num_modes; ++j) omega[j] = Omega(modes.eigenvalues[j]);
  if (options.damping == DampingModel::kModal) {
    if (!options.damping_ratios.empty() &&
        static_cast<int>(options.damping_ratios.size()) != num_modes) {
      std::ostringstream msg;
      msg << options.damping_ratios.size() << " ratios for the " << num_modes
          << " modes used; give one per mode (or none and set damping_ratio)";
      throw InputError("time_response.damping_ratios", msg.str());
    }
    for (int j = 0; j < num_modes; ++j) {
      zeta[j] = options.damping_ratios.empty() ? options.damping_ratio
                                               : options.damping_ratios[j];
      c[j] = 2 * zeta[j] * omega[j];
    }
  } else {
    for (int j = 0; j < num_modes; ++j) {
      c[j] = options.rayleigh_alpha + options.rayleigh_beta * omega[j] * omega[j];
      zeta[j] = omega[j] > 0 ? c[j] / (2 * omega[j])
                             : (c[j] > 0 ? std::numeric_limits<double>::infinity() : 0.0);
    }
  }

  const int num_channels = static_cast<int>(sensors.size());
  const int num_samples = options.NumSamples();
  // Participation of mode j at channel i: phi_j(sensor i) * (phi_j' F).
  const Eigen::VectorXd modal_force = modes.shapes.transpose() * impulse;
  Eigen::MatrixXd gain(num_channels, num_modes);
  for (int i = 0; i < num_channels; ++i) {
    gain.row(i) = modes.shapes.row(sensors[i]).cwiseProduct(modal_force.transpose());
  }

  TimeResponse out;
  out.quantity = options.quantity;
  out.sample_rate_hz = options.sample_rate_hz;
  out.sensor_dofs = sensors;
  out.frequencies_hz = omega / (2 * M_PI);
  out.damping_ratios = zeta;
  out.data = Eigen::MatrixXd::Zero(num_channels, num_samples);
  Eigen::VectorXd q(num_modes);
  for (int s = 0; s < num_samples; ++s) {
    const double t = static_cast<double>(s) / options.sample_rate_hz;
    for (int j = 0; j < num_modes; ++j) {
      const OscillatorResponse h = UnitImpulseResponse(c[j], omega[j] * omega[j], t);
      q[j] = options.quantity == ResponseQuantity::kDisplacement ? h.displacement
             : options.quantity == ResponseQuantity::kVelocity   ? h.velocity
                                                                 : h.acceleration;
    }
    out.data.col(s) = gain * q;
  }

  out.noise_std = Eigen::VectorXd::Zero(num_channels);
  if (options.noise_level > 0) {
    std::mt19937_64 rng(options.noise_seed);
    std::normal_distribution<double> gauss(0.0, 1.0);
    for (int i = 0; i < num_channels; ++i) {
      const double rms = std::sqrt(out.data.row(i).squaredNorm() / num_samples);
      out.noise_std[i] = options.noise_level * rms;
    }
    // Channel by channel, each channel's samples in time order.
    for (int i = 0; i < num_channels; ++i) {
      for (int s = 0; s < num_samples; ++s)
        out.data(i, s) += out.noise_std[i] * gauss(rng);
    }
  }
  return out;
}

TimeResponse SimulateImpulseResponse(const SparseMatrix& stiffness,
                                     const SparseMatrix& mass,
                                     const Eigen::VectorXd& impulse,
                                     const TimeResponseOptions& options) {
  ThrowIfInvalid(options.Validate(), "time_response");
  if (impulse.size() != stiffness.rows()) {
    std::ostringstream msg;
    msg << "has " << impulse.size() << " entries; expected one per model DOF ("
        << stiffness.rows() << ")";
    throw InputError("time_response.impulse", msg.str());
  }
  return SimulateImpulseResponse(SolveModes(stiffness, mass, options.eigen), impulse,
                                 options);
}

TimeResponse SimulateImpulseResponse(const SparseMatrix& stiffness,
                                     const SparseMatrix& mass, int input_dof,
                                     const TimeResponseOptions& options) {
  const Eigen::Index n = stiffness.rows();
  if (input_dof < 0 || input_dof >= n) {
    std::ostringstream msg;
    msg << "DOF " << input_dof << " is outside the model's " << n << " DOFs (0-based)";
    throw InputError("time_response.input_dof", msg.str());
  }
  Eigen::VectorXd impulse = Eigen::VectorXd::Zero(n);
  impulse[input_dof] = 1.0;
  return SimulateImpulseResponse(stiffness, mass, impulse, options);
}

}  // namespace femup
