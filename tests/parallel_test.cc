// ParallelFor (parallel.h): every index once, the same results whatever the
// thread count, and the exception of the lowest failing index.
#include "femup/core/parallel.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace femup {
namespace {

TEST(ParallelFor, RunsEveryIndexOnceWhateverTheThreadCount) {
  for (int threads : {1, 2, 3, 8, 0}) {
    std::vector<int> hits(1000, 0);
    std::vector<double> out(1000, 0.0);
    ParallelFor(1000, threads, [&](int i) {
      ++hits[i];
      out[i] = std::sin(0.01 * i);
    });
    for (int i = 0; i < 1000; ++i) {
      EXPECT_EQ(hits[i], 1) << "threads " << threads << ", index " << i;
      EXPECT_EQ(out[i], std::sin(0.01 * i));
    }
  }
}

TEST(ParallelFor, ReportsProgressAfterEveryIndex) {
  for (int threads : {1, 2, 3, 8}) {
    std::vector<int> hits(37, 0);
    std::atomic<int> reports{0};
    std::atomic<int> last{0};
    ParallelFor(
        37, threads, [&](int i) { hits[static_cast<std::size_t>(i)] += 1; },
        [&](int done, int total) {
          EXPECT_EQ(total, 37);
          EXPECT_GE(done, 1);
          EXPECT_LE(done, 37);
          ++reports;
          int seen = last.load();
          while (done > seen && !last.compare_exchange_weak(seen, done)) {
          }
        });
    EXPECT_EQ(hits, std::vector<int>(37, 1)) << threads;
    EXPECT_EQ(reports.load(), 37);
    EXPECT_EQ(last.load(), 37);
  }
}

// A loop inside a parallel loop's body runs on that body's thread alone.
TEST(ParallelFor, NestedLoopsRunOnTheirCallingThread) {
  std::vector<int> inner_workers(4, -1);
  ParallelFor(4, 2, [&](int i) {
    inner_workers[static_cast<std::size_t>(i)] = ParallelWorkers(8, 8);
    std::vector<int> seen(8, 0);
    ParallelFor(8, 8, [&](int j) { seen[static_cast<std::size_t>(j)] += 1; });
    for (int v : seen) EXPECT_EQ(v, 1);
  });
  for (int w : inner_workers) EXPECT_EQ(w, 1);
  // Outside any loop the count is what was asked for again.
  EXPECT_EQ(ParallelWorkers(8, 3), 3);
  // A loop on one thread does not mark its body as nested.
  int inner = 0;
  ParallelFor(1, 4, [&](int) { inner = ParallelWorkers(8, 3); });
  EXPECT_EQ(inner, 3);
}

TEST(ParallelFor, NothingToDo) {
  std::atomic<int> calls{0};
  ParallelFor(0, 4, [&](int) { ++calls; });
  ParallelFor(-3, 4, [&](int) { ++calls; });
  EXPECT_EQ(calls.load(), 0);
  EXPECT_GE(DefaultThreadCount(), 1);
}

TEST(ParallelFor, RethrowsTheLowestFailingIndex) {
  for (int threads : {1, 2, 4}) {
    try {
      ParallelFor(200, threads, [](int i) {
        if (i == 37 || i == 150) throw std::runtime_error("index " + std::to_string(i));
      });
      ADD_FAILURE() << "no exception";
    } catch (const std::runtime_error& e) {
      EXPECT_EQ(std::string(e.what()), "index 37") << "threads " << threads;
    }
  }
}

// ParallelForWorkers: worker ids in range, never two indices of one worker at
// once (each worker's flag is set for the duration of its body), every index once.
TEST(ParallelForWorkers, WorkersNeverOverlap) {
  for (int threads : {1, 2, 4}) {
    const int count = 500;
    const int workers = ParallelWorkers(count, threads);
    EXPECT_EQ(workers, std::min(threads, count));
    std::vector<std::atomic<int>> busy(static_cast<std::size_t>(workers));
    for (auto& b : busy) b = 0;
    std::vector<int> hits(count, 0);
    std::atomic<int> overlaps{0}, out_of_range{0};
    ParallelForWorkers(count, threads, [&](int i, int worker) {
      if (worker < 0 || worker >= workers) {
        ++out_of_range;
        return;
      }
      if (busy[static_cast<std::size_t>(worker)].exchange(1) != 0) ++overlaps;
      double x = 0;
      for (int k = 0; k < 2000; ++k) x += std::sin(k + i);
      hits[i] += x > 1e9 ? 2 : 1;
      busy[static_cast<std::size_t>(worker)] = 0;
    });
    EXPECT_EQ(overlaps.load(), 0) << threads;
    EXPECT_EQ(out_of_range.load(), 0) << threads;
    for (int i = 0; i < count; ++i) EXPECT_EQ(hits[i], 1) << i;
  }
  EXPECT_EQ(ParallelWorkers(0, 4), 0);
  EXPECT_EQ(ParallelWorkers(3, 8), 3);
  EXPECT_GE(ParallelWorkers(100, 0), 1);  // 0: the hardware's count
}

}  // namespace
}  // namespace femup
