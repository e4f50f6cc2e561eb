// The BLAS femup is linked against (femup/core/linalg/blas.h): the one CMake
// chose (FEMUP_BLAS_VENDOR), its threads set and read back, bad input named.
#include "femup/core/linalg/blas.h"

#include <gtest/gtest.h>

#include <string>

#include "expect_error.h"

namespace femup {
namespace {

TEST(Blas, IsTheVendorCMakeChose) {
  const BlasInfo blas = CurrentBlas();
  const std::string vendor = FEMUP_TEST_BLAS_VENDOR;
  if (vendor == "OpenBLAS") {
    // The library's own configuration string: the symbols are OpenBLAS's.
    EXPECT_EQ(blas.name.rfind("OpenBLAS", 0), 0u) << blas.name;
    EXPECT_TRUE(blas.threads_settable);
  } else {
    EXPECT_EQ(blas.name, vendor);
    EXPECT_FALSE(blas.threads_settable);
  }
}

TEST(Blas, ThreadsAreSetAndReadBack) {
  if (!CurrentBlas().threads_settable) {
    EXPECT_FALSE(SetBlasThreads(2));
    return;
  }
  ASSERT_TRUE(SetBlasThreads(2));
  EXPECT_EQ(CurrentBlas().threads, 2);
  EXPECT_NE(BlasSummary().find("2 threads per call"), std::string::npos) << BlasSummary();
  UseOneBlasThreadPerCaller();
  EXPECT_EQ(CurrentBlas().threads, 1);
  EXPECT_EQ(BlasSummary().rfind("BLAS: OpenBLAS", 0), 0u) << BlasSummary();
  EXPECT_NE(BlasSummary().find(", 1 thread per call"), std::string::npos)
      << BlasSummary();
}

// Where OpenBLAS chose kernels older than the processor's, the better core
// is named, and the summary says how to get it; otherwise nothing is named.
TEST(Blas, BetterKernelsAreNamedOnlyWhereOpenBlasChoseOlderOnes) {
  const BlasInfo blas = CurrentBlas();
  const std::string better = BetterBlasCoreType();
  EXPECT_TRUE(better.empty() || better == "SkylakeX" || better == "Haswell") << better;
  if (!blas.threads_settable) {
    EXPECT_TRUE(blas.core.empty());
    EXPECT_TRUE(better.empty());
    return;
  }
  EXPECT_FALSE(blas.core.empty());
  const bool older =
      blas.core == "Prescott" || blas.core == "Core2" || blas.core == "Penryn" ||
      blas.core == "Nehalem" || blas.core == "Sandybridge" || blas.core == "Dunnington" ||
      blas.core == "Atom" || blas.core == "Nano" || blas.core == "Opteron" ||
      blas.core == "Barcelona" || blas.core == "Bobcat" || blas.core == "Bulldozer" ||
      blas.core == "Piledriver";
  if (!older) {
    EXPECT_EQ(better, "") << blas.core;
  }
  if (better.empty()) {
    EXPECT_EQ(BlasSummary().find("OPENBLAS_CORETYPE"), std::string::npos)
        << BlasSummary();
  } else {
    EXPECT_NE(BlasSummary().find("set OPENBLAS_CORETYPE=" + better), std::string::npos)
        << BlasSummary();
  }
}

TEST(Blas, RejectsFewerThanOneThread) {
  femup::testing::ExpectError([] { SetBlasThreads(0); }, {"threads", "at least 1", "0"});
  femup::testing::ExpectError([] { SetBlasThreads(-3); }, {"threads", "-3"});
}

}  // namespace
}  // namespace femup
