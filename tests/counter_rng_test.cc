// CounterRng (core/include/femup/core/counter_rng.h): Random123's published
// known-answer vectors for Philox4x64-10, streams that depend only on
// (seed, stream, substream), and the moments of its normal and uniform draws.
#include "femup/core/counter_rng.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <set>
#include <vector>

namespace femup {
namespace {

// The three philox4x64 10-round vectors of Random123's kat_vectors file.
TEST(CounterRng, Philox4x64MatchesRandom123KnownAnswers) {
  using Ctr = std::array<std::uint64_t, 4>;
  EXPECT_EQ(CounterRng::Philox4x64({0, 0, 0, 0}, {0, 0}),
            (Ctr{0x16554d9eca36314cULL, 0xdb20fe9d672d0fdcULL, 0xd7e772cee186176bULL,
                 0x7e68b68aec7ba23bULL}));
  const std::uint64_t ones = ~0ULL;
  EXPECT_EQ(CounterRng::Philox4x64({ones, ones, ones, ones}, {ones, ones}),
            (Ctr{0x87b092c3013fe90bULL, 0x438c3c67be8d0224ULL, 0x9cc7d7c69cd777b6ULL,
                 0xa09caebf594f0ba0ULL}));
  EXPECT_EQ(CounterRng::Philox4x64({0x243f6a8885a308d3ULL, 0x13198a2e03707344ULL,
                                    0xa4093822299f31d0ULL, 0x082efa98ec4e6c89ULL},
                                   {0x452821e638d01377ULL, 0xbe5466cf34e90c6cULL}),
            (Ctr{0xa528f45403e61d95ULL, 0x38c72dbd566e9788ULL, 0xa5a1610e72fd18b5ULL,
                 0x57bd43b5e52b7fe6ULL}));
}

std::vector<std::uint64_t> First(CounterRng rng, int n) {
  std::vector<std::uint64_t> out;
  for (int i = 0; i < n; ++i) out.push_back(rng());
  return out;
}

TEST(CounterRng, StreamsAreFunctionsOfTheirThreeNumbers) {
  EXPECT_EQ(First(CounterRng(7, 3, 11), 10), First(CounterRng(7, 3, 11), 10));
  std::set<std::vector<std::uint64_t>> distinct;
  for (const CounterRng& r :
       {CounterRng(7, 3, 11), CounterRng(8, 3, 11), CounterRng(7, 4, 11),
        CounterRng(7, 3, 12), CounterRng(7, 11, 3)}) {
    distinct.insert(First(r, 10));
  }
  EXPECT_EQ(distinct.size(), 5u);
  // Numbers follow one another across blocks of four without repeats.
  const std::vector<std::uint64_t> many = First(CounterRng(1, 0, 0), 4000);
  EXPECT_EQ(std::set<std::uint64_t>(many.begin(), many.end()).size(), many.size());
}

// Moments against N(0, 1) and U(-1, 1): 200,000 draws, standard errors of
// the mean 0.0022 (normal) and 0.0013 (uniform); tolerances are 4 of them.
TEST(CounterRng, GaussianAndSymmetricMoments) {
  CounterRng rng(20261124, 0, 0);
  const int n = 200000;
  double s1 = 0, s2 = 0, s4 = 0, u1 = 0, u2 = 0, lo = 1, hi = -1;
  for (int i = 0; i < n; ++i) {
    const double g = rng.Gaussian();
    s1 += g;
    s2 += g * g;
    s4 += g * g * g * g;
    const double u = rng.Symmetric();
    u1 += u;
    u2 += u * u;
    lo = std::min(lo, u);
    hi = std::max(hi, u);
  }
  EXPECT_NEAR(s1 / n, 0.0, 4 * std::sqrt(1.0 / n));
  EXPECT_NEAR(s2 / n, 1.0, 4 * std::sqrt(2.0 / n));
  EXPECT_NEAR(s4 / n, 3.0, 4 * std::sqrt(96.0 / n));  // kurtosis of a normal
  EXPECT_NEAR(u1 / n, 0.0, 4 * std::sqrt(1.0 / 3.0 / n));
  EXPECT_NEAR(u2 / n, 1.0 / 3.0, 4 * std::sqrt(4.0 / 45.0 / n));
  EXPECT_GT(lo, -1.0);
  EXPECT_LT(hi, 1.0);
  EXPECT_LT(lo, -0.999);
  EXPECT_GT(hi, 0.999);
}

}  // namespace
}  // namespace femup
