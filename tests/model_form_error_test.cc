// The model's own form error as the effect ranking allows for it
// (studies/src/model_form_error.h): the whitening against the covariance
// written out (Sherman-Morrison for one direction, a dense inverse for two)
// and its independence of the rows' order,
// the share of a Jacobian along the variants, the Gauss-Newton step against the
// normal equations, and a portal frame's shear variant to first order against
// the eigenvalues of the same frame built with Timoshenko members.
#include "model_form_error.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <random>
#include <string_view>

#include "expect_error.h"
#include "femup/core/fe/builders.h"
#include "femup/core/fe/plane_frame.h"
#include "femup/core/linalg/modal.h"
#include "femup/problems/effect_priors.h"
#include "structure_specs.h"

namespace femup {
namespace {

Eigen::VectorXd Random(Eigen::Index n, std::mt19937* rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::VectorXd v(n);
  for (Eigen::Index i = 0; i < n; ++i) v[i] = normal(*rng);
  return v;
}

// Rows 0, 2 and 3 are frequencies, 1 and 4 shape entries.
const std::vector<char> kRows = {1, 0, 1, 1, 0};

TEST(ModelFormError, WhitensByTheCovarianceOfOneDirection) {
  std::mt19937 rng(11);
  const Eigen::VectorXd u = Random(3, &rng);
  const ModelFormError form(kRows, {u});
  ASSERT_TRUE(form.Active());
  EXPECT_EQ(form.NumDirections(), 1);
  EXPECT_EQ(form.covered_rows(), (std::vector<int>{0, 2, 3}));
  const Eigen::VectorXd r = Random(5, &rng);
  Eigen::VectorXd w = r;
  form.Whiten(&w, nullptr);
  // The shapes' rows as they were.
  EXPECT_EQ(w[1], r[1]);
  EXPECT_EQ(w[4], r[4]);
  // Sherman-Morrison: rf' (I + u u')^-1 rf = |rf|^2 - (u'rf)^2 / (1 + |u|^2).
  const Eigen::Vector3d rf(r[0], r[2], r[3]);
  const Eigen::Vector3d wf(w[0], w[2], w[3]);
  const double expected =
      rf.squaredNorm() - std::pow(u.dot(rf), 2) / (1 + u.squaredNorm());
  EXPECT_NEAR(wf.squaredNorm(), expected, 1e-12 * rf.squaredNorm());
  // Along u a residual counts 1 / (1 + |u|^2) of its square; across it, fully.
  Eigen::VectorXd along = Eigen::VectorXd::Zero(5);
  along[0] = u[0];
  along[2] = u[1];
  along[3] = u[2];
  form.Whiten(&along, nullptr);
  EXPECT_NEAR(along.squaredNorm(), u.squaredNorm() / (1 + u.squaredNorm()), 1e-12);
}

// The bagged posterior resamples the whitened rows one by one, so how a
// residual is spread over them matters: along a direction shared by every
// row (a uniform change) it stays uniform, 1 / sqrt(1 + n a^2) on each of n
// rows for u = a (1, ..., 1), and permuting the rows (u's with them) permutes
// the whitened rows alike. A Cholesky factor put nearly all of it on the first.
TEST(ModelFormError, WhitensTheSameWhateverTheRowsOrder) {
  const ModelFormError uniform(kRows, {Eigen::Vector3d::Constant(5.0)});
  Eigen::VectorXd r = Eigen::VectorXd::Ones(5);
  uniform.Whiten(&r, nullptr);
  for (int k : {0, 2, 3}) EXPECT_NEAR(r[k], 1 / std::sqrt(1 + 3 * 25.0), 1e-12) << k;

  std::mt19937 rng(13);
  const Eigen::VectorXd u = Random(3, &rng), rf = Random(3, &rng);
  const std::vector<char> all(3, 1);
  Eigen::VectorXd w = rf;
  ModelFormError(all, {u}).Whiten(&w, nullptr);
  const Eigen::Vector3d pu(u[2], u[0], u[1]);
  Eigen::VectorXd pw = Eigen::Vector3d(rf[2], rf[0], rf[1]);
  ModelFormError(all, {pu}).Whiten(&pw, nullptr);
  EXPECT_NEAR(pw[0], w[2], 1e-12);
  EXPECT_NEAR(pw[1], w[0], 1e-12);
  EXPECT_NEAR(pw[2], w[1], 1e-12);
}

// The whitening is C^-1/2 itself, not merely a W with W'W = C^-1: applied to
// the identity's columns it gives the symmetric inverse square root that a
// dense eigendecomposition of C gives (and the unwhitening its square root),
// here on 120 covered rows, with three directions of which one repeats
// another (rank 2) as a frame's variants can.
TEST(ModelFormError, WhitensByTheCovariancesSymmetricInverseRoot) {
  std::mt19937 rng(14);
  const Eigen::Index n = 120;
  const Eigen::VectorXd u1 = 3 * Random(n, &rng), u2 = Random(n, &rng);
  const ModelFormError form(std::vector<char>(n, 1), {u1, u2, -2 * u1});
  EXPECT_EQ(form.NumDirections(), 2);
  const Eigen::MatrixXd c =
      Eigen::MatrixXd::Identity(n, n) + 5 * u1 * u1.transpose() + u2 * u2.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(c);
  const Eigen::MatrixXd& v = eig.eigenvectors();
  const Eigen::MatrixXd root =
      v * eig.eigenvalues().cwiseSqrt().asDiagonal() * v.transpose();
  const Eigen::MatrixXd inverse_root =
      v * eig.eigenvalues().cwiseSqrt().cwiseInverse().asDiagonal() * v.transpose();
  Eigen::VectorXd r = Eigen::VectorXd::Zero(n);
  Eigen::MatrixXd w = Eigen::MatrixXd::Identity(n, n), b = w;
  form.Whiten(&r, &w);
  form.Unwhiten(&r, &b);
  EXPECT_LT((w - inverse_root).norm(), 1e-12 * inverse_root.norm());
  EXPECT_LT((b - root).norm(), 1e-12 * root.norm());
}

TEST(ModelFormError, WhitensResidualAndJacobianAlikeAndUnwhitensBack) {
  std::mt19937 rng(12);
  const Eigen::VectorXd u1 = Random(3, &rng), u2 = Random(3, &rng);
  const ModelFormError form(kRows, {u1, u2});
  EXPECT_EQ(form.NumDirections(), 2);
  Eigen::MatrixXd j(5, 2);
  j.col(0) = Random(5, &rng);
  j.col(1) = Random(5, &rng);
  const Eigen::VectorXd r = Random(5, &rng);
  Eigen::VectorXd wr = r;
  Eigen::MatrixXd wj = j;
  form.Whiten(&wr, &wj);
  // The whitened Gram matrix is J_f' C^-1 J_f + J_s' J_s, C = I + u1 u1' + u2 u2'
  // inverted densely here.
  const Eigen::Matrix3d c =
      Eigen::Matrix3d::Identity() + u1 * u1.transpose() + u2 * u2.transpose();
  const Eigen::Matrix3d c_inv = c.fullPivLu().inverse();
  const std::vector<int> f = {0, 2, 3}, s = {1, 4};
  Eigen::MatrixXd jf(3, 2), js(2, 2);
  Eigen::Vector3d rf;
  for (int k = 0; k < 3; ++k) {
    jf.row(k) = j.row(f[k]);
    rf[k] = r[f[k]];
  }
  for (int k = 0; k < 2; ++k) js.row(k) = j.row(s[k]);
  const Eigen::MatrixXd gram = jf.transpose() * c_inv * jf + js.transpose() * js;
  EXPECT_LT((wj.transpose() * wj - gram).norm(), 1e-12 * gram.norm());
  EXPECT_NEAR(wr.squaredNorm(), rf.dot(c_inv * rf) + r[1] * r[1] + r[4] * r[4],
              1e-12 * r.squaredNorm());
  EXPECT_LT((wj.transpose() * wr -
             (jf.transpose() * c_inv * rf + js.transpose() * Eigen::Vector2d(r[1], r[4])))
                .norm(),
            1e-12 * (1 + gram.norm() * r.norm()));
  form.Unwhiten(&wr, &wj);
  EXPECT_LT((wr - r).norm(), 1e-13 * r.norm());
  EXPECT_LT((wj - j).norm(), 1e-13 * j.norm());
  // A Jacobian of no column ("none") is whitened without reading it.
  Eigen::MatrixXd empty(5, 0);
  Eigen::VectorXd r2 = r;
  form.Whiten(&r2, &empty);
  EXPECT_EQ(empty.cols(), 0);
}

TEST(ModelFormError, AllowsForNothingWithoutFrequencies) {
  const ModelFormError none;
  EXPECT_FALSE(none.Active());
  Eigen::VectorXd r(3);
  r << 1, 2, 3;
  none.Whiten(&r, nullptr);
  EXPECT_EQ(r, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(none.ShareAlongVariants(Eigen::MatrixXd::Ones(3, 1)), 0);
  // Shapes only: nothing to whiten, whatever the directions.
  const ModelFormError shapes({0, 0}, {Eigen::VectorXd(0)});
  EXPECT_FALSE(shapes.Active());
  // Frequencies and no variant: the identity.
  const ModelFormError identity({1, 1}, {});
  EXPECT_TRUE(identity.Active());
  Eigen::VectorXd q(2);
  q << 3, -4;
  identity.Whiten(&q, nullptr);
  EXPECT_EQ(q, Eigen::Vector2d(3, -4));
  EXPECT_EQ(identity.NumDirections(), 0);
}

TEST(ModelFormError, NamesWhatDoesNotFit) {
  testing::ExpectInputError(
      [] { (void)ModelFormError(kRows, {Eigen::VectorXd::Ones(2)}); },
      {"form_error", "2 values", "3 covered rows"});
  Eigen::VectorXd nan = Eigen::VectorXd::Ones(3);
  nan[1] = std::nan("");
  testing::ExpectInputError([&] { (void)ModelFormError(kRows, {nan}); },
                            {"form_error", "finite"});
  const ModelFormError form(kRows, {Eigen::VectorXd::Ones(3)});
  Eigen::VectorXd r = Eigen::VectorXd::Ones(4);
  testing::ExpectInputError([&] { form.Whiten(&r, nullptr); },
                            {"residual", "4 residuals", "expected 5"});
  Eigen::VectorXd r5 = Eigen::VectorXd::Ones(5);
  Eigen::MatrixXd j = Eigen::MatrixXd::Ones(4, 1);
  testing::ExpectInputError([&] { form.Unwhiten(&r5, &j); },
                            {"residual", "4 Jacobian rows", "expected 5"});
  testing::ExpectInputError([&] { form.ShareAlongVariants(j); }, {"jacobian", "4 rows"});
}

TEST(ModelFormError, SharesAJacobiansNormAlongTheVariants) {
  const Eigen::Vector3d u(1, 2, 2);
  const ModelFormError form(kRows, {u});
  Eigen::MatrixXd along = Eigen::MatrixXd::Zero(5, 1);
  along(0, 0) = 2;
  along(2, 0) = 4;
  along(3, 0) = 4;
  EXPECT_NEAR(form.ShareAlongVariants(along), 1.0, 1e-14);
  // Across u in the frequencies: none of it.
  Eigen::MatrixXd across = Eigen::MatrixXd::Zero(5, 1);
  across(0, 0) = 2;
  across(2, 0) = -1;
  EXPECT_NEAR(form.ShareAlongVariants(across), 0.0, 1e-14);
  // Along u in the frequencies, as much again in a shape row: half.
  Eigen::MatrixXd half = along;
  half(4, 0) = 6;  // |(2, 4, 4)|^2 = 36
  EXPECT_NEAR(form.ShareAlongVariants(half), 0.5, 1e-14);
  // Two columns: the share of the whole squared norm.
  Eigen::MatrixXd both(5, 2);
  both << along, across;
  EXPECT_NEAR(form.ShareAlongVariants(both), 36.0 / 41.0, 1e-14);
  EXPECT_EQ(form.ShareAlongVariants(Eigen::MatrixXd::Zero(5, 2)), 0);
  EXPECT_EQ(form.ShareAlongVariants(Eigen::MatrixXd(5, 0)), 0);
}

TEST(ClassPriors, SumsTheNormalPriorsSquares) {
  ClassPriors p;
  EXPECT_EQ(p.Misfit(Eigen::Vector2d(1, 2)), 0);  // uniform: no term
  p.mean = Eigen::Vector2d(1, 0);
  p.sigma = Eigen::Vector2d(0.5, 0);  // the second uniform
  EXPECT_NEAR(p.Misfit(Eigen::Vector2d(2, 7)), 4.0, 1e-15);
}

// The form fit is kept where its misfit (the stated priors as residuals of the
// quantity, WithPriorResiduals) is below the starting one (ClassPriors, the
// priors linearised at the start, LocalNormalPriors): the two forms agree at
// the point they are linearised at, so the comparison is exact there; away
// from it they differ (a log coordinate's prior is not Gaussian in theta).
TEST(ClassPriors, AgreeWithThePriorResidualsWhereLinearised) {
  EffectParameter mass("ln_mass", "ln(m / 10 kg)", -5, 2, false);
  mass.quantity = "mass_kg";
  mass.log_coordinate = true;
  mass.quantity_scale = 10;
  mass.normal_mean = 0.005;  // about 5 g
  mass.normal_sigma = 0.002;
  EffectParameter level("level", "m", 0, 3, true);
  level.quantity = "level_m";
  level.quantity_scale = 1;
  level.normal_mean = 1.5;
  level.normal_sigma = 0.3;
  EffectParameter uniform("ln_ratio", "ln c", -3, 3, false);
  const std::vector<EffectParameter> params = {mass, uniform, level};
  NonlinearProblem data;
  data.initial = Eigen::Vector3d::Zero();
  data.lower = Eigen::Vector3d::Constant(-10);
  data.upper = Eigen::Vector3d::Constant(10);
  data.num_residuals = 1;
  data.evaluate = [](const Eigen::VectorXd&, Eigen::VectorXd* r, Eigen::MatrixXd* j,
                     std::string*) {
    *r = Eigen::VectorXd::Zero(1);
    if (j != nullptr) *j = Eigen::MatrixXd::Zero(1, 3);
    return true;
  };
  const NonlinearProblem with_priors = WithPriorResiduals(data, params);
  for (const Eigen::Vector3d& theta :
       {Eigen::Vector3d(std::log(0.0005), 0.3, 1.2), Eigen::Vector3d(-7, -1, 2.9)}) {
    ClassPriors p;
    LocalNormalPriors(params, theta, &p.mean, &p.sigma);
    Eigen::VectorXd r;
    std::string why;
    ASSERT_TRUE(with_priors.evaluate(theta, &r, nullptr, &why)) << why;
    ASSERT_EQ(r.size(), 3);  // the data's one row, then the two normal priors
    EXPECT_NEAR(p.Misfit(theta), r.squaredNorm(), 1e-12 * r.squaredNorm());
    // Elsewhere the log coordinate's two forms part.
    const Eigen::Vector3d moved = theta + Eigen::Vector3d(0.5, 0, 0);
    ASSERT_TRUE(with_priors.evaluate(moved, &r, nullptr, &why)) << why;
    EXPECT_GT(std::abs(p.Misfit(moved) - r.squaredNorm()), 1e-3 * r.squaredNorm());
  }
}

// On residuals linear in theta the step is the least-squares solution, the
// priors' rows with it: the normal equations (J'J + P) d = -J'r - P (theta -
// mean), P = diag(1 / sigma^2), solved here by an LU of their matrix.
TEST(GaussNewtonStepInForm, SolvesTheLinearProblemAndKeepsItsBox) {
  std::mt19937 rng(13);
  Eigen::MatrixXd j(6, 2);
  j.col(0) = Random(6, &rng);
  j.col(1) = Random(6, &rng);
  const Eigen::VectorXd r = Random(6, &rng);
  const Eigen::Vector2d theta(0.1, -0.2);
  ClassPriors priors;
  priors.lower = Eigen::Vector2d::Constant(-100);
  priors.upper = Eigen::Vector2d::Constant(100);
  const std::optional<Eigen::VectorXd> to = GaussNewtonStepInForm(theta, r, j, priors);
  ASSERT_TRUE(to.has_value());
  const Eigen::Vector2d d = (j.transpose() * j).fullPivLu().solve(-j.transpose() * r);
  EXPECT_LT((*to - theta - d).norm(), 1e-12 * (1 + d.norm()));

  priors.mean = Eigen::Vector2d(0.0, 0.5);
  priors.sigma = Eigen::Vector2d(0.0, 0.1);  // a normal prior on the second only
  const std::optional<Eigen::VectorXd> with_prior =
      GaussNewtonStepInForm(theta, r, j, priors);
  ASSERT_TRUE(with_prior.has_value());
  Eigen::Matrix2d p = Eigen::Matrix2d::Zero();
  p(1, 1) = 1 / (0.1 * 0.1);
  const Eigen::Vector2d dp = (j.transpose() * j + p)
                                 .fullPivLu()
                                 .solve(-j.transpose() * r - p * (theta - priors.mean));
  EXPECT_LT((*with_prior - theta - dp).norm(), 1e-12 * (1 + dp.norm()));

  // The end kept in the box.
  priors.mean.resize(0);
  priors.sigma.resize(0);
  priors.lower = theta + Eigen::Vector2d::Constant(-1e-3);
  priors.upper = theta + Eigen::Vector2d::Constant(1e-3);
  const std::optional<Eigen::VectorXd> boxed = GaussNewtonStepInForm(theta, r, j, priors);
  ASSERT_TRUE(boxed.has_value());
  EXPECT_TRUE(((boxed->array() >= priors.lower.array()) &&
               (boxed->array() <= priors.upper.array()))
                  .all());
  EXPECT_LT((r + j * (*boxed - theta)).squaredNorm(), r.squaredNorm());

  // At the optimum already (or with no unknown) there is no step to take.
  priors.lower = Eigen::Vector2d::Constant(-100);
  priors.upper = Eigen::Vector2d::Constant(100);
  const Eigen::VectorXd at_optimum = r + j * d;
  EXPECT_FALSE(GaussNewtonStepInForm(theta + d, at_optimum, j, priors).has_value());
  EXPECT_FALSE(
      GaussNewtonStepInForm(Eigen::VectorXd(0), r, Eigen::MatrixXd(6, 0), ClassPriors{})
          .has_value());
}

// A two-storey portal of Euler-Bernoulli members, two elements each, measured
// as its own lowest four frequencies (no shapes): its shear variant's change,
// to first order, against the frequencies of the same portal built with
// Timoshenko members of the same shear areas on the variant's finer mesh.
TEST(ModelFormError, MeasuresAPortalsShearDeformationToFirstOrder) {
  PlaneFrameSpec spec = fixtures::PlaneFrame(2, 1, 2, 3.5, 6.0);
  spec.column = {210e9, 7.8e-3, 8.4e-5, 7850};
  spec.beam = {210e9, 5.4e-3, 1.9e-4, 7850};
  const Structure model = BuildPlaneFrameStructure(spec);
  ASSERT_GE(model.form_variants.size(), 1u);
  ASSERT_NE(model.form_variants[0].name.find("shear deformation"), std::string::npos);
  const Modes nominal = SolveModes(model.stiffness, model.mass);
  ModalData d;
  d.state = "air";
  d.frequencies_hz = nominal.FrequenciesHz().head(4);

  EigenSensitivityOptions options;
  const double frequency_sigma = 0.002;
  options.frequency_sigma = 2 * frequency_sigma;  // of lambda
  const NonlinearProblem problem = NominalOutputErrorProblem(model, {}, {d}, options);
  const std::vector<char> is_frequency = FrequencyRows(problem);
  ASSERT_EQ(is_frequency, std::vector<char>(4, 1));
  Eigen::VectorXd r;
  std::string why;
  ASSERT_TRUE(problem.evaluate(Eigen::VectorXd::Zero(1), &r, nullptr, &why)) << why;
  EXPECT_LT(r.norm(), 1e-6);  // the model against its own frequencies

  std::vector<FormErrorAllowance> allowances;
  const ModelFormError form =
      ModelFormError::Measure(model, model.form_variants, {d}, options, is_frequency,
                              false, frequency_sigma, &allowances);
  ASSERT_TRUE(form.Active());
  ASSERT_EQ(allowances.size(), model.form_variants.size());
  EXPECT_EQ(allowances[0].name, model.form_variants[0].name);

  // The same frame with shear deformation, built directly on the finer mesh
  // the variant carries (elements_per_member times 4), shear areas A / 2.
  PlaneFrameSpec sheared = spec;
  sheared.theory = BeamTheory::kTimoshenko;
  sheared.elements_per_member = 8;
  sheared.column_shear_area = spec.column.A / 2;
  sheared.beam_shear_area = spec.beam.A / 2;
  const Structure timoshenko = BuildPlaneFrameStructure(sheared);
  const Eigen::VectorXd f_t =
      SolveModes(timoshenko.stiffness, timoshenko.mass).FrequenciesHz().head(4);
  const Eigen::VectorXd change =
      FormVariantChange(model, model.form_variants[0], {d}, options);
  ASSERT_EQ(change.size(), 4);
  double largest = 0;
  for (int k = 0; k < 4; ++k) {
    // lambda rows: (lambda / lambda_meas - 1) / (2 sigma_f); d lambda / lambda
    // is twice d f / f to first order.
    const double first_order = change[k] * frequency_sigma;
    const double exact = f_t[k] / d.frequencies_hz[k] - 1;
    EXPECT_LT(exact, 0) << k;  // shear makes every mode softer
    EXPECT_NEAR(first_order, exact, 0.1 * std::abs(exact) + 2e-4) << k;
    largest = std::max(largest, std::abs(first_order));
  }
  EXPECT_NEAR(allowances[0].max_frequency_change, largest, 1e-15);
  EXPECT_NEAR(allowances[0].noise_units, change.norm(), 1e-12 * change.norm());

  // Whitened, the shear variant's own change costs less than one unit of
  // squared noise: it is one standard deviation of the form error.
  Eigen::VectorXd u = change;
  form.Whiten(&u, nullptr);
  EXPECT_LT(u.squaredNorm(), 1.0);
  EXPECT_GT(change.squaredNorm(), 1.0);
}

}  // namespace
}  // namespace femup

namespace femup {
namespace {

// An eight-storey shear building measured as its own lowest four modes, with
// shapes at four floors: its flexural variants (BuildSpringMassChain's
// shear_building) move the shapes at the sensors as well as the frequencies.
// Each variant's change, to first order, against the residuals of the chain
// built with the variant's stiffness (its own modes, paired with the data by
// the engine); allowed for on the frequencies alone, the shapes' rows are left
// as they were and the variant's change of them still costs its full square;
// with shapes_too, every row is covered and the change costs less than one
// unit of squared noise, as the covariance over all rows written out says.
TEST(ModelFormError, AllowsForAShearBuildingsFlexureOnItsShapesToo) {
  ChainSpec spec = fixtures::UniformChain(8, 1e5, 2e8);
  spec.shear_building = true;
  const Structure chain = BuildSpringMassChain(spec);
  ASSERT_EQ(chain.form_variants.size(), 2u);
  const Modes nominal = SolveModes(chain.stiffness, chain.mass);
  ModalData d;
  d.state = "air";
  d.frequencies_hz = nominal.FrequenciesHz().head(4);
  d.sensor_dofs = {1, 3, 5, 7};
  d.shapes.resize(4, 4);
  for (int s = 0; s < 4; ++s)
    d.shapes.row(s) =
        nominal.shapes.row(d.sensor_dofs[static_cast<std::size_t>(s)]).head(4);
  EigenSensitivityOptions options;
  const double frequency_sigma = 0.002;
  options.frequency_sigma = 2 * frequency_sigma;
  const NonlinearProblem problem = NominalOutputErrorProblem(chain, {}, {d}, options);
  const std::vector<char> is_frequency = FrequencyRows(problem);
  const auto rows = static_cast<Eigen::Index>(is_frequency.size());
  ASSERT_EQ(std::count(is_frequency.begin(), is_frequency.end(), 1), 4);
  ASSERT_GT(rows, 4);

  std::vector<Eigen::VectorXd> changes;
  for (const FormVariant& v : chain.form_variants) {
    const Eigen::VectorXd change = FormVariantChange(chain, v, {d}, options);
    ASSERT_EQ(change.size(), rows);
    Structure varied = chain;
    varied.stiffness = v.stiffness;
    Eigen::VectorXd exact;
    std::string why;
    ASSERT_TRUE(NominalOutputErrorProblem(varied, {}, {d}, options)
                    .evaluate(Eigen::VectorXd::Zero(1), &exact, nullptr, &why))
        << why;
    // A stiffening of up to a tenth of a storey's: first order to within a
    // tenth of the change, frequencies and shapes alike.
    EXPECT_LT((change - exact).norm(), 0.1 * exact.norm()) << v.name;
    // It moves the shapes at the sensors by more than their noise.
    double shape_change = 0;
    for (Eigen::Index r = 0; r < rows; ++r)
      if (!is_frequency[static_cast<std::size_t>(r)]) shape_change += exact[r] * exact[r];
    EXPECT_GT(shape_change, 2.0) << v.name;
    changes.push_back(change);
  }

  const ModelFormError on_frequencies =
      ModelFormError::Measure(chain, chain.form_variants, {d}, options, is_frequency,
                              false, frequency_sigma, nullptr);
  std::vector<FormErrorAllowance> allowances;
  const ModelFormError on_all =
      ModelFormError::Measure(chain, chain.form_variants, {d}, options, is_frequency,
                              true, frequency_sigma, &allowances);
  std::vector<int> frequency_rows, shape_rows;
  for (int r = 0; r < static_cast<int>(rows); ++r)
    (is_frequency[static_cast<std::size_t>(r)] ? frequency_rows : shape_rows)
        .push_back(r);
  EXPECT_EQ(on_frequencies.covered_rows(), frequency_rows);
  EXPECT_EQ(on_all.covered_rows().size(), static_cast<std::size_t>(rows));
  // The report's sizes are the frequencies' either way.
  ASSERT_EQ(allowances.size(), 2u);
  EXPECT_NEAR(allowances[0].noise_units, changes[0](frequency_rows).norm(), 1e-12);

  Eigen::MatrixXd c = Eigen::MatrixXd::Identity(rows, rows);
  for (const Eigen::VectorXd& u : changes) c += u * u.transpose();
  const Eigen::MatrixXd c_inv = c.fullPivLu().inverse();
  for (const Eigen::VectorXd& u : changes) {
    Eigen::VectorXd w = u;
    on_frequencies.Whiten(&w, nullptr);
    EXPECT_EQ(w(shape_rows), u(shape_rows));
    EXPECT_GT(w.squaredNorm(), 1.0);
    w = u;
    on_all.Whiten(&w, nullptr);
    EXPECT_NEAR(w.squaredNorm(), u.dot(c_inv * u), 1e-9 * u.squaredNorm());
    EXPECT_LT(w.squaredNorm(), 1.0);
  }
}

// A stated uncertainty of the model's overall stiffness (or mass) scales every
// eigenvalue by (1 + s) exactly: each frequency row (a lambda row, in units of
// 2 sigma_f relative) moves by s / (2 sigma_f), the same on every mode, and the
// allowance's largest relative frequency change is s / 2.
TEST(StatedUncertaintyVariants, MoveEveryFrequencyAlike) {
  const Structure chain = BuildSpringMassChain(fixtures::UniformChain(5, 1e5, 2e8));
  const std::vector<FormVariant> none = StatedUncertaintyVariants(chain, 0, 0);
  EXPECT_TRUE(none.empty());
  const std::vector<FormVariant> both = StatedUncertaintyVariants(chain, 0.02, 0.01);
  ASSERT_EQ(both.size(), 2u);
  EXPECT_NE(both[0].name.find("stiffness (2 %)"), std::string::npos) << both[0].name;
  EXPECT_NE(both[1].name.find("mass (1 %)"), std::string::npos) << both[1].name;

  const Modes nominal = SolveModes(chain.stiffness, chain.mass);
  ModalData d;
  d.state = "air";
  d.frequencies_hz = nominal.FrequenciesHz().head(3);
  EigenSensitivityOptions options;
  const double frequency_sigma = 0.002;
  options.frequency_sigma = 2 * frequency_sigma;
  const std::vector<char> is_frequency(3, 1);
  for (std::size_t k = 0; k < both.size(); ++k) {
    const Eigen::VectorXd change = FormVariantChange(chain, both[k], {d}, options);
    const double s = k == 0 ? 0.02 : -0.01;  // a heavier model is a softer one
    ASSERT_EQ(change.size(), 3);
    for (int m = 0; m < 3; ++m)
      EXPECT_NEAR(change[m], s / (2 * frequency_sigma), 1e-9) << k << " " << m;
  }
  std::vector<FormErrorAllowance> allowances;
  const ModelFormError form = ModelFormError::Measure(
      chain, both, {d}, options, is_frequency, false, frequency_sigma, &allowances);
  ASSERT_TRUE(form.Active());
  EXPECT_EQ(form.NumDirections(), 1);  // both along the uniform change
  ASSERT_EQ(allowances.size(), 2u);
  EXPECT_NEAR(allowances[0].max_frequency_change, 0.01, 1e-12);
  EXPECT_NEAR(allowances[1].max_frequency_change, 0.005, 1e-12);
  EXPECT_NEAR(allowances[0].noise_units, std::sqrt(3.0) * 5.0, 1e-8);

  // The covariance I + u u' with u = 5 (1, 1, 1) + (-2.5) (1, 1, 1): a uniform
  // residual of 1 per row is whitened to 1 / sqrt(1 + 3 (5^2 + 2.5^2)) along
  // its direction.
  Eigen::VectorXd r = Eigen::VectorXd::Ones(3);
  form.Whiten(&r, nullptr);
  EXPECT_NEAR(r.squaredNorm(), 3.0 / (1 + 3 * (25 + 6.25)), 1e-12);
}

}  // namespace
}  // namespace femup
