// Confidence intervals of an estimate from its covariance, shared by every
// solver and pipeline that reports them.
#pragma once

#include "femup/solvers/linear_solver.h"

namespace femup {

// Two-sided quantile at `confidence_level`: Student t with `dof` degrees of
// freedom when dof > 0 (noise estimated from the residual), normal otherwise.
double IntervalQuantile(double confidence_level, double dof);

// Standard errors from solution->covariance and the interval x -+ q * se at
// solution->confidence_level (q from IntervalQuantile with `dof`). Does
// nothing when the covariance is empty.
void SetIntervals(double dof, LinearSolution* solution);

}  // namespace femup
