#include "femup/core/sysid/era.h"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "femup/core/enum_names.h"
#include "femup/core/errors.h"
#include "femup/core/linalg/modal.h"

namespace femup {
namespace {

using Complex = std::complex<double>;

// Checks the records; returns the number of samples.
int CheckRecords(const std::vector<Eigen::MatrixXd>& refs, double sample_rate_hz,
                 const std::string& prefix) {
  if (!(sample_rate_hz > 0) || !std::isfinite(sample_rate_hz)) {
    std::ostringstream msg;
    msg << "must be positive and finite, got " << sample_rate_hz;
    throw InputError(prefix + ".sample_rate_hz", msg.str());
  }
  if (refs.empty()) throw InputError(prefix + ".records", "no reference record is given");
  for (std::size_t j = 0; j < refs.size(); ++j) {
    if (refs[j].rows() == 0 || refs[j].cols() == 0) {
      throw InputError(prefix + ".records", "record " + std::to_string(j + 1) +
                                                " has no channel or no sample");
    }
    if (refs[j].rows() != refs[0].rows() || refs[j].cols() != refs[0].cols()) {
      std::ostringstream msg;
      msg << "record " << j + 1 << " is " << refs[j].rows() << " x " << refs[j].cols()
          << " but record 1 is " << refs[0].rows() << " x " << refs[0].cols()
          << "; every reference needs the same channels and samples";
      throw InputError(prefix + ".records", msg.str());
    }
    if (!refs[j].allFinite()) {
      throw InputError(prefix + ".records", "record " + std::to_string(j + 1) +
                                                " has a NaN or infinite sample");
    }
  }
  return static_cast<int>(refs[0].cols());
}

struct HankelSize {
  int rows = 0;     // block rows r
  int columns = 0;  // block columns s
};

HankelSize ChooseSize(const EraOptions& o, int channels, int references, int samples,
                      int order, const std::string& prefix) {
  const int avail = samples - o.first_sample;  // Markov parameters available
  const int cap_rows = std::max(1, o.max_hankel_size / channels);
  const int cap_cols = std::max(1, o.max_hankel_size / references);
  HankelSize h;
  if (o.block_rows > 0 && o.block_columns > 0) {
    h.rows = o.block_rows;
    h.columns = o.block_columns;
  } else if (o.block_rows > 0) {
    h.rows = o.block_rows;
    h.columns = std::min(avail - h.rows, cap_cols);
  } else if (o.block_columns > 0) {
    h.columns = o.block_columns;
    h.rows = std::min(avail - h.columns, cap_rows);
  } else {
    // About square: r * channels ~ s * references with r + s = avail.
    h.rows = static_cast<int>(
        std::lround(static_cast<double>(avail) * references / (channels + references)));
    h.rows = std::max(1, std::min(h.rows, cap_rows));
    h.columns = std::min(avail - h.rows, cap_cols);
  }
  if (h.rows < 1 || h.columns < 1 || h.rows + h.columns > avail) {
    std::ostringstream msg;
    msg << "the Hankel matrices need block_rows + block_columns <= samples - first_sample"
        << " (" << samples << " - " << o.first_sample << " = " << avail << "), with both"
        << " >= 1; got " << h.rows << " + " << h.columns;
    throw InputError(prefix + ".records", msg.str());
  }
  const int bound = std::min(h.rows * channels, h.columns * references);
  if (order > bound) {
    std::ostringstream msg;
    msg << order << " is above the Hankel's rank bound " << bound << " (" << h.rows
        << " block rows x " << channels << " channels, " << h.columns
        << " block columns x " << references
        << " references); use more samples or a lower order";
    throw InputError(prefix + ".order", msg.str());
  }
  return h;
}

// H(shift): block (i, j) = Y_{first + i + j + shift}, Y_k(:, ref) = refs[ref].col(k).
Eigen::MatrixXd Hankel(const std::vector<Eigen::MatrixXd>& refs, int first, HankelSize h,
                       int shift) {
  const int m = static_cast<int>(refs[0].rows());
  const int p = static_cast<int>(refs.size());
  Eigen::MatrixXd out(h.rows * m, h.columns * p);
  for (int j = 0; j < h.columns; ++j) {
    for (int b = 0; b < p; ++b) {
      for (int i = 0; i < h.rows; ++i) {
        out.block(i * m, j * p + b, m, 1) = refs[b].col(first + i + j + shift);
      }
    }
  }
  return out;
}

// The SVD of H(0) and the projection of H(1) on its leading singular vectors,
// enough to realise every order up to max_order.
struct Factorisation {
  int channels = 0, references = 0;
  HankelSize size;
  int first_sample = 0;
  double sample_rate_hz = 0;
  Eigen::VectorXd singular_values;  // all
  Eigen::MatrixXd u, v;             // leading max_order columns
  Eigen::MatrixXd g;                // U' H(1) V, max_order x max_order
};

Factorisation Factorise(const std::vector<Eigen::MatrixXd>& refs, double sample_rate_hz,
                        const EraOptions& options, int max_order,
                        const std::string& prefix) {
  const int samples = CheckRecords(refs, sample_rate_hz, prefix);
  Factorisation f;
  f.channels = static_cast<int>(refs[0].rows());
  f.references = static_cast<int>(refs.size());
  f.size = ChooseSize(options, f.channels, f.references, samples, max_order, prefix);
  f.first_sample = options.first_sample;
  f.sample_rate_hz = sample_rate_hz;
  const Eigen::MatrixXd h0 = Hankel(refs, options.first_sample, f.size, 0);
  const Eigen::MatrixXd h1 = Hankel(refs, options.first_sample, f.size, 1);
  Eigen::BDCSVD<Eigen::MatrixXd> svd(h0, Eigen::ComputeThinU | Eigen::ComputeThinV);
  f.singular_values = svd.singularValues();
  if (!(f.singular_values[max_order - 1] > 0)) {
    std::ostringstream msg;
    msg << "singular value " << max_order << " of H(0) is zero: the records hold fewer"
        << " than " << max_order << " independent states; lower the order";
    throw InputError(prefix + ".order", msg.str());
  }
  f.u = svd.matrixU().leftCols(max_order);
  f.v = svd.matrixV().leftCols(max_order);
  f.g = f.u.transpose() * h1 * f.v;
  return f;
}

// EMAC of one side: `first` the block at time shift 0, `last` the block at
// shift `steps`, extrapolated with z^steps; weights |first_i|^2.
double EmacSide(const Eigen::VectorXcd& first, const Eigen::VectorXcd& last, Complex z,
                int steps) {
  const Complex growth = std::pow(z, steps);
  double num = 0, den = 0;
  for (Eigen::Index i = 0; i < first.size(); ++i) {
    const double w = std::norm(first[i]);
    den += w;
    const Complex predicted = first[i] * growth;
    const double a = std::abs(predicted), b = std::abs(last[i]);
    if (a == 0 || b == 0) continue;
    const double ratio = std::min(a / b, b / a);
    const double phase = std::abs(std::arg(last[i] / predicted));  // in [0, pi]
    const double weight = std::max(0.0, 1.0 - phase / (M_PI / 4));
    num += w * ratio * weight;
  }
  return den > 0 ? num / den : 0.0;
}

// Fills complex_shape, shape and mpc of `mode` from phi = C psi.
void SetShape(const Eigen::VectorXcd& phi, IdentifiedMode* mode) {
  const Complex ptp = phi.transpose() * phi;  // phi^T phi (no conjugate)
  const double php = phi.squaredNorm();       // phi^H phi
  mode->mpc = php > 0 ? std::norm(ptp) / (php * php) : 0.0;
  // Rotation maximising |Re(e^{i theta} phi)|^2 = (php + Re(e^{2 i theta} ptp)) / 2.
  const double theta = std::abs(ptp) > 0 ? -0.5 * std::arg(ptp) : 0.0;
  Eigen::VectorXcd rotated = phi * std::polar(1.0, theta);
  if (php > 0) rotated /= std::sqrt(php);
  Eigen::VectorXd real = rotated.real();
  Eigen::Index imax = 0;
  real.cwiseAbs().maxCoeff(&imax);
  if (real[imax] < 0) {
    real = -real;
    rotated = -rotated;
  }
  const double norm = real.norm();
  mode->complex_shape = rotated;
  mode->shape = norm > 0 ? Eigen::VectorXd(real / norm) : real;
}

struct Realisation {
  Eigen::MatrixXd a, b, c;
  std::vector<IdentifiedMode> poles;  // one per real eigenvalue or conjugate pair
};

Realisation Realise(const Factorisation& f, int n, const EraOptions& options) {
  const int m = f.channels, p = f.references, r = f.size.rows, s = f.size.columns;
  const Eigen::VectorXd sqrt_s = f.singular_values.head(n).cwiseSqrt();
  const Eigen::VectorXd inv_sqrt_s = sqrt_s.cwiseInverse();
  Realisation out;
  out.a = inv_sqrt_s.asDiagonal() * f.g.topLeftCorner(n, n) * inv_sqrt_s.asDiagonal();
  const Eigen::MatrixXd obs = f.u.leftCols(n) * sqrt_s.asDiagonal();  // r m x n
  const Eigen::MatrixXd ctr =
      sqrt_s.asDiagonal() * f.v.leftCols(n).transpose();  // n x s p
  out.c = obs.topRows(m);
  out.b = ctr.leftCols(p);

  Eigen::EigenSolver<Eigen::MatrixXd> es(out.a);
  if (es.info() != Eigen::Success) {
    throw InputError("era", "the eigenvalues of the realised A did not converge");
  }
  const Eigen::VectorXcd z = es.eigenvalues();
  const Eigen::MatrixXcd psi = es.eigenvectors();
  const Eigen::MatrixXcd psi_inv = psi.partialPivLu().inverse();
  const Eigen::MatrixXcd modal_obs = obs.cast<Complex>() * psi;      // r m x n
  const Eigen::MatrixXcd modal_ctr = psi_inv * ctr.cast<Complex>();  // n x s p
  const double nyquist = 0.5 * f.sample_rate_hz;
  const int span = r + s;  // samples H(0) and H(1) span

  double total_energy = 0;
  std::vector<double> energy;
  for (int j = 0; j < n; ++j) {
    if (z[j].imag() < 0) continue;  // the conjugate of a pole kept below
    const bool oscillatory = z[j].imag() > 0;
    IdentifiedMode mode;
    const Eigen::VectorXcd c_j = modal_obs.col(j).head(m);
    const Eigen::VectorXcd b_j = modal_ctr.row(j).head(p).transpose();
    mode.pole = z[j] == 0.0 ? Complex(-std::numeric_limits<double>::infinity(), 0)
                            : std::log(z[j]) * f.sample_rate_hz;
    const double magnitude = std::abs(mode.pole);
    mode.frequency_hz = std::isfinite(magnitude) ? magnitude / (2 * M_PI) : 0.0;
    mode.damping_ratio =
        magnitude > 0 && std::isfinite(magnitude) ? -mode.pole.real() / magnitude : 1.0;
    SetShape(c_j, &mode);
    mode.emac = EmacSide(c_j, modal_obs.col(j).tail(m), z[j], r - 1) *
                EmacSide(b_j, modal_ctr.row(j).tail(p).transpose(), z[j], s - 1);
    // Energy of the mode's part of the realised Markov parameters.
    const Eigen::MatrixXcd cb = c_j * b_j.transpose();
    double e = 0;
    Complex power(1.0, 0.0);
    for (int k = 0; k < span; ++k) {
      const Eigen::MatrixXd part = (oscillatory ? 2.0 : 1.0) * (cb * power).real();
      e += part.squaredNorm();
      power *= z[j];
    }
    energy.push_back(e);
    total_energy += e;

    if (!oscillatory) {
      mode.status = PoleStatus::kNotOscillatory;
    } else if (!(mode.frequency_hz > 0) || !(mode.frequency_hz < nyquist)) {
      mode.status = PoleStatus::kOutOfBand;
    } else if (mode.damping_ratio < 0) {
      mode.status = PoleStatus::kNegativeDamping;
    } else if (mode.damping_ratio > options.max_damping_ratio) {
      mode.status = PoleStatus::kExcessiveDamping;
    } else if (mode.emac < options.min_emac) {
      mode.status = PoleStatus::kLowEmac;
    } else if (mode.mpc < options.min_mpc) {
      mode.status = PoleStatus::kLowMpc;
    }
    out.poles.push_back(mode);
  }
  for (std::size_t j = 0; j < out.poles.size(); ++j) {
    out.poles[j].contribution = total_energy > 0 ? energy[j] / total_energy : 0.0;
  }
  std::stable_sort(out.poles.begin(), out.poles.end(),
                   [](const IdentifiedMode& x, const IdentifiedMode& y) {
                     return x.frequency_hz < y.frequency_hz;
                   });
  return out;
}

}  // namespace

constexpr EnumName<PoleStatus> kPoleStatusNames[] = {
    {PoleStatus::kAccepted, "accepted"},
    {PoleStatus::kNotOscillatory, "not_oscillatory"},
    {PoleStatus::kNegativeDamping, "negative_damping"},
    {PoleStatus::kExcessiveDamping, "excessive_damping"},
    {PoleStatus::kOutOfBand, "out_of_band"},
    {PoleStatus::kLowEmac, "low_emac"},
    {PoleStatus::kLowMpc, "low_mpc"},
};

const char* ToString(PoleStatus status) { return NameIn(kPoleStatusNames, status, "?"); }

namespace {

// Checks shared by EraOptions and StabilisationOptions::era (order excluded).
Invalid ValidateHankelAndLimits(const EraOptions& o) {
  std::string field;
  std::ostringstream msg;
  auto at = [&](const char* name) -> std::ostream& {
    field = name;
    return msg;
  };
  if (o.block_rows < 0) {
    at("block_rows") << "must be >= 0 (0 = automatic), got " << o.block_rows;
  } else if (o.block_columns < 0) {
    at("block_columns") << "must be >= 0 (0 = automatic), got " << o.block_columns;
  } else if (o.max_hankel_size < 1) {
    at("max_hankel_size") << "must be >= 1, got " << o.max_hankel_size;
  } else if (o.first_sample < 0) {
    at("first_sample") << "must be >= 0, got " << o.first_sample;
  } else if (!(o.max_damping_ratio > 0) || !std::isfinite(o.max_damping_ratio)) {
    at("max_damping_ratio") << "must be positive and finite, got " << o.max_damping_ratio;
  } else if (!(o.min_emac >= 0 && o.min_emac <= 1)) {
    at("min_emac") << "must be in [0, 1], got " << o.min_emac;
  } else if (!(o.min_mpc >= 0 && o.min_mpc <= 1)) {
    at("min_mpc") << "must be in [0, 1], got " << o.min_mpc;
  }
  return {field, msg.str()};
}

}  // namespace

Invalid EraOptions::Validate() const {
  if (order < 1) {
    return {"order", "must be >= 1 (2 states per mode), got " + std::to_string(order)};
  }
  return ValidateHankelAndLimits(*this);
}

Invalid StabilisationOptions::Validate() const {
  std::string field;
  std::ostringstream msg;
  auto at = [&](const char* name) -> std::ostream& {
    field = name;
    return msg;
  };
  if (min_order < 1) {
    at("min_order") << "must be >= 1, got " << min_order;
  } else if (max_order < min_order) {
    at("max_order") << "must be >= min_order (" << min_order << "), got " << max_order;
  } else if (order_step < 1) {
    at("order_step") << "must be >= 1, got " << order_step;
  } else if (!(frequency_tolerance > 0) || !std::isfinite(frequency_tolerance)) {
    at("frequency_tolerance") << "must be positive (relative, 0.01 = 1 %), got "
                              << frequency_tolerance;
  } else if (!(damping_tolerance > 0) || !std::isfinite(damping_tolerance)) {
    at("damping_tolerance") << "must be positive (relative, 0.05 = 5 %), got "
                            << damping_tolerance;
  } else if (!(mac_tolerance >= 0 && mac_tolerance <= 1)) {
    at("mac_tolerance") << "must be in [0, 1], got " << mac_tolerance;
  } else {
    return ValidateHankelAndLimits(era).Under("era");
  }
  return {field, msg.str()};
}

EraResult RunEra(const std::vector<Eigen::MatrixXd>& references, double sample_rate_hz,
                 const EraOptions& options) {
  ThrowIfInvalid(options.Validate(), "era");
  const Factorisation f =
      Factorise(references, sample_rate_hz, options, options.order, "era");
  Realisation r = Realise(f, options.order, options);
  EraResult out;
  out.order = options.order;
  out.sample_rate_hz = sample_rate_hz;
  out.block_rows = f.size.rows;
  out.block_columns = f.size.columns;
  out.singular_values = f.singular_values;
  out.a = std::move(r.a);
  out.b = std::move(r.b);
  out.c = std::move(r.c);
  for (IdentifiedMode& mode : r.poles) {
    (mode.status == PoleStatus::kAccepted ? out.modes : out.rejected)
        .push_back(std::move(mode));
  }
  return out;
}

EraResult RunEra(const Eigen::MatrixXd& records, double sample_rate_hz,
                 const EraOptions& options) {
  return RunEra(std::vector<Eigen::MatrixXd>{records}, sample_rate_hz, options);
}

StabilisationDiagram BuildStabilisationDiagram(
    const std::vector<Eigen::MatrixXd>& references, double sample_rate_hz,
    const StabilisationOptions& options) {
  ThrowIfInvalid(options.Validate(), "stabilisation");
  const Factorisation f = Factorise(references, sample_rate_hz, options.era,
                                    options.max_order, "stabilisation");
  StabilisationDiagram out;
  out.sample_rate_hz = sample_rate_hz;
  out.block_rows = f.size.rows;
  out.block_columns = f.size.columns;
  out.singular_values = f.singular_values;
  for (int n = options.min_order; n <= options.max_order; n += options.order_step) {
    DiagramOrder level;
    level.order = n;
    for (IdentifiedMode& mode : Realise(f, n, options.era).poles) {
      DiagramPole pole;
      pole.mode = std::move(mode);
      level.poles.push_back(std::move(pole));
    }
    const DiagramOrder* previous = out.orders.empty() ? nullptr : &out.orders.back();
    for (DiagramPole& pole : level.poles) {
      if (pole.mode.status != PoleStatus::kAccepted) continue;
      pole.stable_run = 1;
      if (previous == nullptr) continue;
      double best = std::numeric_limits<double>::infinity();
      for (std::size_t q = 0; q < previous->poles.size(); ++q) {
        const IdentifiedMode& other = previous->poles[q].mode;
        if (other.status != PoleStatus::kAccepted) continue;
        const double df = std::abs(other.frequency_hz - pole.mode.frequency_hz) /
                          pole.mode.frequency_hz;
        if (df < best) {
          best = df;
          pole.previous = static_cast<int>(q);
        }
      }
      if (pole.previous < 0) continue;
      const DiagramPole& match = previous->poles[pole.previous];
      pole.stable_frequency = best <= options.frequency_tolerance;
      pole.stable_damping =
          std::abs(match.mode.damping_ratio - pole.mode.damping_ratio) <=
          options.damping_tolerance * std::abs(pole.mode.damping_ratio);
      pole.stable_shape = Mac(match.mode.shape, pole.mode.shape) >= options.mac_tolerance;
      if (pole.stable()) pole.stable_run = match.stable_run + 1;
    }
    out.orders.push_back(std::move(level));
  }
  return out;
}

StabilisationDiagram BuildStabilisationDiagram(const Eigen::MatrixXd& records,
                                               double sample_rate_hz,
                                               const StabilisationOptions& options) {
  return BuildStabilisationDiagram(std::vector<Eigen::MatrixXd>{records}, sample_rate_hz,
                                   options);
}

std::vector<StableMode> PickStableModes(const StabilisationDiagram& diagram,
                                        const StabilisationOptions& options,
                                        int min_consecutive) {
  ThrowIfInvalid(options.Validate(), "stabilisation");
  if (min_consecutive < 1) {
    throw InputError("stabilisation.min_consecutive",
                     "must be >= 1, got " + std::to_string(min_consecutive));
  }
  struct Ref {
    int level, index;
  };
  std::vector<Ref> candidates;
  for (std::size_t l = 0; l < diagram.orders.size(); ++l) {
    const std::vector<DiagramPole>& poles = diagram.orders[l].poles;
    for (std::size_t i = 0; i < poles.size(); ++i) {
      if (poles[i].mode.status == PoleStatus::kAccepted &&
          poles[i].stable_run >= min_consecutive) {
        candidates.push_back({static_cast<int>(l), static_cast<int>(i)});
      }
    }
  }
  auto pole_of = [&](const Ref& ref) -> const DiagramPole& {
    return diagram.orders[ref.level].poles[ref.index];
  };
  // Longest run first, then the highest order.
  std::stable_sort(candidates.begin(), candidates.end(), [&](const Ref& x, const Ref& y) {
    if (pole_of(x).stable_run != pole_of(y).stable_run)
      return pole_of(x).stable_run > pole_of(y).stable_run;
    return x.level > y.level;
  });
  // group[level][index]: the group a pole belongs to, -1 = none yet.
  std::vector<std::vector<int>> group(diagram.orders.size());
  for (std::size_t l = 0; l < diagram.orders.size(); ++l)
    group[l].assign(diagram.orders[l].poles.size(), -1);
  std::vector<Ref> representatives;
  std::vector<std::vector<Ref>> members;
  for (const Ref& ref : candidates) {
    int g = group[ref.level][ref.index];
    if (g < 0) {
      const IdentifiedMode& mode = pole_of(ref).mode;
      for (std::size_t k = 0; k < representatives.size() && g < 0; ++k) {
        const IdentifiedMode& rep = pole_of(representatives[k]).mode;
        if (std::abs(rep.frequency_hz - mode.frequency_hz) <=
                options.frequency_tolerance * rep.frequency_hz &&
            Mac(rep.shape, mode.shape) >= options.mac_tolerance) {
          g = static_cast<int>(k);
        }
      }
    }
    if (g < 0) {
      g = static_cast<int>(representatives.size());
      representatives.push_back(ref);
      members.emplace_back();
      // The representative's chain of matches belongs to its group.
      Ref walk = ref;
      while (walk.level >= 0 && group[walk.level][walk.index] < 0) {
        group[walk.level][walk.index] = g;
        const int prev = pole_of(walk).previous;
        if (prev < 0 || walk.level == 0) break;
        walk = {walk.level - 1, prev};
      }
    }
    group[ref.level][ref.index] = g;
    members[g].push_back(ref);
  }
  std::vector<StableMode> out;
  for (std::size_t g = 0; g < representatives.size(); ++g) {
    const DiagramPole& rep = pole_of(representatives[g]);
    StableMode mode;
    mode.mode = rep.mode;
    mode.order = diagram.orders[representatives[g].level].order;
    mode.stable_run = rep.stable_run;
    mode.num_poles = static_cast<int>(members[g].size());
    double sf = 0, sd = 0;
    for (const Ref& ref : members[g]) {
      sf += pole_of(ref).mode.frequency_hz;
      sd += pole_of(ref).mode.damping_ratio;
    }
    const double mf = sf / mode.num_poles, md = sd / mode.num_poles;
    double vf = 0, vd = 0;
    for (const Ref& ref : members[g]) {
      vf += std::pow(pole_of(ref).mode.frequency_hz - mf, 2);
      vd += std::pow(pole_of(ref).mode.damping_ratio - md, 2);
    }
    mode.frequency_std_hz = std::sqrt(vf / mode.num_poles);
    mode.damping_std = std::sqrt(vd / mode.num_poles);
    out.push_back(std::move(mode));
  }
  std::sort(out.begin(), out.end(), [](const StableMode& x, const StableMode& y) {
    return x.mode.frequency_hz < y.mode.frequency_hz;
  });
  return out;
}

}  // namespace femup
