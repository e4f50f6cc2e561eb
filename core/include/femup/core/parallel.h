// Parallel loops on one machine, with results that do not depend on the
// number of threads: ParallelFor runs body(i) for every i in [0, count) on up
// to `threads` threads, each index exactly once. Indices are handed out in
// increasing order; the body must write only to what index i owns (its own
// slot of an output vector, its own rows of a matrix), and reductions are then
// done by the caller in index order, so a run with 1 thread and a run with 8
// give the same bits. Used by the noise study's draws, the blind benchmark's
// cases and the eigen-sensitivity Jacobian's modes.
#pragma once

#include <functional>

#include "femup/core/progress.h"

namespace femup {

// Threads to use when the caller asks for 0: std::thread::hardware_concurrency()
// (at least 1).
int DefaultThreadCount();

// Runs body(0), ..., body(count - 1) on min(threads, count) threads (threads
// < 1: DefaultThreadCount()); with 1 thread, in order on the calling thread.
// A loop started inside the body of a loop running on several threads runs on
// its calling thread alone (nested loops do not multiply threads).
// When the system gives fewer threads than asked, those it gives share the
// work. `progress`, when set, is called after each index as (indices done,
// count), from the worker threads, possibly concurrently; it must not throw.
// An exception thrown by a body stops the loop from starting higher indices;
// once every thread has finished, the exception of the lowest index that threw
// is rethrown: the one a sequential loop would have thrown.
void ParallelFor(int count, int threads, const std::function<void(int)>& body,
                 const ProgressCallback& progress = {});

// The same, with body(index, worker): worker in [0, ParallelWorkers(count,
// threads)) names the thread running it, and no two calls with the same worker
// run at once, so per-worker work space (a solver's scratch) needs no lock.
// Which worker takes which index varies between runs: the results must not
// depend on it.
int ParallelWorkers(int count, int threads);
void ParallelForWorkers(int count, int threads,
                        const std::function<void(int index, int worker)>& body,
                        const ProgressCallback& progress = {});

}  // namespace femup
