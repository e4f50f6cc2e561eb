#include "femup/core/counter_rng.h"

#include <Random123/philox.h>

#include <Random123/uniform.hpp>
#include <cmath>

namespace femup {

CounterRng::CounterRng(std::uint64_t seed, std::uint64_t stream, std::uint64_t substream)
    : key_{seed, 0x66656d7570ULL /* "femup": a fixed second key word */},
      counter_{stream, substream, 0},
      block_{0, 0, 0, 0} {}

std::array<std::uint64_t, 4> CounterRng::Philox4x64(
    const std::array<std::uint64_t, 4>& counter,
    const std::array<std::uint64_t, 2>& key) {
  const r123::Philox4x64::ctr_type c = {{counter[0], counter[1], counter[2], counter[3]}};
  const r123::Philox4x64::key_type k = {{key[0], key[1]}};
  const r123::Philox4x64::ctr_type out = r123::Philox4x64()(c, k);
  return {out[0], out[1], out[2], out[3]};
}

void CounterRng::Refill() {
  const std::array<std::uint64_t, 4> out =
      Philox4x64({counter_[0], counter_[1], counter_[2], 0}, {key_[0], key_[1]});
  for (int i = 0; i < 4; ++i) block_[i] = out[i];
  ++counter_[2];
  used_ = 0;
}

double CounterRng::Gaussian() {
  if (has_spare_) {
    has_spare_ = false;
    return spare_;
  }
  // Marsaglia's polar method (as libstdc++'s normal_distribution), on
  // Random123's uniform conversion: no trigonometry, and none of the long
  // double logarithm libstdc++'s generate_canonical takes per number.
  double u, v, s;
  do {
    u = Symmetric();
    v = Symmetric();
    s = u * u + v * v;
  } while (s >= 1.0 || s == 0.0);
  const double factor = std::sqrt(-2.0 * std::log(s) / s);
  spare_ = v * factor;
  has_spare_ = true;
  return u * factor;
}

double CounterRng::Symmetric() { return r123::uneg11<double>((*this)()); }

}  // namespace femup
