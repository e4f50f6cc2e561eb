#include "mode_pairing.h"

#include <Eigen/SVD>
#include <algorithm>
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

Eigen::Index LastOfRepeated(const Modes& modes, Eigen::Index first) {
  Eigen::Index last = first;
  while (last + 1 < modes.size() &&
         modes.eigenvalues[last + 1] - modes.eigenvalues[last] <=
             kRepeatedEigenvalueTolerance * std::abs(modes.eigenvalues[last + 1])) {
    ++last;
  }
  return last;
}

void AlignRepeatedModes(const StateTerms& st, Modes* modes) {
  const Eigen::Index num = modes->size();
  if (st.shapes.cols() == 0 || num < 3) return;
  const Eigen::MatrixXd all_at_sensors = AtSensors(st, modes->shapes);
  const Eigen::Index num_measured = st.shapes.cols();
  for (Eigen::Index first = 0; first < num;) {
    const Eigen::Index last = LastOfRepeated(*modes, first);
    const Eigen::Index dim = last - first + 1;
    if (dim < 2 || last + 1 >= num) {
      first = last + 1;
      continue;
    }
    const Eigen::MatrixXd at_sensors = all_at_sensors.middleCols(first, dim);
    const Eigen::JacobiSVD<Eigen::MatrixXd> span(
        at_sensors, Eigen::ComputeThinU | Eigen::ComputeThinV);
    // Each measured shape's MAC with the eigenspace (with its best combination,
    // the least-squares one) and with the best single mode outside it.
    struct Candidate {
      Eigen::Index measured;
      double mac;
      Eigen::VectorXd combination;
    };
    std::vector<Candidate> candidates;
    for (Eigen::Index j = 0; j < num_measured; ++j) {
      const Eigen::VectorXd psi = st.shapes.col(j);
      if (!(psi.squaredNorm() > 0)) continue;
      Eigen::VectorXd a = span.solve(psi);
      const double norm = a.norm();
      if (!(norm > 0) || !std::isfinite(norm)) continue;
      const double mac = Mac(psi, at_sensors * a);
      double outside = 0;
      for (Eigen::Index q = 0; q < num; ++q) {
        if (q < first || q > last)
          outside = std::max(outside, Mac(psi, all_at_sensors.col(q)));
      }
      if (mac >= outside) candidates.push_back({j, mac, a / norm});
    }
    if (candidates.empty()) {
      first = last + 1;
      continue;
    }
    std::stable_sort(
        candidates.begin(), candidates.end(),
        [](const Candidate& a, const Candidate& b) { return a.mac > b.mac; });
    const Eigen::Index k = std::min<Eigen::Index>(dim, candidates.size());
    Eigen::MatrixXd combination(dim, k);
    for (Eigen::Index q = 0; q < k; ++q) combination.col(q) = candidates[q].combination;
    // The nearest orthonormal set to the combinations (the polar factor),
    // completed by the rest of the eigenspace: an orthogonal dim x dim matrix.
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(
        combination, Eigen::ComputeFullU | Eigen::ComputeThinV);
    Eigen::MatrixXd rotation(dim, dim);
    rotation.leftCols(k) = svd.matrixU().leftCols(k) * svd.matrixV().transpose();
    rotation.rightCols(dim - k) = svd.matrixU().rightCols(dim - k);
    const Eigen::MatrixXd basis = modes->shapes.middleCols(first, dim);
    modes->shapes.middleCols(first, dim) = basis * rotation;
    first = last + 1;
  }
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
