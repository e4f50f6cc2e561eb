// What the data cannot tell apart (studies/src/observational_equivalence.h):
// subspaces at known principal angles, and hand-made classes whose residuals
// and Jacobians are equivalent, or alike the model's own form error, or not.
#include "observational_equivalence.h"

#include <gtest/gtest.h>

#include <cmath>

#include "expect_error.h"

namespace femup {
namespace {

Eigen::VectorXd Unit(int n, int i) { return Eigen::VectorXd::Unit(n, i); }

TEST(SameSpan, ComparesColumnSpacesByTheirPrincipalAngles) {
  Eigen::MatrixXd a(4, 2), b(4, 2);
  a << Unit(4, 0), Unit(4, 1);
  b << Unit(4, 0) + Unit(4, 1), 3 * (Unit(4, 0) - Unit(4, 1));
  EXPECT_TRUE(SameSpan(a, b, 0.999));  // another basis of the same plane
  b << Unit(4, 0), Unit(4, 2);
  EXPECT_FALSE(SameSpan(a, b, 0.999));  // one angle of 90 degrees
  // The second column turned out of the plane by theta: the smaller cosine
  // of the principal angles is cos theta (0.99955 and 0.99875).
  for (const double theta : {0.03, 0.05}) {
    b << Unit(4, 0), std::cos(theta) * Unit(4, 1) + std::sin(theta) * Unit(4, 3);
    EXPECT_EQ(SameSpan(a, b, 0.999), std::cos(theta) >= 0.999) << theta;
  }
  EXPECT_FALSE(SameSpan(a, a.leftCols(1), 0.999));  // not the same dimension
  EXPECT_FALSE(SameSpan(Eigen::MatrixXd(4, 0), Eigen::MatrixXd(4, 0), 0.999));
  testing::ExpectInputError([&] { SameSpan(a, Eigen::MatrixXd::Ones(3, 2), 0.999); },
                            {"jacobian", "4 rows against 3"});
}

TEST(ClassLabel, NamesTheKindAndItsRegion) {
  RankedClass none;
  none.kind = "none";
  EXPECT_EQ(ClassLabel(none), "none");
  RankedClass loss;
  loss.kind = "stiffness_loss";
  loss.region = "element 1";
  EXPECT_EQ(ClassLabel(loss), "stiffness_loss at element 1");
}

RankedClass Class(const std::string& kind, const std::string& region, double p,
                  bool fitted = true) {
  RankedClass c;
  c.kind = kind;
  c.region = region;
  c.probability = p;
  c.fitted = fitted;
  return c;
}

// Five residuals: a chain's ground spring and its first storey predict the same
// data along the same direction; a third class fits as well along another.
TEST(NameEquivalentClasses, GroupsClassesThatPredictAlikeAlongTheSameDirections) {
  const Eigen::VectorXd u = (Eigen::VectorXd(5) << 1, 2, 0, 1, 0).finished();
  const Eigen::VectorXd r0 = (Eigen::VectorXd(5) << 3, 1, 2, 0, 1).finished();
  std::vector<RankedClass> classes = {
      Class("none", "", 0.1), Class("support_flexibility", "supports", 0.4),
      Class("stiffness_loss", "element 1", 0.3), Class("attached_mass", "node 3", 0.2)};
  const std::vector<Eigen::VectorXd> residuals = {r0, 0.1 * r0,
                                                  0.1 * r0 + 0.5 * Unit(5, 4), 0.1 * r0};
  std::vector<Eigen::MatrixXd> jacobians = {Eigen::MatrixXd(5, 0), u, -2 * u, Unit(5, 2)};
  NameEquivalentClasses(residuals, jacobians, &classes);
  EXPECT_TRUE(classes[0].equivalent.empty());
  EXPECT_EQ(classes[0].group_probability, 0.1);
  EXPECT_EQ(classes[1].equivalent,
            std::vector<std::string>{"stiffness_loss at element 1"});
  EXPECT_NEAR(classes[1].group_probability, 0.7, 1e-15);
  EXPECT_EQ(classes[2].equivalent,
            std::vector<std::string>{"support_flexibility at supports"});
  EXPECT_NEAR(classes[2].group_probability, 0.7, 1e-15);
  EXPECT_TRUE(classes[3].equivalent.empty());  // the same fit, another direction
  EXPECT_EQ(classes[3].group_probability, 0.2);

  // Residuals further apart than 1 in squared norm: told apart.
  std::vector<RankedClass> apart = {Class("none", "", 0.5), Class("a", "1", 0.25),
                                    Class("b", "2", 0.25)};
  NameEquivalentClasses({r0, r0, r0 + 1.01 * Unit(5, 0)}, {Eigen::MatrixXd(5, 0), u, u},
                        &apart);
  EXPECT_TRUE(apart[1].equivalent.empty());
  testing::ExpectInputError(
      [&] {
        NameEquivalentClasses({r0}, {u, u, u, u}, &classes);
      },
      {"classes", "4 classes, 1 residuals and 4 Jacobians"});
}

// Three frequency rows and two shape rows; the model's form error moves the
// frequencies along u.
TEST(NameFormErrorAlikeAsNone, NamesNoneForWhatOnlyTheFormErrorCouldDo) {
  const Eigen::Vector3d u(1, 2, 2);
  const ModelFormError form({1, 1, 1, 0, 0}, {u});
  Eigen::MatrixXd along = Eigen::MatrixXd::Zero(5, 1), across = along;
  along.topRows(3) = u;
  across(0, 0) = 2;
  across(1, 0) = -1;
  const Eigen::VectorXd r_none = Eigen::VectorXd::Constant(5, 1.0);  // 5
  const Eigen::VectorXd r_small = Eigen::VectorXd::Zero(5);          // gains 5
  std::vector<RankedClass> classes = {Class("none", "", 0.4),
                                      Class("material_scaling", "all elements", 0.3),
                                      Class("stiffness_loss", "element 2", 0.2),
                                      Class("stiffness_loss", "element 3", 0.1),
                                      Class("stiffness_loss", "element 4", 0.0, false)};
  const Eigen::VectorXd row_scale = Eigen::VectorXd::Ones(5);
  for (RankedClass& c : classes) c.group_probability = c.probability;
  const std::string note = NameFormErrorAlikeAsNone(
      form, {r_none, r_small, r_small, r_small, r_small},
      {Eigen::MatrixXd(5, 0), along, across, along, along}, row_scale, &classes);
  // material_scaling and element 3 change the data only along u; element 2
  // across it; element 4 is screened, not fitted.
  EXPECT_EQ(classes[0].equivalent,
            (std::vector<std::string>{"material_scaling at all elements",
                                      "stiffness_loss at element 3"}));
  EXPECT_NEAR(classes[0].group_probability, 0.8, 1e-15);
  EXPECT_EQ(classes[1].equivalent, std::vector<std::string>{"none"});
  EXPECT_NEAR(classes[1].group_probability, 0.7, 1e-15);
  EXPECT_TRUE(classes[2].equivalent.empty());
  EXPECT_TRUE(classes[4].equivalent.empty());
  EXPECT_NE(note.find("2 fitted classes"), std::string::npos) << note;
  EXPECT_NE(note.find("the most probable: material_scaling at all elements"),
            std::string::npos)
      << note;

  // A gain of 9 or more over none at the noise temperature is an effect.
  std::vector<RankedClass> strong = {Class("none", "", 0.5),
                                     Class("material_scaling", "all elements", 0.5)};
  const Eigen::VectorXd r_far = Eigen::VectorXd::Constant(5, 1.5);  // 11.25
  EXPECT_EQ(NameFormErrorAlikeAsNone(form, {r_far, r_small},
                                     {Eigen::MatrixXd(5, 0), along}, row_scale, &strong),
            "");
  EXPECT_TRUE(strong[1].equivalent.empty());
  // ... but not once the noise temperature shrinks it: 11.25 / 2 < 9.
  EXPECT_NE(
      NameFormErrorAlikeAsNone(form, {r_far, r_small}, {Eigen::MatrixXd(5, 0), along},
                               Eigen::VectorXd::Constant(5, std::sqrt(0.5)), &strong),
      "");
  std::vector<RankedClass> no_none = {Class("stiffness_loss", "element 1", 1.0)};
  testing::ExpectInputError(
      [&] { NameFormErrorAlikeAsNone(form, {r_small}, {along}, row_scale, &no_none); },
      {"classes", "first class must be none"});
}

}  // namespace
}  // namespace femup
