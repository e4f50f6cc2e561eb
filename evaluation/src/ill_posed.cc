#include "femup/evaluation/ill_posed.h"

#include <cmath>
#include <cstdlib>
#include <random>
#include <sstream>

#include "femup/core/errors.h"

namespace femup {
namespace {

const char kWhere[] = "ill-posed problem";
const double kPi = 3.14159265358979323846;

// Throws unless n >= 2 and n is a multiple of `multiple` (1: any n).
void CheckOrder(const std::string& name, int n, int multiple) {
  if (n >= 2 && n % multiple == 0) return;
  std::string rule = "n must be at least 2";
  if (multiple == 2) rule = "n must be even and at least 2";
  if (multiple > 2) {
    rule = "n must be a positive multiple of " + std::to_string(multiple);
  }
  throw InputError(kWhere, name + ": n = " + std::to_string(n) + "; " + rule);
}

IllPosedProblem Empty(const std::string& name, int n) {
  IllPosedProblem p;
  p.name = name;
  p.A = Eigen::MatrixXd::Zero(n, n);
  p.b = Eigen::VectorXd::Zero(n);
  p.x_exact = Eigen::VectorXd::Zero(n);
  return p;
}

// int_{s0}^{s1} exp(c s) ds. The expm1 form stays accurate as c -> 0, which
// happens at t = pi/2 in baart (cos(pi/2) rounds to 6e-17, not 0).
double IntegralOfExp(double s0, double s1, double c) {
  if (c == 0) return s1 - s0;
  return std::exp(c * s0) * std::expm1(c * (s1 - s0)) / c;
}

}  // namespace

// K(s,t) = phi(s - t), f = phi, phi(x) = 1 + cos(pi x / 3) for |x| < 3 and 0
// beyond, on [-6, 6]. With box functions of width h = 12/n, A is symmetric
// Toeplitz: entry m = |i - j| is (1/h) int_{-h}^{h} (h - |w|) phi(m h + w) dw,
// which vanishes for m > n/4 since 3 = (n/4) h.
IllPosedProblem Phillips(int n) {
  CheckOrder("phillips", n, 4);
  IllPosedProblem p = Empty("phillips", n);
  const int quarter = n / 4;
  const double h = 12.0 / n;
  const double c = kPi / 3;
  const double sqrt_h = std::sqrt(h);
  // 1 - cos(c h), written without cancellation; c h = 4 pi / n.
  const double one_minus_cos = 2 * std::pow(std::sin(2 * kPi / n), 2);

  Eigen::VectorXd row = Eigen::VectorXd::Zero(n);
  for (int m = 0; m < quarter; ++m) {
    row[m] = h + 2 * one_minus_cos / (h * c * c) * std::cos(4 * kPi * m / n);
  }
  // At m = n/4 only the half of the cell pair with |s - t| < 3 contributes.
  row[quarter] = h / 2 - one_minus_cos / (h * c * c);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) p.A(i, j) = row[std::abs(i - j)];
  }

  // b_i = (1/sqrt(h)) int_cell g, g(s) = (6 - |s|)(1 + cos(c s)/2) + 9/(2 pi)
  // sin(c |s|), from the antiderivative G (G(0) = 0) on s >= 0; g is even.
  auto antiderivative = [c](double s) {
    const double half_angle = std::sin(c * s / 2);
    return s * (6 - s / 2) +
           ((3 - s / 2) * std::sin(c * s) + 4 * half_angle * half_angle / c) / c;
  };
  // x_i = (1/sqrt(h)) int_cell f: f is nonzero on the n/4 cells either side of 0.
  for (int k = 1; k <= n / 2; ++k) {
    const double s0 = (k - 1) * h, s1 = k * h;
    const double b = (antiderivative(s1) - antiderivative(s0)) / sqrt_h;
    p.b[n / 2 + k - 1] = b;
    p.b[n / 2 - k] = b;
    if (k <= quarter) {
      const double x = (h + (std::sin(c * s1) - std::sin(c * s0)) / c) / sqrt_h;
      p.x_exact[n / 2 + k - 1] = x;
      p.x_exact[n / 2 - k] = x;
    }
  }
  return p;
}

// K(s,t) = (cos s + cos t)^2 (sin u / u)^2, u = pi (sin s + sin t), and
// f(t) = 2 exp(-6 (t - 0.8)^2) + exp(-2 (t + 0.5)^2) on [-pi/2, pi/2], by the
// midpoint rule; b = A x_exact as in the toolbox.
IllPosedProblem Shaw(int n) {
  CheckOrder("shaw", n, 2);
  IllPosedProblem p = Empty("shaw", n);
  const double h = kPi / n;
  Eigen::VectorXd cos_t(n), psi(n);
  for (int i = 0; i < n; ++i) {
    // (i + 0.5 - n/2) is exact, so t_{n-1-i} = -t_i exactly: u vanishes exactly
    // on the anti-diagonal and A is exactly persymmetric.
    const double t = kPi * ((i + 0.5) - 0.5 * n) / n;
    cos_t[i] = std::cos(t);
    psi[i] = kPi * std::sin(t);
    p.x_exact[i] =
        2 * std::exp(-6 * std::pow(t - 0.8, 2)) + std::exp(-2 * std::pow(t + 0.5, 2));
  }
  for (int i = 0; i < n; ++i) {
    for (int j = i; j < n; ++j) {
      const double u = psi[i] + psi[j];
      const double sinc = u == 0 ? 1.0 : std::sin(u) / u;
      const double k = (cos_t[i] + cos_t[j]) * sinc;
      p.A(i, j) = h * k * k;
      p.A(j, i) = p.A(i, j);
    }
  }
  p.b = p.A * p.x_exact;
  return p;
}

// K(s,t) = exp(s cos t), g(s) = 2 sinh(s)/s, f(t) = sin t, s in [0, pi/2],
// t in [0, pi]. Galerkin with box functions (widths hs = pi/(2n), ht = pi/n):
// the s-integral of K is exact, the t-integral is Simpson's rule on each cell,
// and b's cell integrals of g are Simpson's rule too.
IllPosedProblem Baart(int n) {
  CheckOrder("baart", n, 2);
  IllPosedProblem p = Empty("baart", n);
  const double hs = kPi / (2 * n), ht = kPi / n;
  // (1 / sqrt(hs ht)) * ht / 6 = sqrt(2) / 6.
  const double simpson_scale = std::sqrt(2.0) / 6;
  for (int j = 0; j < n; ++j) {
    const double c0 = std::cos(j * ht), c_mid = std::cos((j + 0.5) * ht),
                 c1 = std::cos((j + 1) * ht);
    for (int i = 0; i < n; ++i) {
      const double s0 = i * hs, s1 = (i + 1) * hs;
      p.A(i, j) =
          simpson_scale * (IntegralOfExp(s0, s1, c0) + 4 * IntegralOfExp(s0, s1, c_mid) +
                           IntegralOfExp(s0, s1, c1));
    }
    // (1/sqrt(ht)) int_cell sin t dt = 2 sin(t_mid) sin(ht/2) / sqrt(ht).
    p.x_exact[j] = 2 * std::sin((j + 0.5) * ht) * std::sin(ht / 2) / std::sqrt(ht);
  }
  auto g = [](double s) { return s == 0 ? 2.0 : 2 * std::sinh(s) / s; };
  for (int i = 0; i < n; ++i) {
    p.b[i] = std::sqrt(hs) / 6 * (g(i * hs) + 4 * g((i + 0.5) * hs) + g((i + 1) * hs));
  }
  return p;
}

// K(s,t) = s (t - 1) for s < t and t (s - 1) for s >= t (Green's function of
// the second derivative) on [0, 1], example 1: f(t) = t, g(s) = (s^3 - s)/6.
// Galerkin with box functions of width h = 1/n; every integral is exact.
IllPosedProblem Deriv2(int n) {
  CheckOrder("deriv2", n, 1);
  IllPosedProblem p = Empty("deriv2", n);
  const double h = 1.0 / n, h2 = h * h, h32 = h * std::sqrt(h);
  for (int i = 1; i <= n; ++i) {
    // On the diagonal cell the kernel changes branch at s = t.
    p.A(i - 1, i - 1) = h2 * ((i * i - i + 0.25) * h - (i - 2.0 / 3));
    for (int j = 1; j < i; ++j) {
      p.A(i - 1, j - 1) = h2 * (j - 0.5) * ((i - 0.5) * h - 1);
      p.A(j - 1, i - 1) = p.A(i - 1, j - 1);
    }
    // (1/sqrt(h)) times the cell integrals of g and of f.
    p.b[i - 1] = h32 * (i - 0.5) * ((i * i + (i - 1) * (i - 1)) * h2 / 2 - 1) / 6;
    p.x_exact[i - 1] = h32 * (i - 0.5);
  }
  return p;
}

// K(s,t) = sqrt(s^2 + t^2), f(t) = t, g(s) = ((1 + s^2)^(3/2) - s^3)/3 on
// [0, 1] (Fox & Goodwin), by the midpoint rule; b samples g at the midpoints.
IllPosedProblem Foxgood(int n) {
  CheckOrder("foxgood", n, 1);
  IllPosedProblem p = Empty("foxgood", n);
  const double h = 1.0 / n;
  for (int i = 0; i < n; ++i) {
    const double s = (i + 0.5) * h;
    for (int j = 0; j < n; ++j) {
      const double t = (j + 0.5) * h;
      p.A(i, j) = h * std::sqrt(s * s + t * t);
    }
    p.x_exact[i] = s;
    p.b[i] = (std::pow(1 + s * s, 1.5) - s * s * s) / 3;
  }
  return p;
}

std::vector<std::string> IllPosedProblemNames() {
  return {"phillips", "shaw", "baart", "deriv2", "foxgood"};
}

IllPosedProblem MakeIllPosedProblem(const std::string& name, int n) {
  if (name == "phillips") return Phillips(n);
  if (name == "shaw") return Shaw(n);
  if (name == "baart") return Baart(n);
  if (name == "deriv2") return Deriv2(n);
  if (name == "foxgood") return Foxgood(n);
  std::string allowed;
  for (const std::string& known : IllPosedProblemNames()) {
    allowed += (allowed.empty() ? "" : ", ") + known;
  }
  throw InputError(kWhere,
                   "unknown problem \"" + name + "\"; expected one of " + allowed);
}

Eigen::VectorXd AddRelativeNoise(const Eigen::VectorXd& b, double level,
                                 std::uint64_t seed) {
  if (!(level >= 0) || !std::isfinite(level)) {
    std::ostringstream what;
    what << "level = " << level << "; it must be finite and >= 0";
    throw InputError("relative noise", what.str());
  }
  if (level == 0 || b.size() == 0) return b;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  Eigen::VectorXd e(b.size());
  for (Eigen::Index i = 0; i < e.size(); ++i) e[i] = gauss(rng);
  return b + (level * b.norm() / e.norm()) * e;
}

}  // namespace femup
