#include "femup/evaluation/benchmark_oracle.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "benchmark_generator.h"
#include "femup/core/errors.h"
#include "femup/core/linalg/banded_eigen.h"
#include "femup/problems/effect_fit.h"
#include "femup/solvers/sampled_evidence.h"

namespace femup {

namespace {

using benchmark_generator::Ranges;
using benchmark_generator::TrueEffect;

const double kTwoPi = 2 * std::acos(-1.0);
const double kMinusInf = -std::numeric_limits<double>::infinity();

double Lerp(double lo, double hi, double u) { return lo + (hi - lo) * u; }
double LogLerp(double lo, double hi, double u) {
  return std::exp(Lerp(std::log(lo), std::log(hi), u));
}

// A part of a kind's prior where the generator makes a discrete choice: its
// weight within the kind and the number of uniform draws it integrates over
// (the last one always the size).
struct SubClass {
  std::string kind;
  double weight = 1;
  int choice = 0;  // added_mass 1: fade; support 1: rotation only; material: -1 / +1
  int size = 0;    // 0: absolute sizes, 1: at the noise level, 2: above it
  int dims = 1;
};

std::vector<SubClass> SubClasses(const std::string& kind, const std::string& sizes) {
  std::vector<SubClass> forms;
  auto add = [&](int choice, double weight, int dims) {
    SubClass s;
    s.kind = kind;
    s.choice = choice;
    s.weight = weight;
    s.dims = dims;
    forms.push_back(s);
  };
  if (kind == "added_mass") {
    add(0, 1 - Ranges::kFadeShare, 2);  // depth, size
    add(1, Ranges::kFadeShare, 3);      // depth, fade, size
  } else if (kind == "support_flexibility") {
    add(0, Ranges::kBothShare, 2);      // ratio, size
    add(1, 1 - Ranges::kBothShare, 1);  // size
  } else if (kind == "attached_mass") {
    add(0, 1, 3);  // position, gyration, size
  } else if (kind == "stiffness_loss") {
    add(0, 1, 3);  // width, centre, size
  } else {
    add(-1, Ranges::kLowerShare, 1);
    add(1, 1 - Ranges::kLowerShare, 1);
  }
  std::vector<SubClass> out;
  for (SubClass s : forms) {
    if (sizes == "absolute") {
      out.push_back(s);
      continue;
    }
    SubClass weak = s, strong = s;
    weak.size = 1;
    weak.weight *= 1 - Ranges::kStrongShare;
    strong.size = 2;
    strong.weight *= Ranges::kStrongShare;
    out.push_back(weak);
    out.push_back(strong);
  }
  return out;
}

// What the oracle knows of a case: the generator's truth mesh of the study's
// beam, the measured modes and the stated noise.
struct CaseModel {
  CantileverSpec fine;
  double length = 0;
  int elements = 0;  // diagnosis mesh
  int modes = 0;
  std::vector<std::string> sensors;  // truth-mesh labels
  double sigma_f = 0, sigma_s = 0;
  Eigen::VectorXd measured_hz;
  Eigen::MatrixXd measured_shapes;  // sensors x modes, or empty
  Eigen::MatrixXd k0, m0;           // the nominal truth mesh's bending matrices
  std::vector<std::string> labels0;
  std::vector<int> rows0;    // the sensors' rows in them
  BandedEigenpairs nominal;  // its modes (vectors when there are shapes)
  Eigen::VectorXd f0;        // their frequencies
  std::string sizes;
};

// The effect a sub-class's uniform draws u stand for, and its target shift.
TrueEffect MakeEffect(const SubClass& sc, const Eigen::VectorXd& u, const CaseModel& cm,
                      double* target) {
  TrueEffect e;
  e.kind = sc.kind;
  const double l = cm.length;
  if (sc.kind == "added_mass") {
    e.a = Lerp(Ranges::kDepthMin, Ranges::kDepthMax, u[0]) * l;
    e.b = sc.choice == 1 ? Lerp(Ranges::kFadeMin, Ranges::kFadeMax, u[1]) * e.a : 0.0;
  } else if (sc.kind == "support_flexibility") {
    e.variant = sc.choice;
    e.a = sc.choice == 0 ? Lerp(Ranges::kRatioMin, Ranges::kRatioMax, u[0]) : 1.0;
  } else if (sc.kind == "attached_mass") {
    // One uniform for the element and the place in it: the integer and the
    // fractional part of u N are independent and uniform, as the generator's
    // two draws are.
    const int n = cm.elements - Ranges::kFirstElement;
    const double w = u[0] * n;
    const int k = std::min(static_cast<int>(std::floor(w)), n - 1);
    const double h = l / cm.elements;
    e.a = std::min(l, (Ranges::kFirstElement + k +
                       Lerp(Ranges::kInElementMin, Ranges::kInElementMax, w - k)) *
                          h);
    if (e.a > l) e.a = l - 0.3 * h;
    e.b = Lerp(Ranges::kGyrationMin, Ranges::kGyrationMax, u[1]);
  } else if (sc.kind == "stiffness_loss") {
    e.b = Lerp(Ranges::kWidthMin, Ranges::kWidthMax, u[0]) * l;
    e.a = Lerp(Ranges::kCentreMin, Ranges::kCentreMax, u[1]) * l;
  } else {
    e.a = sc.choice;
  }
  const double v = u[sc.dims - 1];
  if (sc.size == 0) {
    *target = LogLerp(Ranges::kAbsoluteMin, Ranges::kAbsoluteMax, v);
  } else if (sc.size == 1) {
    *target = LogLerp(Ranges::kWeakMin, Ranges::kWeakMax, v) * cm.sigma_f;
  } else {
    *target = LogLerp(Ranges::kStrongMin, Ranges::kStrongMax, v) * cm.sigma_f;
  }
  return e;
}

// The bending matrices of the truth mesh with effect e at strength s:
// K = ka + g(s) kd, M = ma + g(s) md, g(s) = s (1 / s for the support springs,
// whose stiffness is EI / (5 s L)).
struct AffineModel {
  Eigen::MatrixXd ka, kd, ma, md;
  bool inverse = false;
  std::vector<int> rows;  // the sensors' rows
  double G(double s) const { return inverse ? 1 / s : s; }
};

// The rows of `sensors` among the bending DOFs `labels` (false where one is
// missing).
bool SensorRows(const std::vector<std::string>& labels,
                const std::vector<std::string>& sensors, std::vector<int>* rows) {
  rows->clear();
  for (const std::string& sensor : sensors) {
    const auto it = std::find(labels.begin(), labels.end(), sensor);
    if (it == labels.end()) return false;
    rows->push_back(static_cast<int>(it - labels.begin()));
  }
  return true;
}

bool BuildAffine(const TrueEffect& e, const CaseModel& cm, AffineModel* am) {
  std::string why;
  Eigen::MatrixXd k1, m1;
  std::vector<std::string> labels1;
  CantileverSpec one = cm.fine;
  e.Apply(1.0, &one);
  if (!AssembleBendingMatrices(one, &k1, &m1, &labels1, &why)) return false;
  am->inverse = e.kind == "support_flexibility";
  if (!am->inverse) {
    // Same DOFs as the nominal mesh: its sensor rows hold.
    if (labels1 != cm.labels0) return false;
    am->rows = cm.rows0;
    am->kd = k1 - cm.k0;
    am->md = m1 - cm.m0;
    am->ka = cm.k0;
    am->ma = cm.m0;
    return true;
  }
  // g(1) = 1, g(1/2) = 2.
  Eigen::MatrixXd kh, mh;
  std::vector<std::string> labels;
  CantileverSpec half = cm.fine;
  e.Apply(0.5, &half);
  if (!AssembleBendingMatrices(half, &kh, &mh, &labels, &why) || labels != labels1 ||
      !SensorRows(labels1, cm.sensors, &am->rows))
    return false;
  am->kd = kh - k1;
  am->md = mh - m1;
  am->ka = k1 - am->kd;
  am->ma = m1 - am->md;
  return true;
}

bool Eigenpairs(const AffineModel& am, double s, int modes, bool vectors,
                BandedEigenpairs* out) {
  const double g = am.G(s);
  std::string why;
  return LowestBandedEigenpairs(am.ka + g * am.kd, am.ma + g * am.md, modes, vectors, out,
                                &why);
}

Eigen::VectorXd Hz(const Eigen::VectorXd& lambda) {
  return lambda.array().max(0.0).sqrt() / kTwoPi;
}

// The largest relative frequency shift at strength s (1 where unsolvable).
double Shift(const AffineModel& am, const CaseModel& cm, double s, int* evaluations) {
  BandedEigenpairs ep;
  ++*evaluations;
  if (!Eigenpairs(am, s, cm.modes, false, &ep)) return 1.0;
  return (Hz(ep.eigenvalues).array() / cm.f0.array() - 1).abs().maxCoeff();
}

// The generator's calibration (benchmark_generator::CalibrateStrength): the
// strength in (0, 1] whose largest shift is the target, 1 where even that falls
// short. Secant steps on log shift against log s (a straight line of slope 1
// for small effects), kept inside a bracket, until the log shift is within 1e-5
// of the target or the bracket is 1e-6 wide in log s. For a 1-sigma shift of
// 0.1 % the eigenvalues' rounding (up to a few 1e-7 of the lowest, measured
// against the directly assembled model) already moves the shift by ~1e-4 of
// itself, so there the bracket ends the search; either way the likelihood
// changes far less than the sampling error.
double Strength(const AffineModel& am, const CaseModel& cm, double target,
                int* evaluations) {
  const double top = Shift(am, cm, 1.0, evaluations);
  if (top <= target) return 1.0;
  auto h = [&](double x) {
    const double shift = Shift(am, cm, std::exp(x), evaluations);
    return shift > 0 ? std::log(shift / target) : -1e3;
  };
  // The generator's sizes shift a frequency by at least 1e-4 of itself, which
  // takes far more than 1e-12 of any family's full strength.
  double lo = std::log(1e-12), hi = 0;
  double x1 = 0, h1 = std::log(top / target);
  double x = std::max(lo + 1, std::log(target / top));
  for (int it = 0; it < 60; ++it) {
    const double hx = h(x);
    if (std::abs(hx) < 1e-5) break;
    (hx < 0 ? lo : hi) = x;
    if (hi - lo < 1e-6) break;
    double next = hx != h1 ? x - hx * (x - x1) / (hx - h1) : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    x1 = x;
    h1 = hx;
    x = next;
  }
  return std::exp(x);
}

// -2 log likelihood of the measured modes for truth eigenpairs (constants
// common to every model left out).
double Misfit(const CaseModel& cm, const BandedEigenpairs& ep,
              const std::vector<int>& rows) {
  const Eigen::VectorXd f = Hz(ep.eigenvalues);
  double chi2 = 0;
  for (int k = 0; k < cm.modes; ++k) {
    const double r = (cm.measured_hz[k] / f[k] - 1) / cm.sigma_f;
    chi2 += r * r + 2 * std::log(f[k] / cm.measured_hz[k]);
  }
  if (cm.measured_shapes.size() == 0) return chi2;
  Eigen::VectorXd t(static_cast<Eigen::Index>(rows.size()));
  for (int k = 0; k < cm.modes; ++k) {
    for (std::size_t i = 0; i < rows.size(); ++i)
      t[static_cast<Eigen::Index>(i)] = ep.vectors(rows[i], k);
    t /= t.cwiseAbs().maxCoeff();
    const Eigen::VectorXd y = cm.measured_shapes.col(k);
    const double plus = (y - t).squaredNorm() / (cm.sigma_s * cm.sigma_s);
    const double minus = (y + t).squaredNorm() / (cm.sigma_s * cm.sigma_s);
    // -2 log(e^{-plus/2} / 2 + e^{-minus/2} / 2), without the common log 2.
    const double low = std::min(plus, minus);
    chi2 += low - 2 * std::log1p(std::exp(-0.5 * std::abs(plus - minus)));
  }
  return chi2;
}

CaseModel ReadCase(const Study& study, const BenchmarkOptions& gen) {
  if (!study.cantilever)
    throw InputError(study.path,
                     "the oracle needs a cantilever model (a benchmark case)");
  if (study.measurements.size() != 1)
    throw InputError(study.path + ": measurements",
                     "a benchmark case has one measured state, not " +
                         std::to_string(study.measurements.size()));
  if (!study.diagnosis)
    throw InputError(study.path + ": diagnosis",
                     "a benchmark case states its noise in a diagnosis section");
  CaseModel cm;
  const CantileverSpec& nominal = *study.cantilever;
  cm.elements = static_cast<int>(nominal.node_heights.size()) - 1;
  if (cm.elements != gen.diagnosis_elements)
    throw InputError(study.path + ": model.elements",
                     "the generator's diagnosis mesh has " +
                         std::to_string(gen.diagnosis_elements) + " elements, not " +
                         std::to_string(cm.elements));
  cm.length = nominal.node_heights.back();
  cm.fine = nominal;
  cm.fine.node_heights = UniformHeights(cm.length, cm.elements * gen.refinement);
  const ModalData& md = study.measurements[0].data;
  cm.modes = md.num_modes();
  cm.measured_hz = md.frequencies_hz;
  cm.sigma_f = study.diagnosis->frequency_noise;
  cm.sigma_s = study.diagnosis->shape_noise;
  cm.sizes = gen.sizes;
  if (md.HasInterpolatedSensors())
    throw InputError(study.path + ": sensors",
                     "the oracle expects the generator's ux sensors on nodes, not "
                     "sensors between nodes");
  if (md.HasShapes()) {
    cm.measured_shapes = md.shapes;
    for (Eigen::Index i = 0; i < md.shapes.rows(); ++i) {
      const int dof = md.sensor_dofs.empty()
                          ? static_cast<int>(i)
                          : md.sensor_dofs[static_cast<std::size_t>(i)];
      const std::string& label =
          study.structure.dof_labels[static_cast<std::size_t>(dof)];
      const std::size_t colon = label.find(':');
      if (label.empty() || label[0] != 'n' || colon == std::string::npos ||
          label.substr(colon) != ":ux")
        throw InputError(
            study.path + ": sensors",
            "the oracle expects the generator's ux sensors, not '" + label + "'");
      const int node = std::stoi(label.substr(1, colon - 1));
      cm.sensors.push_back("n" + std::to_string(node * gen.refinement) + ":ux");
    }
  }
  std::string why;
  if (!AssembleBendingMatrices(cm.fine, &cm.k0, &cm.m0, &cm.labels0, &why))
    throw InputError(study.path + ": model", "the truth mesh cannot be built: " + why);
  if (!SensorRows(cm.labels0, cm.sensors, &cm.rows0))
    throw InputError(study.path + ": sensors",
                     "a sensor is not a bending DOF of the generator's truth mesh");
  if (!LowestBandedEigenpairs(cm.k0, cm.m0, cm.modes, cm.measured_shapes.size() > 0,
                              &cm.nominal, &why))
    throw InputError(study.path + ": model", "the truth mesh cannot be solved: " + why);
  cm.f0 = Hz(cm.nominal.eigenvalues);
  return cm;
}

double LogSumExp(const std::vector<double>& v) {
  double m = kMinusInf;
  for (double x : v) m = std::max(m, x);
  if (m == kMinusInf) return m;
  double s = 0;
  for (double x : v) s += std::exp(x - m);
  return m + std::log(s);
}

}  // namespace

Invalid OracleOptions::Validate() const {
  if (samples < 50) return {"samples", "expected at least 50"};
  const std::vector<std::string>& known = benchmark_generator::Kinds();
  for (const std::string& k : kinds)
    if (std::find(known.begin(), known.end(), k) == known.end())
      return {"kinds", "'" + k + "' is not a kind the generator draws"};
  return {};
}

OracleResult BayesOracle(const Study& study, const BenchmarkOptions& generator,
                         const OracleOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  ThrowIfInvalid(options.Validate(), "oracle");
  if (generator.suite != "single")
    throw InputError("oracle",
                     "the Bayes oracle models the single suite only (the mixed "
                     "suite's pairs are not modelled), not '" +
                         generator.suite + "'");
  const CaseModel cm = ReadCase(study, generator);
  OracleResult result;

  // "none": the nominal truth mesh.
  OracleClass none;
  none.label = "none";
  none.prior = Ranges::kSingleNoneShare;
  none.log_evidence = -0.5 * Misfit(cm, cm.nominal, cm.rows0);
  result.classes.push_back(none);
  ++result.evaluations;

  const std::vector<std::string>& all = benchmark_generator::Kinds();
  std::uint64_t stream = 0;
  for (const std::string& kind : all) {
    // Each kind keeps its own stream whichever kinds are asked for.
    const std::uint64_t first_stream = stream;
    stream += SubClasses(kind, cm.sizes).size();
    if (!options.kinds.empty() && std::find(options.kinds.begin(), options.kinds.end(),
                                            kind) == options.kinds.end())
      continue;
    std::uint64_t sub_stream = first_stream;
    OracleClass oc;
    oc.label = kind;
    oc.prior = (1 - Ranges::kSingleNoneShare) / static_cast<double>(all.size());
    std::vector<double> log_terms, se;
    std::vector<double> ess;
    for (const SubClass& sc : SubClasses(kind, cm.sizes)) {
      bool checked = false;
      int evaluations = 0;
      MisfitFunction misfit = [&](const Eigen::VectorXd& u, Eigen::VectorXd* chi2) {
        double target = 0;
        const TrueEffect e = MakeEffect(sc, u, cm, &target);
        AffineModel am;
        if (!BuildAffine(e, cm, &am)) return false;
        const double s = Strength(am, cm, target, &evaluations);
        BandedEigenpairs ep;
        ++evaluations;
        if (!Eigenpairs(am, s, cm.modes, cm.measured_shapes.size() > 0, &ep))
          return false;
        if (!checked) {
          // The affine shortcut against the model assembled at s.
          CantileverSpec direct = cm.fine;
          e.Apply(s, &direct);
          Eigen::MatrixXd k, m;
          std::vector<std::string> labels;
          std::string why;
          BandedEigenpairs dp;
          if (AssembleBendingMatrices(direct, &k, &m, &labels, &why) &&
              LowestBandedEigenpairs(k, m, cm.modes, false, &dp, &why)) {
            const double err =
                ((dp.eigenvalues - ep.eigenvalues).array() / dp.eigenvalues.array())
                    .abs()
                    .maxCoeff();
            result.affine_error = std::max(result.affine_error, err);
            checked = true;
          }
        }
        chi2->resize(1);
        (*chi2)[0] = Misfit(cm, ep, am.rows);
        return std::isfinite((*chi2)[0]);
      };
      SampledEvidenceOptions so;
      so.samples = options.samples;
      so.seed = options.seed;
      so.stream = sub_stream++;
      const EvidenceSamples samples =
          SampleEvidence(misfit, 1, Eigen::VectorXd::Zero(sc.dims),
                         Eigen::VectorXd::Ones(sc.dims), {}, so);
      result.evaluations += evaluations;
      const SampledLogEvidence z = LogEvidenceFromSamples(samples, {true});
      log_terms.push_back(std::log(sc.weight) + z.log_evidence);
      se.push_back(z.log_standard_error);
      ess.push_back(z.effective_samples);
    }
    oc.log_evidence = LogSumExp(log_terms);
    double var = 0, largest = -1;
    for (std::size_t i = 0; i < log_terms.size(); ++i) {
      const double r =
          oc.log_evidence == kMinusInf ? 0.0 : std::exp(log_terms[i] - oc.log_evidence);
      if (r > 0) var += r * r * se[i] * se[i];
      if (r > largest) {
        largest = r;
        oc.effective_samples = ess[i];
      }
    }
    oc.log_standard_error = std::sqrt(var);
    result.classes.push_back(oc);
  }

  std::vector<double> log_post;
  for (const OracleClass& c : result.classes)
    log_post.push_back(std::log(c.prior) + c.log_evidence);
  const double norm = LogSumExp(log_post);
  for (std::size_t i = 0; i < result.classes.size(); ++i)
    result.classes[i].probability = std::exp(log_post[i] - norm);
  std::stable_sort(result.classes.begin(), result.classes.end(),
                   [](const OracleClass& a, const OracleClass& b) {
                     return a.probability > b.probability;
                   });
  result.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return result;
}

}  // namespace femup
