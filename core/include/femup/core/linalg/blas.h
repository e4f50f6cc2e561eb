// The BLAS and LAPACK femup runs on, its kernels and its own threads.
//
// femup is linked against Debian's OpenBLAS (CMake's FEMUP_BLAS_VENDOR,
// default OpenBLAS; scripts/setup.sh installs its thread-safe pthread
// flavour; docs/benchmarks.md "The BLAS" measures it against ATLAS).
//
// Threads: femup parallelises above the BLAS, on its own threads (`--threads`,
// ParallelFor), with results that do not depend on their number; a BLAS that
// splits one call over threads may sum in another order for another thread
// count. So every entry point (the command line, the Python module, the tests
// and benchmarks) runs the BLAS on one thread per caller:
// UseOneBlasThreadPerCaller().
//
// Kernels: OpenBLAS picks its kernels for the processor when it is loaded.
// Debian 12's OpenBLAS (0.3.21) does not know processors newer than itself
// (an Intel Xeon of family 6, model 207, here) and falls back to its oldest
// x86-64 kernels (Prescott: SSE3): dgemm at 15.5 GFLOP/s there against 68
// with the AVX-512 kernels that processor runs (scripts/blas_compare.sh).
// BetterBlasCoreType() names those, and a program's main can start itself again with them
// (RestartWithBetterBlasKernels): OpenBLAS reads OPENBLAS_CORETYPE only when
// it is loaded.
#pragma once

#include <string>

namespace femup {

struct BlasInfo {
  // "OpenBLAS 0.3.21 ..." (the library's own configuration string), or the
  // vendor CMake was given when the library cannot say ("ATLAS", "Generic").
  std::string name;
  // The kernels OpenBLAS chose ("SkylakeX", "Haswell", "Prescott"); "" for
  // another BLAS.
  std::string core;
  // The BLAS's threads per call; 0 when the BLAS cannot say.
  int threads = 0;
  // Whether femup can set the BLAS's threads (OpenBLAS).
  bool threads_settable = false;
};

BlasInfo CurrentBlas();

// Sets the BLAS's threads per call (>= 1, else InputError naming "threads").
// Returns false, changing nothing, when the BLAS offers no way to set them.
bool SetBlasThreads(int threads);

// SetBlasThreads(1): the entry points' call.
void UseOneBlasThreadPerCaller();

// The OpenBLAS core type whose kernels this processor runs, when OpenBLAS
// chose kernels older than AVX2 on a processor with AVX2 and FMA: "SkylakeX"
// where the processor has AVX-512 (F, DQ, BW, VL), else "Haswell". "" when
// OpenBLAS's choice stands, or the BLAS is another.
std::string BetterBlasCoreType();

// For a program's main, before it does anything else: when
// BetterBlasCoreType() names a core and OPENBLAS_CORETYPE is not set (by the
// user, or by this function in the process it replaced), sets it and starts
// the program again (execv of /proc/self/exe with the same arguments). Returns
// only when there is nothing to do or the start failed (the program then goes
// on with OpenBLAS's own choice).
void RestartWithBetterBlasKernels(char** argv);

// What a program's main calls first: RestartWithBetterBlasKernels(argv), then
// UseOneBlasThreadPerCaller().
void SetUpBlasForProgram(char** argv);

// One line for `femup --version` and reports: "BLAS: OpenBLAS 0.3.21 ...,
// 1 thread per call", and a hint where the kernels are older than the
// processor's.
std::string BlasSummary();

}  // namespace femup
