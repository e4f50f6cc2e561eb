// The NIST StRD nonlinear models (one per formula, each written once over the
// scalar type; the table of datasets that use them) and what evaluates them:
// NistNonlinearProblem (residuals, automatic-differentiation Jacobian),
// NistNonlinearResiduals (long double) and NistNonlinearModelNames.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <unsupported/Eigen/AutoDiff>
#include <vector>

#include "femup/core/errors.h"
#include "femup/evaluation/nist_strd.h"

namespace femup {
namespace {

// ---------------------------------------------------------------------------
// The nonlinear models, each written once over the scalar type T (double, long
// double, or an automatic-differentiation scalar over double). `b` holds the
// parameters b1.. at b[0].., `x` one observation's predictors, in the real type
// R of T (double for the AD scalar).

using AD = Eigen::AutoDiffScalar<Eigen::VectorXd>;

template <typename T>
struct RealOf {
  using type = T;
};
template <>
struct RealOf<AD> {
  using type = double;
};
template <typename T>
using Real = typename RealOf<T>::type;

// a^e with both depending on the parameters.
template <typename T>
T Pow(const T& a, const T& e) {
  using std::exp;
  using std::log;
  return exp(e * log(a));
}
double Pow(double a, double e) { return std::pow(a, e); }
long double Pow(long double a, long double e) { return std::pow(a, e); }

// a^e with e a constant.
template <typename T>
T PowConst(const T& a, Real<T> e) {
  using std::pow;
  return pow(a, e);
}

// arctan: the AD scalar has atan2 only (atan(v) = atan2(v, 1)).
double Atan(double v) { return std::atan(v); }
long double Atan(long double v) { return std::atan(v); }
AD Atan(const AD& v) {
  return atan2(v, AD(1.0, Eigen::VectorXd::Zero(v.derivatives().size())));
}

template <typename T>
Real<T> Pi() {
  return static_cast<Real<T>>(3.141592653589793238462643383279L);
}

// y = b1 * (b2+x)**(-1/b3)
struct Bennett5 {
  template <typename T>
  static T f(const T* b, const Real<T>* x) {
    return b[0] * Pow(T(b[1] + x[0]), T(-1.0 / b[2]));
  }
};
// y = b1*(1-exp[-b2*x])  (BoxBOD and Misra1a)
struct BoxBOD {
  template <typename T>
  static T f(const T* b, const Real<T>* x) {
    using std::exp;
    return b[0] * (1.0 - exp(-b[1] * x[0]));
  }
};
// y = exp[-b1*x]/(b2+b3*x)  (Chwirut1, Chwirut2)
struct Chwirut {
  template <typename T>
  static T f(const T* b, const Real<T>* x) {
    using std::exp;
    return exp(-b[0] * x[0]) / (b[1] + b[2] * x[0]);
  }
};
// y = b1*x**b2
struct DanWood {
  template <typename T>
  static T f(const T* b, const Real<T>* x) {
    using std::exp;
    using std::log;
    return b[0] * exp(b[1] * log(x[0]));
  }
};
// y = b1 + b2*cos(2*pi*x/12) + b3*sin(2*pi*x/12) + b5*cos(2*pi*x/b4)
//        + b6*sin(2*pi*x/b4) + b8*cos(2*pi*x/b7) + b9*sin(2*pi*x/b7)
struct ENSO {
  template <typename T>
  static T f(const T* b, const Real<T>* x) {
    using std::cos;
    using std::sin;
    const Real<T> w = 2 * Pi<T>() * x[0];
    const T a4 = w / b[3];
    const T a7 = w / b[6];
    return b[0] + b[1] * cos(w / 12) + b[2] * sin(w / 12) + b[4] * cos(a4) +
           b[5] * sin(a4) + b[7] * cos(a7) + b[8] * sin(a7);
  }
};
// y = (b1/b2) * exp[-0.5*((x-b3)/b2)**2]
struct Eckerle4 {
  template <typename T>
  static T f(const T* b, const Real<T>* x) {
    using std::exp;
    const T u = (x[0] - b[2]) / b[1];
    return b[0] / b[1] * exp(-0.5 * u * u);
  }
};
// y = b1*exp(-b2*x) + b3*exp(-(x-b4)**2/b5**2) + b6*exp(-(x-b7)**2/b8**2)
struct Gauss {
  template <typename T>
  static T f(const T* b, const Real<T>* x) {
    using std::exp;
    const T u = (x[0] - b[3]) / b[4];
    const T v = (x[0] - b[6]) / b[7];
    return b[0] * exp(-b[1] * x[0]) + b[2] * exp(-(u * u)) + b[5] * exp(-(v * v));
  }
};
// y = (b1+b2*x+b3*x**2+b4*x**3) / (1+b5*x+b6*x**2+b7*x**3)  (Hahn1, Thurber)
struct CubicOverCubic {
  template <typename T>
  static T f(const T* b, const Real<T>* x) {
    const Real<T> t = x[0];
    return (b[0] + t * (b[1] + t * (b[2] + t * b[3]))) /
           (1.0 + t * (b[4] + t * (b[5] + t * b[6])));
  }
};
// y = (b1 + b2*x + b3*x**2) / (1 + b4*x + b5*x**2)
struct Kirby2 {
  template <typename T>
  static T f(const T* b, const Real<T>* x) {
    const Real<T> t = x[0];
    return (b[0] + t * (b[1] + t * b[2])) / (1.0 + t * (b[3] + t * b[4]));
  }
};
// y = b1*exp(-b2*x) + b3*exp(-b4*x) + b5*exp(-b6*x)  (Lanczos1-3)
struct Lanczos {
  template <typename T>
  static T f(const T* b, const Real<T>* x) {
    using std::exp;
    return b[0] * exp(-b[1] * x[0]) + b[2] * exp(-b[3] * x[0]) + b[4] * exp(-b[5] * x[0]);
  }
};
// y = b1*(x**2+x*b2) / (x**2+x*b3+b4)
struct MGH09 {
  template <typename T>
  static T f(const T* b, const Real<T>* x) {
    const Real<T> t = x[0];
    return b[0] * (t * t + t * b[1]) / (t * t + t * b[2] + b[3]);
  }
};
// y = b1 * exp[b2/(x+b3)]
struct MGH10 {
  template <typename T>
  static T f(const T* b, const Real<T>* x) {
    using std::exp;
    return b[0] * exp(b[1] / (x[0] + b[2]));
  }
};
// y = b1 + b2*exp[-x*b4] + b3*exp[-x*b5]
struct MGH17 {
  template <typename T>
  static T f(const T* b, const Real<T>* x) {
    using std::exp;
    return b[0] + b[1] * exp(-x[0] * b[3]) + b[2] * exp(-x[0] * b[4]);
  }
};
// y = b1 * (1-(1+b2*x/2)**(-2))
struct Misra1b {
  template <typename T>
  static T f(const T* b, const Real<T>* x) {
    return b[0] * (1.0 - PowConst(T(1.0 + b[1] * x[0] / 2), Real<T>(-2)));
  }
};
// y = b1 * (1-(1+2*b2*x)**(-.5))
struct Misra1c {
  template <typename T>
  static T f(const T* b, const Real<T>* x) {
    return b[0] * (1.0 - PowConst(T(1.0 + 2 * b[1] * x[0]), Real<T>(-0.5)));
  }
};
// y = b1*b2*x*((1+b2*x)**(-1))
struct Misra1d {
  template <typename T>
  static T f(const T* b, const Real<T>* x) {
    return b[0] * b[1] * x[0] / (1.0 + b[1] * x[0]);
  }
};
// log[y] = b1 - b2*x1 * exp[-b3*x2]  (the response is log(y))
struct Nelson {
  template <typename T>
  static T f(const T* b, const Real<T>* x) {
    using std::exp;
    return b[0] - b[1] * x[0] * exp(-b[2] * x[1]);
  }
};
// y = b1 / (1+exp[b2-b3*x])
struct Rat42 {
  template <typename T>
  static T f(const T* b, const Real<T>* x) {
    using std::exp;
    return b[0] / (1.0 + exp(b[1] - b[2] * x[0]));
  }
};
// y = b1 / ((1+exp[b2-b3*x])**(1/b4))
struct Rat43 {
  template <typename T>
  static T f(const T* b, const Real<T>* x) {
    using std::exp;
    return b[0] / Pow(T(1.0 + exp(b[1] - b[2] * x[0])), T(1.0 / b[3]));
  }
};
// y = b1 - b2*x - arctan[b3/(x-b4)]/pi
struct Roszman1 {
  template <typename T>
  static T f(const T* b, const Real<T>* x) {
    return b[0] - b[1] * x[0] - Atan(T(b[2] / (x[0] - b[3]))) / Pi<T>();
  }
};

struct Model {
  int num_parameters = 0;
  int num_predictors = 1;
  bool log_response = false;  // Nelson: the model is for log(y)
  double (*f_double)(const double*, const double*) = nullptr;
  long double (*f_long)(const long double*, const long double*) = nullptr;
  AD (*f_ad)(const AD*, const double*) = nullptr;
};

template <typename M>
Model Make(int num_parameters, int num_predictors = 1, bool log_response = false) {
  Model m;
  m.num_parameters = num_parameters;
  m.num_predictors = num_predictors;
  m.log_response = log_response;
  m.f_double = &M::template f<double>;
  m.f_long = &M::template f<long double>;
  m.f_ad = &M::template f<AD>;
  return m;
}

const std::map<std::string, Model>& Models() {
  static const std::map<std::string, Model> models = {
      {"Bennett5", Make<Bennett5>(3)},
      {"BoxBOD", Make<BoxBOD>(2)},
      {"Chwirut1", Make<Chwirut>(3)},
      {"Chwirut2", Make<Chwirut>(3)},
      {"DanWood", Make<DanWood>(2)},
      {"ENSO", Make<ENSO>(9)},
      {"Eckerle4", Make<Eckerle4>(3)},
      {"Gauss1", Make<Gauss>(8)},
      {"Gauss2", Make<Gauss>(8)},
      {"Gauss3", Make<Gauss>(8)},
      {"Hahn1", Make<CubicOverCubic>(7)},
      {"Kirby2", Make<Kirby2>(5)},
      {"Lanczos1", Make<Lanczos>(6)},
      {"Lanczos2", Make<Lanczos>(6)},
      {"Lanczos3", Make<Lanczos>(6)},
      {"MGH09", Make<MGH09>(4)},
      {"MGH10", Make<MGH10>(3)},
      {"MGH17", Make<MGH17>(5)},
      {"Misra1a", Make<BoxBOD>(2)},
      {"Misra1b", Make<Misra1b>(2)},
      {"Misra1c", Make<Misra1c>(2)},
      {"Misra1d", Make<Misra1d>(2)},
      {"Nelson", Make<Nelson>(3, 2, true)},
      {"Rat42", Make<Rat42>(3)},
      {"Rat43", Make<Rat43>(4)},
      {"Roszman1", Make<Roszman1>(4)},
      {"Thurber", Make<CubicOverCubic>(7)},
  };
  return models;
}

// The model for `data`, checked against its sizes.
const Model& ModelFor(const NistNonlinearDataset& data, const std::string& where) {
  const auto& models = Models();
  const auto it = models.find(data.name);
  if (it == models.end()) {
    std::string known;
    for (const auto& m : models) known += (known.empty() ? "" : ", ") + m.first;
    throw InputError(where, "no NIST model for dataset '" + data.name +
                                "' (known datasets: " + known + ")");
  }
  const Model& m = it->second;
  const Eigen::Index n = data.y.size();
  if (data.certified.size() != m.num_parameters ||
      data.starts.rows() != m.num_parameters || data.starts.cols() != 2 ||
      data.x.cols() != m.num_predictors || data.x.rows() != n || n == 0) {
    std::ostringstream msg;
    msg << "dataset '" << data.name << "' has " << data.certified.size()
        << " certified parameters, a " << data.starts.rows() << " x "
        << data.starts.cols() << " start table, " << data.x.rows() << " x "
        << data.x.cols() << " predictors and " << n << " responses; the model needs "
        << m.num_parameters << " parameters (starts: " << m.num_parameters << " x 2) and "
        << m.num_predictors << " predictor column(s) with one row per response";
    throw InputError(where, msg.str());
  }
  return m;
}

}  // namespace

NonlinearProblem NistNonlinearProblem(const NistNonlinearDataset& data, int start) {
  const std::string where = "NistNonlinearProblem(" + data.name + ")";
  const Model& model = ModelFor(data, where);
  if (start != 1 && start != 2) {
    throw InputError(where, "start must be 1 or 2 (NIST's two starting points), not " +
                                std::to_string(start));
  }
  NonlinearProblem p;
  p.num_residuals = static_cast<int>(data.y.size());
  p.initial = data.starts.col(start - 1);
  p.names = data.parameter_names;
  // The residual is against log(y) for Nelson.
  Eigen::VectorXd target = data.y;
  if (model.log_response) target = data.y.array().log().matrix();
  // Predictors row-major, one observation after another.
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> x = data.x;
  const std::string name = data.name;
  const auto f_ad = model.f_ad;
  const auto f_plain = model.f_double;
  const int num_parameters = model.num_parameters;
  p.evaluate = [name, target, x, f_ad, f_plain, num_parameters](
                   const Eigen::VectorXd& b, Eigen::VectorXd* residuals,
                   Eigen::MatrixXd* jacobian, std::string* why) {
    const Eigen::Index n = target.size();
    const Eigen::Index k = b.size();
    residuals->resize(n);
    if (k != num_parameters) {
      if (jacobian) jacobian->resize(n, k);
      if (why) {
        *why = name + ": " + std::to_string(k) + " parameters given, the model has " +
               std::to_string(num_parameters);
      }
      return false;
    }
    if (jacobian) jacobian->resize(n, k);
    std::vector<AD> params(static_cast<std::size_t>(k));
    std::vector<double> plain(static_cast<std::size_t>(k));
    for (Eigen::Index j = 0; j < k; ++j) {
      plain[j] = b(j);
      if (jacobian) params[j] = AD(b(j), k, j);
    }
    // Without a Jacobian the plain double model is evaluated (the same
    // operations on the values as the AD scalar performs).
    for (Eigen::Index i = 0; i < n; ++i) {
      const double* xi = x.data() + i * x.cols();
      double value = 0;
      if (jacobian) {
        const AD fi = f_ad(params.data(), xi);
        value = fi.value();
        const Eigen::Index m = fi.derivatives().size();
        for (Eigen::Index j = 0; j < k; ++j) {
          (*jacobian)(i, j) = j < m ? fi.derivatives()(j) : 0.0;
        }
      } else {
        value = f_plain(plain.data(), xi);
      }
      (*residuals)(i) = value - target(i);
      if (!std::isfinite((*residuals)(i)) ||
          (jacobian && !jacobian->row(i).allFinite())) {
        if (why) {
          std::ostringstream msg;
          msg.precision(17);
          msg << name << ": the model "
              << (std::isfinite((*residuals)(i)) ? "derivative" : "value")
              << " is not finite at observation " << i + 1 << " (x = " << xi[0] << ")";
          *why = msg.str();
        }
        return false;
      }
    }
    return true;
  };
  return p;
}

VectorLD NistNonlinearResiduals(const NistNonlinearDataset& data, const VectorLD& b) {
  const std::string where = "NistNonlinearResiduals(" + data.name + ")";
  const Model& model = ModelFor(data, where);
  if (b.size() != model.num_parameters) {
    throw InputError(where, "expected " + std::to_string(model.num_parameters) +
                                " parameters, got " + std::to_string(b.size()));
  }
  const bool exact = data.x_long.rows() == data.x.rows() &&
                     data.x_long.cols() == data.x.cols() &&
                     data.y_long.size() == data.y.size();
  const MatrixLD x = exact ? data.x_long : data.x.cast<LongDouble>();
  const VectorLD y = exact ? data.y_long : data.y.cast<LongDouble>();
  VectorLD r(y.size());
  std::vector<LongDouble> xi(static_cast<std::size_t>(x.cols()));
  for (Eigen::Index i = 0; i < y.size(); ++i) {
    for (Eigen::Index c = 0; c < x.cols(); ++c) xi[c] = x(i, c);
    const LongDouble target = model.log_response ? std::log(y(i)) : y(i);
    r(i) = model.f_long(b.data(), xi.data()) - target;
  }
  return r;
}

std::vector<std::string> NistNonlinearModelNames() {
  std::vector<std::string> names;
  for (const auto& m : Models()) names.push_back(m.first);
  return names;
}

}  // namespace femup
