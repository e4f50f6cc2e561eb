// What the data cannot tell apart (effect_ranking.h, "Observational
// equivalence"): classes whose fits predict the data alike and whose Jacobians
// span the same directions of the data (a chain's ground spring and its first
// storey's stiffness), and classes that change the data only as the model's
// own form error does (model_form_error.h), which are named equivalent to
// "none". Each such class lists the others (RankedClass::equivalent), and the
// group's summed probability is stated with it (group_probability) rather than
// read as a split between them.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "femup/studies/effect_ranking.h"
#include "model_form_error.h"

namespace femup {

// True when the column spaces of a and b coincide: the same number of columns
// (at least one each) and every cosine of their principal angles at least
// `cosine`. Throws InputError("jacobian", ...) where a and b have different
// row counts.
bool SameSpan(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, double cosine);

// "<kind> at <region>", or the kind alone where there is no region ("none").
std::string ClassLabel(const RankedClass& c);

// Sets every class's group_probability to its probability plus those of the
// classes equivalent to it: whitened residuals (residuals[k], in the classes'
// order, at the noise the probabilities were formed at) within 1 of each other
// in squared norm, and Jacobians (jacobians[k]) of the same span, every cosine
// >= 0.999; their labels are appended to `equivalent`. Throws
// InputError("classes", ...) where the three lists differ in length.
void NameEquivalentClasses(const std::vector<Eigen::VectorXd>& residuals,
                           const std::vector<Eigen::MatrixXd>& jacobians,
                           std::vector<RankedClass>* classes);

// classes[0] is "none". A fitted class after it that can only change the data
// as the model's own form error does (at least 98 % of its raw Jacobian's
// squared norm along the variants' change of the frequencies,
// ModelFormError::ShareAlongVariants) and gains less than 9 (3 noise standard
// deviations) over none at the noise temperatures (residuals[k] whitened, times
// row_scale) is named equivalent to none, both ways, and their probabilities
// are added to each other's group. Returns the note that says so (the count
// and the most probable), or "" where there is none.
std::string NameFormErrorAlikeAsNone(const ModelFormError& form,
                                     const std::vector<Eigen::VectorXd>& residuals,
                                     const std::vector<Eigen::MatrixXd>& raw_jacobians,
                                     const Eigen::VectorXd& row_scale,
                                     std::vector<RankedClass>* classes);

}  // namespace femup
