#!/usr/bin/env bash
# The BLAS measured against ATLAS on the same runs (docs/benchmarks.md, "The
# BLAS"): one build linked to liblapack.so.3 / libblas.so.3 only
# (FEMUP_BLAS_VENDOR=Generic, in build-generic/), run with LD_LIBRARY_PATH set
# to Debian's ATLAS or OpenBLAS folder, so that femup, CHOLMOD, LAPACK and the
# scipy peer all run on the one BLAS. Needs libatlas3-base (Ceres brings it)
# and libopenblas0-pthread (scripts/setup.sh installs it).
# Usage: bash scripts/blas_compare.sh [ROUNDS]   (default 2)
set -euo pipefail
rounds="${1:-2}"
root="$(cd "$(dirname "$0")/.." && pwd)"
cd "$root"
cmake -S . -B build-generic -G Ninja -DCMAKE_BUILD_TYPE=Release -DFEMUP_BLAS_VENDOR=Generic \
  -DFEMUP_BUILD_BENCHMARKS=ON > /dev/null
cmake --build build-generic --target femup_eigen_peer_compare femup_system_peer_compare > /dev/null
lib=/usr/lib/x86_64-linux-gnu
run() {  # run NAME FOLDER [CORETYPE]
  local name="$1" folder="$2" core="${3:-}"
  local envs=(LD_LIBRARY_PATH="$lib/$folder" OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1)
  [ -n "$core" ] && envs+=(OPENBLAS_CORETYPE="$core")
  echo "== $name: lowest 10 modes, 10^5 DOF (femup s, peak MB, MB/1e5, scipy s, ratio, ...)"
  env "${envs[@]}" build-generic/bench/femup_eigen_peer_compare --dofs 1e5 \
    --python /usr/bin/python3 --peers symmetric --threads 1 2>&1 | grep "^| 100152 | 803308"
  echo "== $name: correction system, 10^5 DOF"
  env "${envs[@]}" build-generic/bench/femup_system_peer_compare --size 1e5 \
    --python /nonexistent --threads 1 2>&1 | grep -E "dense product|^\| femup|half solves" |
    sed 's/Read bound.*femup: sparse/ sparse/; s/femup ran with.*//'
}
uptime
for ((r = 1; r <= rounds; ++r)); do
  echo "=== round $r"
  run ATLAS atlas
  run "OpenBLAS (its own kernels)" openblas-pthread
  run "OpenBLAS (SkylakeX kernels)" openblas-pthread SkylakeX
done
uptime
