// Test helper: runs a computation `runs` times on each of `threads` threads at
// once and expects every run to give the bits of a run alone. `same_as_alone`
// runs the computation once and says whether its result equals the result
// computed before on one thread.
#pragma once

#include <gtest/gtest.h>

#include <cstddef>
#include <functional>
#include <thread>
#include <vector>

namespace femup::testing {

inline void ExpectSameBitsOnThreads(int threads, int runs,
                                    const std::function<bool()>& same_as_alone) {
  std::vector<int> differing(static_cast<std::size_t>(threads), 0);
  std::vector<std::thread> workers;
  for (int t = 0; t < threads; ++t) {
    workers.emplace_back([&, t] {
      for (int k = 0; k < runs; ++k) {
        if (!same_as_alone()) ++differing[static_cast<std::size_t>(t)];
      }
    });
  }
  for (std::thread& worker : workers) worker.join();
  for (int t = 0; t < threads; ++t)
    EXPECT_EQ(differing[static_cast<std::size_t>(t)], 0)
        << "runs of thread " << t << " of " << threads << " that differ from a run alone";
}

}  // namespace femup::testing
