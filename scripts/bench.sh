#!/usr/bin/env bash
# Builds the solver benchmarks (Release, build-bench/) and runs them, writing
# out/bench/:
#   machine.txt   nproc, CPU model, load, compiler, elapsed time (build and runs)
#   solvers.json  Google Benchmark's JSON (--benchmark_out) of bench/solvers_bench.cc
#   solvers.txt   its console output; solvers.md the same results as a Markdown table
#   peer.md       femup's bounded solvers against scipy's lsq_linear
#                 (bench/peer_compare.cc), ratios measured in this one run
#   eigen_peer.md femup's sparse shift-invert eigensolver against scipy's eigsh
#                 on the space frames (bench/eigen_peer_compare.cc), 10 modes:
#                 eigsh with its defaults and with a symmetric-ordering splu as
#                 OPinv (FEMUP_EIGEN_PEERS, default "default,symmetric"; at 10^6
#                 DOF the default one runs out of memory after ~15 min: use
#                 FEMUP_EIGEN_PEERS=symmetric there); femup on
#                 FEMUP_EIGEN_THREADS threads (EigenOptions::threads, default 0:
#                 one per core; 1 runs M's check and K's factorisation in turn)
#   system_peer.md the linear correction-factor system of a 10^5-DOF frame with
#                 10^3 factors and 10 measured modes, femup against scipy
#                 (bench/system_peer_compare.cc), with the memory read bound
#                 and the arithmetic floor; femup's half solves and G on
#                 FEMUP_SYSTEM_THREADS threads (NormalCorrectionOptions::threads,
#                 default 0: one per core)
#   noise_peer.md the paper's noise study (11 levels x 1000 draws) in femup (1
#                 and 2 threads) against the same computation in numpy
#                 (bench/noise_peer_compare.cc), 5 interleaved rounds, with the
#                 Rm averages of both
# Each benchmark runs 3 repetitions of at least FEMUP_BENCH_MIN_TIME seconds
# (default 0.2); the tables give the median and the spread. Environment:
# FEMUP_BENCH_MIN_TIME, FEMUP_PEER_SIZES (default 500x50,2000x200,5000x500),
# FEMUP_EIGEN_PEER_DOFS (default 1e5; 1e5,1e6 adds the 10^6-DOF frame: minutes and
# several GB), FEMUP_SYSTEM_PEER_SIZE (default 1e5), FEMUP_NOISE_PEER_DRAWS
# (default 1000 draws per level), FEMUP_BENCH_JOBS (build jobs, default 2).
set -euo pipefail
cd "$(dirname "$0")/.."
build=build-bench
out=out/bench
min_time=${FEMUP_BENCH_MIN_TIME:-0.2}
sizes=${FEMUP_PEER_SIZES:-500x50,2000x200,5000x500}
eigen_dofs=${FEMUP_EIGEN_PEER_DOFS:-1e5}
eigen_peers=${FEMUP_EIGEN_PEERS:-default,symmetric}
eigen_threads=${FEMUP_EIGEN_THREADS:-0}
system_size=${FEMUP_SYSTEM_PEER_SIZE:-1e5}
system_threads=${FEMUP_SYSTEM_THREADS:-0}
noise_draws=${FEMUP_NOISE_PEER_DRAWS:-1000}

# The compiler flags of the CI's Release build, so that a compiler cache (ccache,
# used when installed) serves this build from that one.
launcher=()
if command -v ccache > /dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DFEMUP_BUILD_TESTS=OFF \
  -DFEMUP_BUILD_BENCHMARKS=ON -DCMAKE_CXX_FLAGS="-Werror" "${launcher[@]}" > /dev/null
cmake --build "$build" --target solvers_bench femup_peer_compare \
  femup_eigen_peer_compare femup_system_peer_compare femup_noise_peer_compare \
  -j "${FEMUP_BENCH_JOBS:-2}"

mkdir -p "$out"
{
  echo "date: $(date -u +%Y-%m-%dT%H:%M:%SZ)"
  echo "nproc: $(nproc)"
  echo "cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ //')"
  echo "load average: $(cut -d' ' -f1-3 /proc/loadavg)"
  echo "compiler: $(c++ --version | head -1)"
  echo "blas: $(readlink -f "$(ldconfig -p | awk '/libblas.so.3 .*x86-64/ {print $NF; exit}')" 2>/dev/null)"
  echo "source: $(git rev-parse --short HEAD 2>/dev/null || echo unknown)$(
    git diff --quiet HEAD 2>/dev/null || echo ' plus uncommitted changes')"
  echo "command: scripts/bench.sh (FEMUP_BENCH_MIN_TIME=$min_time FEMUP_PEER_SIZES=$sizes" \
    "FEMUP_EIGEN_PEER_DOFS=$eigen_dofs FEMUP_SYSTEM_PEER_SIZE=$system_size" \
    "FEMUP_EIGEN_THREADS=$eigen_threads FEMUP_SYSTEM_THREADS=$system_threads" \
    "FEMUP_NOISE_PEER_DRAWS=$noise_draws)"
} > "$out/machine.txt"
cat "$out/machine.txt"

echo "== solvers_bench"
# One OpenMP thread for CHOLMOD (the large frame's modes): its threads degrade
# badly when the machine is shared, and the solvers compared use one thread.
OMP_NUM_THREADS=1 "$build/bench/solvers_bench" --benchmark_min_time="$min_time" \
  --benchmark_repetitions=3 \
  --benchmark_display_aggregates_only=true --benchmark_out="$out/solvers.json" \
  --benchmark_out_format=json | tee "$out/solvers.txt"
/usr/bin/python3 bench/benchmark_table.py "$out/solvers.json" > "$out/solvers.md" ||
  echo "solvers.md not written (needs /usr/bin/python3); solvers.json has the results"

echo "== peer comparison (scipy.optimize.lsq_linear)"
"$build/bench/femup_peer_compare" --sizes "$sizes" --markdown "$out/peer.md"

echo "== peer comparison (scipy.sparse.linalg.eigsh, shift-invert)"
# One OpenMP thread for CHOLMOD, as scipy gets one BLAS thread.
OMP_NUM_THREADS=1 "$build/bench/femup_eigen_peer_compare" --dofs "$eigen_dofs" --peers "$eigen_peers" \
  --threads "$eigen_threads" \
  --markdown "$out/eigen_peer.md"
echo "== peer comparison (the linear correction-factor system, scipy)"
OMP_NUM_THREADS=1 "$build/bench/femup_system_peer_compare" --size "$system_size" \
  --threads "$system_threads" --markdown "$out/system_peer.md"
echo "== peer comparison (the paper's noise study in numpy)"
"$build/bench/femup_noise_peer_compare" --draws "$noise_draws" --repeat 5 --rounds 5 \
  --markdown "$out/noise_peer.md"
echo "elapsed (build and runs): ${SECONDS} s" >> "$out/machine.txt"
echo "results in $out/"
