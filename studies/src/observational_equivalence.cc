#include "observational_equivalence.h"

#include <Eigen/QR>
#include <Eigen/SVD>

#include "femup/core/errors.h"

namespace femup {
namespace {

// Throws unless there is one residual and one Jacobian per class.
void CheckOnePerClass(const std::vector<Eigen::VectorXd>& residuals,
                      const std::vector<Eigen::MatrixXd>& jacobians,
                      const std::vector<RankedClass>& classes) {
  if (residuals.size() == classes.size() && jacobians.size() == classes.size()) return;
  throw InputError("classes", std::to_string(classes.size()) + " classes, " +
                                  std::to_string(residuals.size()) + " residuals and " +
                                  std::to_string(jacobians.size()) + " Jacobians");
}

}  // namespace

bool SameSpan(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, double cosine) {
  if (a.cols() == 0 || b.cols() == 0 || a.cols() != b.cols()) return false;
  if (a.rows() != b.rows()) {
    throw InputError("jacobian", std::to_string(a.rows()) + " rows against " +
                                     std::to_string(b.rows()) + ": not the same data");
  }
  const Eigen::MatrixXd qa =
      a.householderQr().householderQ() * Eigen::MatrixXd::Identity(a.rows(), a.cols());
  const Eigen::MatrixXd qb =
      b.householderQr().householderQ() * Eigen::MatrixXd::Identity(b.rows(), b.cols());
  const Eigen::VectorXd s = (qa.transpose() * qb).jacobiSvd().singularValues();
  return s.minCoeff() >= cosine;
}

std::string ClassLabel(const RankedClass& c) {
  return c.region.empty() ? c.kind : c.kind + " at " + c.region;
}

void NameEquivalentClasses(const std::vector<Eigen::VectorXd>& residuals,
                           const std::vector<Eigen::MatrixXd>& jacobians,
                           std::vector<RankedClass>* classes) {
  CheckOnePerClass(residuals, jacobians, *classes);
  std::vector<RankedClass>& c = *classes;
  for (std::size_t i = 0; i < c.size(); ++i) {
    c[i].group_probability = c[i].probability;
    for (std::size_t k = 0; k < c.size(); ++k) {
      if (k == i || (residuals[i] - residuals[k]).squaredNorm() > 1.0 ||
          !SameSpan(jacobians[i], jacobians[k], 0.999)) {
        continue;
      }
      c[i].equivalent.push_back(ClassLabel(c[k]));
      c[i].group_probability += c[k].probability;
    }
  }
}

std::string NameFormErrorAlikeAsNone(const ModelFormError& form,
                                     const std::vector<Eigen::VectorXd>& residuals,
                                     const std::vector<Eigen::MatrixXd>& raw_jacobians,
                                     const Eigen::VectorXd& row_scale,
                                     std::vector<RankedClass>* classes) {
  CheckOnePerClass(residuals, raw_jacobians, *classes);
  std::vector<RankedClass>& c = *classes;
  if (c.empty() || c[0].kind != "none")
    throw InputError("classes", "the first class must be none");
  int alike = 0;
  const RankedClass* most = nullptr;
  const double none_tempered = residuals[0].cwiseProduct(row_scale).squaredNorm();
  for (std::size_t i = 1; i < c.size(); ++i) {
    if (!c[i].fitted) continue;
    const double along = form.ShareAlongVariants(raw_jacobians[i]);
    const double tempered_gain =
        none_tempered - residuals[i].cwiseProduct(row_scale).squaredNorm();
    if (!(along >= 0.98) || !(tempered_gain < 9)) continue;
    c[i].equivalent.push_back(ClassLabel(c[0]));
    c[i].group_probability += c[0].probability;
    c[0].equivalent.push_back(ClassLabel(c[i]));
    c[0].group_probability += c[i].probability;
    ++alike;
    if (most == nullptr || c[i].probability > most->probability) most = &c[i];
  }
  if (alike == 0) return "";
  return std::to_string(alike) +
         " fitted classes change the data only as the model's own form error does "
         "(the most probable: " +
         ClassLabel(*most) +
         "), and gain less than 9 (3 noise standard deviations) over none once it "
         "is allowed for: the data cannot tell them from none, and they are named "
         "equivalent";
}

}  // namespace femup
