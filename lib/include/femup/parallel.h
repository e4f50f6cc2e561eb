// Parallel loops on one machine, with results that do not depend on the
// number of threads: ParallelFor runs body(i) for every i in [0, count) on up
// to `threads` threads, each index exactly once, in no particular order. The
// body must write only to what index i owns (its own slot of an output vector,
// its own rows of a matrix); reductions are then done by the caller in index
// order, so a run with 1 thread and a run with 8 give the same bits.
#pragma once

#include <functional>

namespace femup {

// Threads to use when the caller asks for 0: std::thread::hardware_concurrency()
// (at least 1).
int DefaultThreadCount();

// Runs body(0), ..., body(count - 1) on min(threads, count) threads (threads
// < 1: DefaultThreadCount()); with 1 thread, in order on the calling thread.
// An exception thrown by a body stops the loop from starting further indices;
// once every thread has finished, the exception of the lowest index that threw
// is rethrown (the same one whatever the thread count, when bodies that throw
// do so independently of each other).
void ParallelFor(int count, int threads, const std::function<void(int)>& body);

}  // namespace femup
