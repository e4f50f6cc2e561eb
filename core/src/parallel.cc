#include "femup/core/parallel.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <limits>
#include <mutex>
#include <optional>
#include <system_error>
#include <thread>
#include <vector>

namespace femup {
namespace {

// True on a thread while it runs the body of a parallel loop of more than one
// thread: a loop started there runs on that thread alone (the blind benchmark's
// cases in parallel, each ranking its effects, do not start threads squared).
thread_local bool tls_in_parallel_loop = false;

struct InParallelLoop {
  bool previous = tls_in_parallel_loop;
  InParallelLoop() { tls_in_parallel_loop = true; }
  ~InParallelLoop() { tls_in_parallel_loop = previous; }
};

}  // namespace

int DefaultThreadCount() {
  const unsigned n = std::thread::hardware_concurrency();
  return n == 0 ? 1 : static_cast<int>(n);
}

int ParallelWorkers(int count, int threads) {
  if (count <= 0) return 0;
  if (tls_in_parallel_loop) return 1;
  if (threads < 1) threads = DefaultThreadCount();
  return std::min(threads, count);
}

void ParallelFor(int count, int threads, const std::function<void(int)>& body,
                 const ProgressCallback& progress) {
  ParallelForWorkers(
      count, threads, [&body](int i, int /*worker*/) { body(i); }, progress);
}

void ParallelForWorkers(int count, int threads,
                        const std::function<void(int index, int worker)>& body,
                        const ProgressCallback& progress) {
  if (count <= 0) return;
  const int pool_size = ParallelWorkers(count, threads);
  std::atomic<int> next{0}, done{0};
  // Lowest failing index so far; indices above it are not started.
  std::atomic<int> failed{std::numeric_limits<int>::max()};
  std::mutex error_mutex;
  std::exception_ptr error;
  const auto worker = [&](int id) {
    std::optional<InParallelLoop> nested;
    if (pool_size > 1) nested.emplace();
    for (int i = next++; i < count; i = next++) {
      if (i > failed) break;
      try {
        body(i, id);
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (i < failed) {
          failed = i;
          error = std::current_exception();
        }
        continue;
      }
      const int finished = ++done;
      if (progress) progress(finished, count);
    }
  };
  if (pool_size == 1) {
    worker(0);
  } else {
    std::vector<std::thread> pool;
    pool.reserve(static_cast<std::size_t>(pool_size - 1));
    for (int t = 1; t < pool_size; ++t) {
      try {
        pool.emplace_back(worker, t);
      } catch (const std::system_error&) {
        break;  // no more threads to be had: the ones started share the work
      }
    }
    worker(0);  // the calling thread works too
    for (std::thread& t : pool) t.join();
  }
  if (error) std::rethrow_exception(error);
}

}  // namespace femup
