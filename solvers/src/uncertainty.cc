#include "femup/solvers/uncertainty.h"

#include <boost/math/distributions/normal.hpp>
#include <boost/math/distributions/students_t.hpp>

namespace femup {

namespace {
// Double precision throughout (the default policy promotes to long double).
using Policy =
    boost::math::policies::policy<boost::math::policies::promote_double<false>>;
}  // namespace

double IntervalQuantile(double confidence_level, double dof) {
  const double p = 0.5 + 0.5 * confidence_level;
  if (dof <= 0)
    return boost::math::quantile(boost::math::normal_distribution<double, Policy>(), p);
  return boost::math::quantile(boost::math::students_t_distribution<double, Policy>(dof),
                               p);
}

void SetIntervals(double dof, LinearSolution* solution) {
  if (solution->covariance.size() == 0) return;
  solution->standard_error = solution->covariance.diagonal().cwiseMax(0.0).cwiseSqrt();
  const double q = IntervalQuantile(solution->confidence_level, dof);
  solution->interval_lower = solution->x - q * solution->standard_error;
  solution->interval_upper = solution->x + q * solution->standard_error;
}

}  // namespace femup
