// A counter-based random generator for parallel Monte Carlo studies: the
// stream of numbers for a (seed, stream, substream) triple is a pure function of
// those three integers (Random123's Philox4x64-10, Salmon et al., SC'11), so a
// study can give every draw its own generator, create it in nanoseconds (no
// state set-up, unlike seeding std::mt19937_64 through std::seed_seq), and get
// the same numbers whatever the order or thread the draws run on.
// It satisfies the C++11 UniformRandomBitGenerator requirements, so the
// standard distributions take it; Gaussian() (polar method) and Symmetric()
// (Random123's conversion to (-1, 1)) are faster than libstdc++'s
// distributions, whose generate_canonical takes a long double logarithm per
// number.
#pragma once

#include <array>
#include <cstdint>
#include <limits>

namespace femup {

class CounterRng {
 public:
  using result_type = std::uint64_t;

  // `seed` keys the generator; (stream, substream) pick one of 2^128 streams,
  // each 2^66 numbers long (e.g. a noise level and a draw).
  CounterRng(std::uint64_t seed, std::uint64_t stream, std::uint64_t substream);

  static constexpr result_type min() { return 0; }
  static constexpr result_type max() { return std::numeric_limits<result_type>::max(); }

  result_type operator()() {
    if (used_ == 4) Refill();
    return block_[used_++];
  }

  // A standard normal draw (Marsaglia's polar method; the pair's second value
  // is kept for the next call).
  double Gaussian();
  // A uniform draw on (-1, 1).
  double Symmetric();

  // The block function itself: Philox4x64 with 10 rounds of (counter, key),
  // as published with Random123 (its known-answer vectors test it).
  static std::array<std::uint64_t, 4> Philox4x64(
      const std::array<std::uint64_t, 4>& counter,
      const std::array<std::uint64_t, 2>& key);

 private:
  void Refill();  // the next 4 numbers: Philox4x64 of (stream, substream, n)

  std::uint64_t key_[2];
  std::uint64_t counter_[3];  // stream, substream, block number
  std::uint64_t block_[4];
  int used_ = 4;
  double spare_ = 0;
  bool has_spare_ = false;
};

}  // namespace femup
