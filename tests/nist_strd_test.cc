// The NIST StRD readers and problems, checked against NIST's certified values
// (never against earlier output of this code): the counts stated in each file,
// the residual statistics at the certified parameters, the certified standard
// deviations, and the analytic Jacobians against finite differences.
#include "femup/evaluation/nist_strd.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <ostream>
#include <string>
#include <vector>

#include "expect_error.h"
#include "femup/core/errors.h"

namespace femup {
namespace {

namespace fs = std::filesystem;

const std::string kNistDir = std::string(FEMUP_TEST_DATA_DIR) + "/nist";

std::string LinearFile(const std::string& name) {
  return kNistDir + "/linear/" + name + ".dat";
}
std::string NonlinearFile(const std::string& name) {
  return kNistDir + "/nonlinear/" + name + ".dat";
}

// A file under the test temporary directory, private to the running test,
// removed at the end.
class ScratchFile {
 public:
  explicit ScratchFile(const std::string& stem) {
    const ::testing::TestInfo* test =
        ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = std::string("femup_nist_") + test->test_suite_name() + "_" +
                       test->name() + "_" + std::to_string(::getpid()) + "_" + stem;
    for (char& c : name) {
      if (c == '/') c = '_';
    }
    path_ = (fs::path(::testing::TempDir()) / name).string();
  }
  ScratchFile(const ScratchFile&) = delete;
  ScratchFile& operator=(const ScratchFile&) = delete;
  ~ScratchFile() {
    std::error_code ignored;
    fs::remove(path_, ignored);
  }
  const std::string& path() const { return path_; }
  void Write(const std::vector<std::string>& lines) const {
    std::ofstream out(path_, std::ios::binary);
    for (const std::string& line : lines) out << line << "\r\n";
  }

 private:
  std::string path_;
};

std::vector<std::string> ReadLines(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::vector<std::string> lines;
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(line);
  }
  return lines;
}

// The InputError message from `read`, or "" when it does not throw.
template <typename Read>
std::string ErrorOf(Read read) {
  return testing::InputErrorMessage(read);
}

// ---------------------------------------------------------------------------
// Linear sets.

// As stated in each file's header ("Data:" and "Model:" sections).
struct LinearExpected {
  const char* name;
  int observations;
  int parameters;
  int predictors;
  int degree;  // 0: one column per predictor (Longley)
  bool intercept;
  const char* difficulty;
};

const LinearExpected kLinear[] = {
    {"Norris", 36, 2, 1, 1, true, "Lower"},    {"Pontius", 40, 3, 1, 2, true, "Lower"},
    {"NoInt1", 11, 1, 1, 1, false, "Average"}, {"NoInt2", 3, 1, 1, 1, false, "Average"},
    {"Filip", 82, 11, 1, 10, true, "Higher"},  {"Longley", 16, 7, 6, 0, true, "Higher"},
    {"Wampler1", 21, 6, 1, 5, true, "Higher"}, {"Wampler2", 21, 6, 1, 5, true, "Higher"},
    {"Wampler3", 21, 6, 1, 5, true, "Higher"}, {"Wampler4", 21, 6, 1, 5, true, "Higher"},
    {"Wampler5", 21, 6, 1, 5, true, "Higher"},
};

void PrintTo(const LinearExpected& e, std::ostream* os) { *os << e.name; }

class NistLinearTest : public ::testing::TestWithParam<LinearExpected> {};

TEST_P(NistLinearTest, ParsesWithTheStatedCounts) {
  const LinearExpected& e = GetParam();
  const NistLinearDataset d = ReadNistLinear(LinearFile(e.name));
  EXPECT_EQ(d.name, e.name);
  EXPECT_EQ(d.difficulty, e.difficulty);
  EXPECT_EQ(d.num_observations(), e.observations);
  EXPECT_EQ(d.predictors.rows(), e.observations);
  EXPECT_EQ(d.predictors.cols(), e.predictors);
  EXPECT_EQ(d.num_parameters(), e.parameters);
  EXPECT_EQ(d.certified_sd.size(), e.parameters);
  EXPECT_EQ(d.degree, e.degree);
  EXPECT_EQ(d.intercept, e.intercept);
  ASSERT_EQ(static_cast<int>(d.parameter_names.size()), e.parameters);
  for (int j = 0; j < e.parameters; ++j) {
    EXPECT_EQ(d.parameter_names[j], "B" + std::to_string(j + (e.intercept ? 0 : 1)));
  }
  EXPECT_NE(d.model.find("y = "), std::string::npos) << d.model;

  // The design: columns in the order of the certified parameters.
  const MatrixLD A = d.Design<LongDouble>();
  ASSERT_EQ(A.rows(), e.observations);
  ASSERT_EQ(A.cols(), e.parameters);
  for (int i = 0; i < e.observations; ++i) {
    int j = 0;
    if (e.intercept) {
      EXPECT_EQ(A(i, j), 1.0L);
      ++j;
    }
    if (e.degree == 0) {
      for (int c = 0; c < e.predictors; ++c) {
        EXPECT_EQ(A(i, j + c), d.predictors(i, c));
      }
    } else {
      EXPECT_EQ(A(i, j), d.predictors(i, 0));
      if (e.degree >= 2) {
        EXPECT_EQ(A(i, j + 1), d.predictors(i, 0) * d.predictors(i, 0));
      }
    }
  }
}

// Long double at the certified parameters (the certified values have 15
// significant digits): the residual standard deviation, R^2 and the parameter
// standard deviations reproduce NIST's, and the normal-equation gradient vanishes.
// Filip is looser: its residuals (~3e-3) come from cancelling terms of ~1e6, so
// long double (64-bit mantissa) leaves about 11 correct digits.
TEST_P(NistLinearTest, CertifiedValuesAreConsistent) {
  if (std::numeric_limits<LongDouble>::digits < 64) {
    GTEST_SKIP() << "the thresholds assume long double with at least 64 mantissa bits";
  }
  const LinearExpected& e = GetParam();
  const NistLinearDataset d = ReadNistLinear(LinearFile(e.name));
  const bool filip = d.name == "Filip";
  const MatrixLD A = d.Design<LongDouble>();
  const VectorLD& y = d.response;
  const VectorLD r = y - A * d.certified;
  const int n = d.num_observations();
  const int k = d.num_parameters();
  const LongDouble rss = r.squaredNorm();
  const LongDouble s = std::sqrt(rss / (n - k));
  EXPECT_GE(LogRelativeError(s, d.residual_sd), filip ? 10 : 13)
      << "s = " << static_cast<double>(s);

  // R^2 is centred with an intercept, uncentred without (NIST's convention).
  const LongDouble tss =
      d.intercept ? (y.array() - y.mean()).square().sum() : y.squaredNorm();
  EXPECT_GE(LogRelativeError(1 - rss / tss, d.r_squared), filip ? 12 : 13);

  // A'(y - A b) relative to |A_j| |y|.
  const VectorLD g = A.transpose() * r;
  for (int j = 0; j < k; ++j) {
    const LongDouble relative = std::fabs(g(j)) / (A.col(j).norm() * y.norm());
    EXPECT_LE(relative, filip ? 1e-7L : 1e-12L) << d.parameter_names[j];
  }

  // sd_j = s sqrt([(A'A)^-1]_jj), from a column-scaled pivoted QR in long double.
  const VectorLD scale = A.colwise().norm().transpose();
  const MatrixLD scaled = A * scale.cwiseInverse().asDiagonal();
  const Eigen::ColPivHouseholderQR<MatrixLD> qr(scaled);
  ASSERT_EQ(qr.rank(), k);
  const MatrixLD R = qr.matrixR().topLeftCorner(k, k).triangularView<Eigen::Upper>();
  const MatrixLD Rinv = R.triangularView<Eigen::Upper>().solve(MatrixLD::Identity(k, k));
  const MatrixLD cov =
      qr.colsPermutation() * (Rinv * Rinv.transpose()) * qr.colsPermutation().transpose();
  for (int j = 0; j < k; ++j) {
    const LongDouble sd = d.residual_sd * std::sqrt(cov(j, j)) / scale(j);
    EXPECT_GE(LogRelativeError(sd, d.certified_sd(j)), filip ? 10 : 13)
        << d.parameter_names[j];
  }
}

TEST_P(NistLinearTest, ProblemIsTheDoubleDesign) {
  const NistLinearDataset d = ReadNistLinear(LinearFile(GetParam().name));
  const LinearProblem p = d.Problem();
  EXPECT_EQ(p.Validate().ToString(), "");
  EXPECT_EQ(p.A, d.Design<double>());
  EXPECT_EQ(p.b, d.response.cast<double>());
  EXPECT_EQ(p.names, d.parameter_names);
}

std::string LinearTestName(const ::testing::TestParamInfo<LinearExpected>& param) {
  return param.param.name;
}
INSTANTIATE_TEST_SUITE_P(Nist, NistLinearTest, ::testing::ValuesIn(kLinear),
                         LinearTestName);

TEST(NistLinear, ParsesEveryDigit) {
  const NistLinearDataset filip = ReadNistLinear(LinearFile("Filip"));
  EXPECT_EQ(filip.response(0), 0.8116L);
  EXPECT_EQ(filip.predictors(0, 0), -6.860120914L);
  EXPECT_EQ(filip.certified(10), -0.402962525080404E-04L);
  EXPECT_EQ(filip.certified_sd(0), 298.084530995537L);
  EXPECT_EQ(filip.residual_sd, 0.334801051324544E-02L);
  EXPECT_EQ(filip.r_squared, 0.996727416185620L);
  // Design<double> rounds the long double power once.
  EXPECT_EQ(filip.Design<double>()(0, 10),
            static_cast<double>(filip.Design<LongDouble>()(0, 10)));

  const NistLinearDataset longley = ReadNistLinear(LinearFile("Longley"));
  const LongDouble last[] = {70551, 116.9L, 554894, 4007, 2827, 130081, 1962};
  EXPECT_EQ(longley.response(15), last[0]);
  for (int c = 0; c < 6; ++c) EXPECT_EQ(longley.predictors(15, c), last[c + 1]);
  EXPECT_EQ(longley.certified(0), -3482258.63459582L);
}

// ---------------------------------------------------------------------------
// Nonlinear sets.

struct NonlinearExpected {
  const char* name;
  int observations;
  int parameters;
  int predictors;
  const char* difficulty;
};

const NonlinearExpected kNonlinear[] = {
    {"Misra1a", 14, 2, 1, "Lower"},    {"Chwirut2", 54, 3, 1, "Lower"},
    {"Chwirut1", 214, 3, 1, "Lower"},  {"Lanczos3", 24, 6, 1, "Lower"},
    {"Gauss1", 250, 8, 1, "Lower"},    {"Gauss2", 250, 8, 1, "Lower"},
    {"DanWood", 6, 2, 1, "Lower"},     {"Misra1b", 14, 2, 1, "Lower"},
    {"Kirby2", 151, 5, 1, "Average"},  {"Hahn1", 236, 7, 1, "Average"},
    {"Nelson", 128, 3, 2, "Average"},  {"MGH17", 33, 5, 1, "Average"},
    {"Lanczos1", 24, 6, 1, "Average"}, {"Lanczos2", 24, 6, 1, "Average"},
    {"Gauss3", 250, 8, 1, "Average"},  {"Misra1c", 14, 2, 1, "Average"},
    {"Misra1d", 14, 2, 1, "Average"},  {"Roszman1", 25, 4, 1, "Average"},
    {"ENSO", 168, 9, 1, "Average"},    {"MGH09", 11, 4, 1, "Higher"},
    {"Thurber", 37, 7, 1, "Higher"},   {"BoxBOD", 6, 2, 1, "Higher"},
    {"Rat42", 9, 3, 1, "Higher"},      {"MGH10", 16, 3, 1, "Higher"},
    {"Eckerle4", 35, 3, 1, "Higher"},  {"Rat43", 15, 4, 1, "Higher"},
    {"Bennett5", 154, 3, 1, "Higher"},
};

// Residuals and Jacobian of `p` at b; fails the test when evaluate fails.
void Evaluate(const NonlinearProblem& p, const Eigen::VectorXd& b, Eigen::VectorXd* r,
              Eigen::MatrixXd* J) {
  std::string why;
  ASSERT_TRUE(p.evaluate(b, r, J, &why)) << why;
}

// Central differences with steps h = 1e-6 |b_j| against the Jacobian, column by
// column: the largest ratio of |fd - J_j| to what is allowed, `tolerance` |J_j|
// plus the differences' own rounding error, 100 eps |r| / h (this matters where a
// column is tiny against the residuals, as MGH17's exp(-x b5) at start 1).
double JacobianError(const NonlinearProblem& p, const Eigen::VectorXd& b,
                     double tolerance) {
  Eigen::VectorXd r;
  Eigen::MatrixXd J;
  Evaluate(p, b, &r, &J);
  double worst = 0;
  for (Eigen::Index j = 0; j < b.size(); ++j) {
    const double h = 1e-6 * (b(j) != 0 ? std::fabs(b(j)) : 1.0);
    Eigen::VectorXd plus = b, minus = b, r_plus, r_minus;
    plus(j) += h;
    minus(j) -= h;
    Evaluate(p, plus, &r_plus, nullptr);
    Evaluate(p, minus, &r_minus, nullptr);
    const Eigen::VectorXd fd = (r_plus - r_minus) / (plus(j) - minus(j));
    const double allowed = tolerance * J.col(j).norm() +
                           100 * std::numeric_limits<double>::epsilon() * r.norm() / h;
    worst = std::max(worst, (fd - J.col(j)).norm() / allowed);
  }
  return worst;
}

void PrintTo(const NonlinearExpected& e, std::ostream* os) { *os << e.name; }

class NistNonlinearTest : public ::testing::TestWithParam<NonlinearExpected> {};

TEST_P(NistNonlinearTest, ParsesWithTheStatedCounts) {
  const NonlinearExpected& e = GetParam();
  const NistNonlinearDataset d = ReadNistNonlinear(NonlinearFile(e.name));
  EXPECT_EQ(d.name, e.name);
  EXPECT_EQ(d.difficulty, e.difficulty);
  EXPECT_EQ(d.num_observations(), e.observations);
  EXPECT_EQ(d.x.rows(), e.observations);
  EXPECT_EQ(d.x.cols(), e.predictors);
  EXPECT_EQ(d.x_long.rows(), e.observations);
  EXPECT_EQ(d.y_long.size(), e.observations);
  EXPECT_EQ(d.num_parameters(), e.parameters);
  EXPECT_EQ(d.certified_sd.size(), e.parameters);
  EXPECT_EQ(d.certified_long.size(), e.parameters);
  EXPECT_EQ(d.starts.rows(), e.parameters);
  EXPECT_EQ(d.starts.cols(), 2);
  EXPECT_EQ(d.degrees_of_freedom, e.observations - e.parameters);
  ASSERT_EQ(static_cast<int>(d.parameter_names.size()), e.parameters);
  for (int j = 0; j < e.parameters; ++j) {
    EXPECT_EQ(d.parameter_names[j], "b" + std::to_string(j + 1));
  }
  EXPECT_FALSE(d.model.empty());
}

// At the certified parameters the residual sum of squares reproduces NIST's (to
// 9 of its 11 digits; evaluated in long double from the long double data). For
// Lanczos1 (certified RSS 1.4e-25) the 11-digit rounding of the certified
// parameters alone moves the RSS far more than that: there the RSS must lie
// within the bound that rounding allows, (sqrt(RSS) + sum_j |J_j| h_j)^2 with
// h_j half a unit in the 11th digit of b_j.
TEST_P(NistNonlinearTest, CertifiedResidualSumOfSquares) {
  if (std::numeric_limits<LongDouble>::digits < 64) {
    GTEST_SKIP() << "the thresholds assume long double with at least 64 mantissa bits";
  }
  const NistNonlinearDataset d = ReadNistNonlinear(NonlinearFile(GetParam().name));
  const LongDouble rss = NistNonlinearResiduals(d, d.certified_long).squaredNorm();
  if (d.name == "Lanczos1") {
    const NonlinearProblem p = NistNonlinearProblem(d, 1);
    Eigen::VectorXd r;
    Eigen::MatrixXd J;
    Evaluate(p, d.certified, &r, &J);
    LongDouble shift = 0;
    for (int j = 0; j < d.num_parameters(); ++j) {
      const LongDouble b = std::fabs(d.certified_long(j));
      const LongDouble h = 0.5e-10L * std::pow(10.0L, std::floor(std::log10(b)));
      shift += J.col(j).norm() * h;
    }
    const LongDouble root = std::sqrt(d.certified_rss_long);
    EXPECT_LE(std::fabs(rss - d.certified_rss_long),
              (root + shift) * (root + shift) - d.certified_rss_long)
        << "RSS " << static_cast<double>(rss);
    EXPECT_LT(rss, 1e-19L);  // against sum y^2 = 24.6: still 20 digits of fit
  } else {
    EXPECT_GE(LogRelativeError(rss, d.certified_rss_long), 9)
        << "RSS " << static_cast<double>(rss) << ", certified " << d.certified_rss;
    // The double problem too.
    const NonlinearProblem p = NistNonlinearProblem(d, 1);
    Eigen::VectorXd r;
    Evaluate(p, d.certified, &r, nullptr);
    EXPECT_GE(LogRelativeError(r.squaredNorm(), d.certified_rss), 8);
  }
  // The certified residual standard deviation is sqrt(RSS / (n - p)).
  EXPECT_GE(
      LogRelativeError(std::sqrt(d.certified_rss / d.degrees_of_freedom), d.residual_sd),
      9);
}

// The certified standard deviations are those of the linearisation at the
// certified values: sqrt(RSS / (n - p) [(J'J)^-1]_jj), with J from the problem.
TEST_P(NistNonlinearTest, CertifiedStandardDeviations) {
  const NistNonlinearDataset d = ReadNistNonlinear(NonlinearFile(GetParam().name));
  const NonlinearProblem p = NistNonlinearProblem(d, 2);
  Eigen::VectorXd r;
  Eigen::MatrixXd J;
  Evaluate(p, d.certified, &r, &J);
  const int k = d.num_parameters();
  const Eigen::VectorXd scale = J.colwise().norm().transpose();
  const Eigen::MatrixXd scaled = J * scale.cwiseInverse().asDiagonal();
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(scaled);
  ASSERT_EQ(qr.rank(), k);
  const Eigen::MatrixXd R =
      qr.matrixR().topLeftCorner(k, k).triangularView<Eigen::Upper>();
  const Eigen::MatrixXd Rinv =
      R.triangularView<Eigen::Upper>().solve(Eigen::MatrixXd::Identity(k, k));
  const Eigen::MatrixXd cov =
      qr.colsPermutation() * (Rinv * Rinv.transpose()) * qr.colsPermutation().transpose();
  for (int j = 0; j < k; ++j) {
    const double sd = d.residual_sd * std::sqrt(cov(j, j)) / scale(j);
    EXPECT_GE(LogRelativeError(sd, d.certified_sd(j)), 8) << d.parameter_names[j];
  }
}

TEST_P(NistNonlinearTest, JacobianMatchesCentralDifferences) {
  const NistNonlinearDataset d = ReadNistNonlinear(NonlinearFile(GetParam().name));
  for (int start : {1, 2}) {
    const NonlinearProblem p = NistNonlinearProblem(d, start);
    EXPECT_LE(JacobianError(p, d.certified, 1e-6), 1) << "at the certified values";
    EXPECT_LE(JacobianError(p, p.initial, 1e-6), 1) << "at start " << start;
  }
}

TEST_P(NistNonlinearTest, ProblemFields) {
  const NistNonlinearDataset d = ReadNistNonlinear(NonlinearFile(GetParam().name));
  for (int start : {1, 2}) {
    const NonlinearProblem p = NistNonlinearProblem(d, start);
    EXPECT_EQ(p.num_residuals, d.num_observations());
    EXPECT_EQ(p.initial, d.starts.col(start - 1));
    EXPECT_EQ(p.names, d.parameter_names);
    ASSERT_TRUE(static_cast<bool>(p.evaluate));
    // With and without the Jacobian: the same residuals.
    Eigen::VectorXd with_jacobian, without;
    Eigen::MatrixXd J;
    Evaluate(p, p.initial, &with_jacobian, &J);
    Evaluate(p, p.initial, &without, nullptr);
    EXPECT_EQ(J.rows(), d.num_observations());
    EXPECT_EQ(J.cols(), d.num_parameters());
    for (int i = 0; i < d.num_observations(); ++i) {
      EXPECT_NEAR(with_jacobian(i), without(i), 1e-14 * (1 + std::fabs(without(i))));
    }
  }
  EXPECT_NE(ErrorOf([&] { NistNonlinearProblem(d, 3); }).find("start must be 1 or 2"),
            std::string::npos);
  EXPECT_NE(ErrorOf([&] { NistNonlinearProblem(d, 0); }), "");
}

std::string NonlinearTestName(const ::testing::TestParamInfo<NonlinearExpected>& param) {
  return param.param.name;
}
INSTANTIATE_TEST_SUITE_P(Nist, NistNonlinearTest, ::testing::ValuesIn(kNonlinear),
                         NonlinearTestName);

TEST(NistNonlinear, EveryDatasetHasAModel) {
  std::vector<std::string> expected;
  for (const NonlinearExpected& e : kNonlinear) expected.push_back(e.name);
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(NistNonlinearModelNames(), expected);
  std::vector<std::string> files;
  for (const auto& entry : fs::directory_iterator(kNistDir + "/nonlinear")) {
    if (entry.path().extension() == ".dat") files.push_back(entry.path().stem().string());
  }
  std::sort(files.begin(), files.end());
  EXPECT_EQ(files, expected);
}

TEST(NistNonlinear, ParsesEveryDigit) {
  const NistNonlinearDataset nelson = ReadNistNonlinear(NonlinearFile("Nelson"));
  EXPECT_EQ(nelson.y(0), 15.0);
  EXPECT_EQ(nelson.x(0, 0), 1.0);
  EXPECT_EQ(nelson.x(0, 1), 180.0);
  EXPECT_EQ(nelson.starts(1, 1), 0.000000005);
  EXPECT_EQ(nelson.certified_long(1), 5.6177717026E-09L);
  EXPECT_EQ(nelson.certified_rss, 3.7976833176E+00);
  const NistNonlinearDataset lanczos = ReadNistNonlinear(NonlinearFile("Lanczos1"));
  EXPECT_EQ(lanczos.y_long(1), 2.044333373291E+00L);
  EXPECT_EQ(lanczos.certified_rss_long, 1.4307867721E-25L);
  // Roszman1: NIST's b1 (a copy in circulation has 1.20196866396E-0).
  const NistNonlinearDataset roszman = ReadNistNonlinear(NonlinearFile("Roszman1"));
  EXPECT_EQ(roszman.certified_long(0), 2.0196866396E-01L);
}

// Nelson's model is for log(y): the residual is f - log(y).
TEST(NistNonlinear, NelsonResidualIsOnTheLogScale) {
  const NistNonlinearDataset d = ReadNistNonlinear(NonlinearFile("Nelson"));
  const NonlinearProblem p = NistNonlinearProblem(d, 1);
  Eigen::VectorXd r;
  Evaluate(p, d.certified, &r, nullptr);
  const Eigen::VectorXd& b = d.certified;
  for (int i : {0, 64, 127}) {
    const double f = b(0) - b(1) * d.x(i, 0) * std::exp(-b(2) * d.x(i, 1));
    EXPECT_NEAR(r(i), f - std::log(d.y(i)), 1e-14);
  }
}

// The RSS check catches an altered certified value: Roszman1 with b1 changed
// to 1.20196866396E-0, as in a copy of the file that circulates.
TEST(NistNonlinear, ResidualCheckCatchesAnAlteredCertifiedValue) {
  std::vector<std::string> lines = ReadLines(NonlinearFile("Roszman1"));
  ASSERT_GE(lines.size(), 41u);
  const std::string good = "2.0196866396E-01";
  const auto at = lines[40].find(good);
  ASSERT_NE(at, std::string::npos) << lines[40];
  lines[40].replace(at, good.size(), "1.20196866396E-0");
  const ScratchFile altered("Roszman1.dat");
  altered.Write(lines);
  const NistNonlinearDataset d = ReadNistNonlinear(altered.path());
  EXPECT_EQ(d.certified_long(0), 1.20196866396L);
  const LongDouble rss = NistNonlinearResiduals(d, d.certified_long).squaredNorm();
  EXPECT_LT(LogRelativeError(rss, d.certified_rss_long), 1);
}

TEST(NistNonlinear, UnknownDataset) {
  NistNonlinearDataset d = ReadNistNonlinear(NonlinearFile("Misra1a"));
  d.name = "Misra9z";
  const std::string what = ErrorOf([&] { NistNonlinearProblem(d, 1); });
  EXPECT_NE(what.find("Misra9z"), std::string::npos) << what;
  EXPECT_NE(what.find("Bennett5"), std::string::npos) << what;
  EXPECT_NE(what.find("Thurber"), std::string::npos) << what;
  EXPECT_NE(ErrorOf([&] { NistNonlinearResiduals(d, d.certified_long); }), "");
  // A dataset whose sizes do not fit its model.
  NistNonlinearDataset short_one = ReadNistNonlinear(NonlinearFile("Misra1a"));
  short_one.certified.conservativeResize(1);
  EXPECT_NE(ErrorOf([&] { NistNonlinearProblem(short_one, 1); }).find("parameters"),
            std::string::npos);
}

TEST(NistNonlinear, EvaluateReportsNonFiniteValues) {
  const NistNonlinearDataset d = ReadNistNonlinear(NonlinearFile("DanWood"));
  const NonlinearProblem p = NistNonlinearProblem(d, 1);
  Eigen::VectorXd r;
  Eigen::MatrixXd J;
  std::string why;
  Eigen::VectorXd b(2);
  b << std::numeric_limits<double>::quiet_NaN(), 1.0;
  EXPECT_FALSE(p.evaluate(b, &r, &J, &why));
  EXPECT_NE(why.find("DanWood"), std::string::npos) << why;
  EXPECT_NE(why.find("observation 1"), std::string::npos) << why;
  // A parameter vector of the wrong size.
  why.clear();
  EXPECT_FALSE(p.evaluate(Eigen::VectorXd::Ones(3), &r, &J, &why));
  EXPECT_NE(why.find("3 parameters"), std::string::npos) << why;
}

// ---------------------------------------------------------------------------
// Malformed files: the message names the file, the line and what was expected.

TEST(NistMalformed, TruncatedDataNamesFileAndLine) {
  const std::vector<std::string> lines = ReadLines(LinearFile("Filip"));
  ASSERT_EQ(lines.size(), 142u);
  const ScratchFile truncated("Filip.dat");
  truncated.Write(std::vector<std::string>(lines.begin(), lines.begin() + 100));
  const std::string what = ErrorOf([&] { ReadNistLinear(truncated.path()); });
  EXPECT_NE(what.find(truncated.path() + ":101"), std::string::npos) << what;
  EXPECT_NE(what.find("expected data line 41 of 82"), std::string::npos) << what;
  EXPECT_NE(what.find("end of file"), std::string::npos) << what;
}

TEST(NistMalformed, TruncatedCertifiedValues) {
  const std::vector<std::string> lines = ReadLines(NonlinearFile("Gauss1"));
  const ScratchFile truncated("Gauss1.dat");
  truncated.Write(std::vector<std::string>(lines.begin(), lines.begin() + 45));
  const std::string what = ErrorOf([&] { ReadNistNonlinear(truncated.path()); });
  EXPECT_NE(what.find(truncated.path() + ":46"), std::string::npos) << what;
  EXPECT_NE(what.find("expected 8 parameter lines"), std::string::npos) << what;
}

TEST(NistMalformed, BadNumberNamesFileAndLine) {
  std::vector<std::string> lines = ReadLines(NonlinearFile("Misra1a"));
  lines[62] = "      17.9O4E0     141.1E0";  // line 63: letter O for zero
  const ScratchFile bad("Misra1a.dat");
  bad.Write(lines);
  const std::string what = ErrorOf([&] { ReadNistNonlinear(bad.path()); });
  EXPECT_NE(what.find(bad.path() + ":63"), std::string::npos) << what;
  EXPECT_NE(what.find("17.9O4E0"), std::string::npos) << what;
  EXPECT_NE(what.find("response"), std::string::npos) << what;
}

TEST(NistMalformed, WrongColumnCount) {
  std::vector<std::string> lines = ReadLines(LinearFile("Longley"));
  lines[64] = "        63221    96.2   328975   2099     3099    112075";  // x6 missing
  const ScratchFile bad("Longley.dat");
  bad.Write(lines);
  const std::string what = ErrorOf([&] { ReadNistLinear(bad.path()); });
  EXPECT_NE(what.find(bad.path() + ":65"), std::string::npos) << what;
  EXPECT_NE(what.find("7 numbers, found 6"), std::string::npos) << what;
}

TEST(NistMalformed, WrongKindMissingFileAndNotNist) {
  const std::string nonlinear = NonlinearFile("Misra1a");
  std::string what = ErrorOf([&] { ReadNistLinear(nonlinear); });
  EXPECT_NE(what.find(nonlinear + ":9"), std::string::npos) << what;
  EXPECT_NE(what.find("Linear Least Squares Regression"), std::string::npos) << what;

  const std::string missing = kNistDir + "/linear/NoSuchSet.dat";
  what = ErrorOf([&] { ReadNistLinear(missing); });
  EXPECT_NE(what.find(missing), std::string::npos) << what;
  EXPECT_NE(what.find("not found"), std::string::npos) << what;

  const ScratchFile other("other.dat");
  other.Write({"%%MatrixMarket matrix array real general", "1 1", "2.0"});
  what = ErrorOf([&] { ReadNistNonlinear(other.path()); });
  EXPECT_NE(what.find(other.path() + ":1"), std::string::npos) << what;
  EXPECT_NE(what.find("NIST/ITL StRD"), std::string::npos) << what;
}

TEST(NistMalformed, ObservationCountDisagreesWithLineRange) {
  std::vector<std::string> lines = ReadLines(LinearFile("Norris"));
  // "36 Observations" -> "35 Observations".
  bool changed = false;
  for (std::string& line : lines) {
    const auto at = line.find("36 Observations");
    if (at != std::string::npos) {
      line.replace(at, 2, "35");
      changed = true;
    }
  }
  ASSERT_TRUE(changed);
  const ScratchFile bad("Norris.dat");
  bad.Write(lines);
  const std::string what = ErrorOf([&] { ReadNistLinear(bad.path()); });
  EXPECT_NE(what.find(bad.path() + ":61"), std::string::npos) << what;
  EXPECT_NE(what.find("35 observations"), std::string::npos) << what;
}

// ---------------------------------------------------------------------------

TEST(LogRelativeError, KnownValues) {
  EXPECT_NEAR(LogRelativeError(1.0001, 1.0), 4.0, 1e-6);
  EXPECT_NEAR(LogRelativeError(-2.002, -2.0), 3.0, 1e-6);
  EXPECT_NEAR(LogRelativeError(123.456, 123.0), -std::log10(0.456 / 123.0), 1e-12);
  EXPECT_EQ(LogRelativeError(0.5, 0.5), 15.0);          // exact: the cap
  EXPECT_EQ(LogRelativeError(1.0 + 1e-16, 1.0), 15.0);  // beyond 15 digits
  EXPECT_EQ(LogRelativeError(3.0, 1.0), 0.0);           // off by 200 %: 0
  EXPECT_NEAR(LogRelativeError(1e-7, 0.0), 7.0, 1e-9);  // certified 0: -log10|v|
  EXPECT_EQ(LogRelativeError(0.0, 0.0), 15.0);
  EXPECT_EQ(LogRelativeError(std::nan(""), 1.0), 0.0);
  EXPECT_EQ(LogRelativeError(std::numeric_limits<double>::infinity(), 1.0), 0.0);
  EXPECT_NEAR(LogRelativeError(1.000000000001L, 1.0L), 12.0, 1e-6);
  EXPECT_NEAR(LogRelativeError(2.0L + 2e-14L, 2.0L), 14.0, 1e-4);
  EXPECT_EQ(LogRelativeError(std::nanl(""), 1.0L), 0.0);
}

}  // namespace
}  // namespace femup
