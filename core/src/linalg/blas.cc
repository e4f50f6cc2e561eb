#include "femup/core/linalg/blas.h"

#include <unistd.h>

#include <cctype>
#include <cstdlib>
#include <set>
#include <string>

#include "femup/core/errors.h"

#ifdef FEMUP_BLAS_OPENBLAS
// OpenBLAS's own interface (cblas.h declares it too; these need nothing else
// from it).
extern "C" {
void openblas_set_num_threads(int num_threads);
int openblas_get_num_threads(void);
char* openblas_get_config(void);
char* openblas_get_corename(void);
}
#endif

#ifndef FEMUP_BLAS_VENDOR_NAME
#define FEMUP_BLAS_VENDOR_NAME "unknown"
#endif

namespace femup {

BlasInfo CurrentBlas() {
  BlasInfo info;
#ifdef FEMUP_BLAS_OPENBLAS
  const char* config = openblas_get_config();
  info.name = config != nullptr ? config : "OpenBLAS";
  const char* core = openblas_get_corename();
  info.core = core != nullptr ? core : "";
  info.threads = openblas_get_num_threads();
  info.threads_settable = true;
#else
  info.name = FEMUP_BLAS_VENDOR_NAME;
#endif
  return info;
}

bool SetBlasThreads(int threads) {
  if (threads < 1) {
    throw InputError("threads", "the BLAS's threads must be at least 1, not " +
                                    std::to_string(threads));
  }
#ifdef FEMUP_BLAS_OPENBLAS
  openblas_set_num_threads(threads);
  return true;
#else
  return false;
#endif
}

void UseOneBlasThreadPerCaller() { SetBlasThreads(1); }

std::string BetterBlasCoreType() {
  // OpenBLAS's x86-64 cores without AVX2 kernels (its names, lower case as
  // openblas_get_corename gives them).
  static const std::set<std::string> kOlder = {
      "prescott",    "core2",     "penryn",    "dunnington", "nehalem",
      "sandybridge", "atom",      "nano",      "opteron",    "barcelona",
      "bobcat",      "bulldozer", "piledriver"};
  const std::string core = CurrentBlas().core;
  std::string lower;
  for (char c : core)
    lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (kOlder.count(lower) == 0) return "";
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
  __builtin_cpu_init();
  if (!__builtin_cpu_supports("avx2") || !__builtin_cpu_supports("fma")) return "";
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") &&
      __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512vl")) {
    return "SkylakeX";
  }
  return "Haswell";
#else
  return "";
#endif
}

void RestartWithBetterBlasKernels(char** argv) {
  if (std::getenv("OPENBLAS_CORETYPE") != nullptr) return;
  const std::string core = BetterBlasCoreType();
  if (core.empty() || argv == nullptr || argv[0] == nullptr) return;
  if (::setenv("OPENBLAS_CORETYPE", core.c_str(), 1) != 0) return;
  ::execv("/proc/self/exe", argv);
  ::unsetenv("OPENBLAS_CORETYPE");  // not started again: OpenBLAS's choice stands
}

void SetUpBlasForProgram(char** argv) {
  RestartWithBetterBlasKernels(argv);
  UseOneBlasThreadPerCaller();
}

std::string BlasSummary() {
  const BlasInfo blas = CurrentBlas();
  std::string line = "BLAS: " + blas.name;
  if (blas.threads > 0) {
    line += ", " + std::to_string(blas.threads) +
            (blas.threads == 1 ? " thread per call" : " threads per call");
  }
  const std::string better = BetterBlasCoreType();
  if (!better.empty()) {
    line += " (" + blas.core + " kernels on a processor that runs " + better +
            "'s: set OPENBLAS_CORETYPE=" + better + " before starting the program)";
  }
  return line;
}

}  // namespace femup
