#include "mode_pairing.h"

#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>

namespace femup::output_error {

ShapeScale ScaleShape(const StateTerms& st, Eigen::Index j, const Eigen::VectorXd& s) {
  const Eigen::VectorXd target = st.targets.col(j);
  const double sign = s.dot(target) >= 0 ? 1.0 : -1.0;
  ShapeScale out;
  if (st.scaling == "fit") {
    // c minimises sum_i W_i^2 (c s_i - psi_i)^2: c = N / D, and
    // dc = (dN - c dD) / D with dN = (W^2 psi)' ds, dD = 2 (W^2 s)' ds.
    const Eigen::ArrayXd w2 = st.shape_weights.col(j).array().square();
    const double d = (w2 * s.array().square()).sum();
    if (!(d > 0)) {
      out.c = 0;
      out.dc_ds = Eigen::VectorXd::Zero(s.size());
      return out;
    }
    out.c = (w2 * target.array() * s.array()).sum() / d;
    out.dc_ds = ((w2 * target.array() - 2.0 * out.c * w2 * s.array()) / d).matrix();
  } else if (st.scaling == "unit") {
    out.c = sign / s.norm();
    out.dc_ds = -out.c / s.squaredNorm() * s;  // d(1 / ||s||) = -s' ds / ||s||^3
  } else {
    out.c = sign;
    out.dc_ds = Eigen::VectorXd::Zero(s.size());
  }
  return out;
}

double ShapeMisfit(const StateTerms& st, Eigen::Index j, const Eigen::VectorXd& s) {
  if (!(s.squaredNorm() > 0)) return std::numeric_limits<double>::infinity();
  const double c = ScaleShape(st, j, s).c;
  return st.shape_weights.col(j).cwiseProduct(c * s - st.targets.col(j)).squaredNorm();
}

void AlignRepeatedModes(const StateTerms& st, Modes* modes) {
  if (st.shapes.cols() == 0) return;
  femup::AlignRepeatedModes(st.shapes, AtSensors(st, modes->shapes), modes);
}

bool PairMeasuredModes(const Context& c, const StateTerms& st, const Modes& modes,
                       std::vector<int>* pairing, std::string* why) {
  pairing->resize(static_cast<std::size_t>(st.lambdas.size()));
  std::iota(pairing->begin(), pairing->end(), 0);
  if (!st.pair_by_mac) return true;
  const Eigen::MatrixXd model_at_sensors = AtSensors(st, modes.shapes);
  const Eigen::Index num_measured = st.lambdas.size();
  const Eigen::Index num_candidates = model_at_sensors.cols();
  Eigen::MatrixXd shape_misfit(num_measured, num_candidates);
  Eigen::MatrixXd frequency_misfit(num_measured, num_candidates);
  for (Eigen::Index j = 0; j < num_measured; ++j) {
    for (Eigen::Index q = 0; q < num_candidates; ++q) {
      shape_misfit(j, q) = ShapeMisfit(st, j, model_at_sensors.col(q));
      const double gap = (modes.eigenvalues[q] / st.lambdas[j] - 1.0) / c.frequency_sigma;
      frequency_misfit(j, q) = gap * gap;
    }
  }
  const std::vector<ModePair> pairs =
      PairModesByMacAndMisfit(MacMatrix(st.shapes, model_at_sensors), shape_misfit,
                              frequency_misfit, c.min_mac, kPairingTie);
  for (std::size_t j = 0; j < pairs.size(); ++j) {
    if (pairs[j].candidate < 0) {
      std::ostringstream msg;
      msg << st.name << " mode " << j + 1
          << ": no model mode left to pair with MAC >= " << c.min_mac;
      if (why != nullptr) *why = msg.str();
      return false;
    }
    (*pairing)[j] = pairs[j].candidate;
  }
  return true;
}

}  // namespace femup::output_error
