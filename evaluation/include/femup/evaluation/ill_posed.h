// Discrete ill-posed test problems: discretisations of first-kind Fredholm
// integral equations  int K(s,t) f(t) dt = g(s)  whose matrices have rapidly
// decaying singular values, used to exercise regularisation methods.
//
// Reference: P. C. Hansen, "Regularization Tools: A Matlab package for analysis
// and solution of discrete ill-posed problems", Numer. Algorithms 6 (1994) 1-35,
// and "Regularization Tools version 4.0 for Matlab 7.3", Numer. Algorithms 46
// (2007) 189-194. Each function here uses the formulation of the toolbox's
// function of the same name (same grid, discretisation, scaling of A, b and x),
// so A, b and x_exact agree with the toolbox's [A,b,x] up to rounding:
//   phillips  Galerkin, orthonormal box functions on [-6, 6]
//   shaw      midpoint quadrature on [-pi/2, pi/2]; b = A x_exact
//   baart     Galerkin, box functions; s in [0, pi/2], t in [0, pi]
//   deriv2    Galerkin, box functions on [0, 1]; example 1 (f(t) = t)
//   foxgood   midpoint quadrature on [0, 1]
// For the Galerkin problems x_exact holds the coefficients of the L2 projection
// of f (cell integrals divided by sqrt(h)), not samples of f.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace femup {

struct IllPosedProblem {
  std::string name;         // "phillips", "shaw", "baart", "deriv2", "foxgood"
  Eigen::MatrixXd A;        // n x n
  Eigen::VectorXd b;        // exact right-hand side as the toolbox returns it
  Eigen::VectorXd x_exact;  // exact solution as the toolbox returns it
};

// Each throws InputError for an n the toolbox rejects or that is below 2.
IllPosedProblem Phillips(int n);  // n a multiple of 4 (toolbox requirement)
IllPosedProblem Shaw(int n);      // n even
IllPosedProblem Baart(int n);     // n even (toolbox requirement)
IllPosedProblem Deriv2(int n);    // example 1: x(t) = t, b(s) = (s^3 - s)/6, Galerkin
IllPosedProblem Foxgood(int n);

std::vector<std::string> IllPosedProblemNames();  // the five names above

// The problem called `name` of order n. Throws InputError("ill-posed problem", ...)
// naming an unknown problem and the allowed names, or the bad n and the rule.
IllPosedProblem MakeIllPosedProblem(const std::string& name, int n);

// b + e, e Gaussian (std::mt19937_64 seeded with `seed`, std::normal_distribution)
// scaled so that ||e|| = level * ||b||: Hansen's "relative noise level". The
// draws depend on the standard library's normal_distribution, so a seed gives
// the same vector on one platform, not necessarily across platforms. Throws
// InputError for a negative or non-finite level.
Eigen::VectorXd AddRelativeNoise(const Eigen::VectorXd& b, double level,
                                 std::uint64_t seed);

}  // namespace femup
