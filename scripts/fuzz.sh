#!/usr/bin/env bash
# fuzz.sh [SECONDS_PER_PARSER] [--long]: builds the libFuzzer harnesses of
# fuzz/ (clang, ASan + UBSan, in build-fuzz/) and runs each parser's fuzzer, one
# at a time, from its seed corpus (fuzz/corpus/<parser>/ and the crash inputs of
# fuzz/regressions/<parser>/, copied to a temporary work folder: nothing is
# written into the repository). Prints per parser the executions, exec/s, wall
# time and crashes, and exits non-zero on any crash (a crash is an uncaught
# exception other than femup::InputError, an abort, a sanitizer report, a hang
# of more than 10 s (FEMUP_FUZZ_TIMEOUT) or an allocation of 1 GiB or more); the work folder of a
# crash is kept and its reproducing command printed.
#
#   scripts/fuzz.sh            12 s per parser (scripts/test.sh runs this)
#   scripts/fuzz.sh 300        5 minutes per parser
#   scripts/fuzz.sh --long     the campaign of docs/fuzzing.md: 10^7 executions
#                              per parser, at most 900 s each (or SECONDS)
#
# FEMUP_FUZZ_JOBS sets the build's parallel jobs (default: all cores).
# FEMUP_FUZZ_PARSERS="uff csv_series" runs only those.
# FEMUP_FUZZ_KEEP=1 keeps every work folder (log, corpus), not only a crash's.
# FEMUP_FUZZ_TIMEOUT=S: an input running longer than S seconds is a hang
# (default 10). Raise it for a campaign on a machine busy with other work: a
# starved process (nice, other jobs) then shows as a hang that is not one.
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=""
long=0
for arg in "$@"; do
  case "$arg" in
    --long) long=1 ;;
    '' | *[!0-9]*)
      echo "usage: scripts/fuzz.sh [SECONDS_PER_PARSER] [--long]" >&2
      exit 2
      ;;
    *) seconds="$arg" ;;
  esac
done
if [ -z "$seconds" ]; then
  if [ "$long" = 1 ]; then seconds=900; else seconds=12; fi
fi
runs_args=()
[ "$long" = 1 ] && runs_args=(-runs=10000000)

parsers=(${FEMUP_FUZZ_PARSERS:-uff csv_series matrix_market study modes_json})
jobs="${FEMUP_FUZZ_JOBS:-$(nproc)}"
build=build-fuzz

if ! command -v clang++ > /dev/null; then
  echo "fuzz.sh: clang++ not found (scripts/setup.sh installs clang and libclang-rt-14-dev)" >&2
  exit 1
fi
# With line tables, without NDEBUG: Eigen's own checks (an index out of range,
# sizes that do not match) abort here too, and every report has a line. -O1 for
# the short runs (OSS-Fuzz's default level: the build is most of the short
# stage's time, and the whole library is compiled for the study parser), -O2
# for a campaign, where executions per second count.
opt=-O1
[ "$long" = 1 ] && opt=-O2
CC=clang CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="$opt -g1" -DFEMUP_FUZZ=ON -DFEMUP_BUILD_TESTS=OFF \
  -DFEMUP_BUILD_BENCHMARKS=OFF -DFEMUP_BUILD_VALIDATION=OFF > /dev/null
# ccache does not hash the coverage allowlist's content (nor, in its preprocessor
# mode, the -D that carries its checksum): name it, or an edited list is ignored.
export CCACHE_EXTRAFILES="$PWD/fuzz/coverage_allowlist.txt"
targets=()
for p in "${parsers[@]}"; do targets+=("${p}_fuzzer"); done
if ! cmake --build "$build" -j "$jobs" --target "${targets[@]}" > "$build/fuzz-build.log" 2>&1; then
  tail -30 "$build/fuzz-build.log" >&2
  echo "fuzz.sh: the build in $build failed (log: $build/fuzz-build.log)" >&2
  exit 1
fi

limits=(-rss_limit_mb=2048 -malloc_limit_mb=1024 -timeout="${FEMUP_FUZZ_TIMEOUT:-10}")
# A campaign records no allocation stacks (ASan's stack depot took a quarter of
# the study fuzzer's time in session 21); rerun a crash's input without this to
# see where its memory was allocated.
if [ "$long" = 1 ]; then
  export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:malloc_context_size=0}"
else
  export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1}"
fi
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
failed=0
printf '%-14s %12s %10s %8s %8s %8s\n' parser executions exec/s wall_s cov crashes
for p in "${parsers[@]}"; do
  work=$(mktemp -d "${TMPDIR:-/tmp}/femup-fuzz-$p.XXXXXX")
  mkdir -p "$work/corpus" "$work/artifacts"
  cp fuzz/corpus/"$p"/* "$work/corpus/"
  if compgen -G "fuzz/regressions/$p/*" > /dev/null; then
    cp fuzz/regressions/"$p"/* "$work/corpus/"
  fi
  start=$(date +%s)
  status=0
  "$build/fuzz/${p}_fuzzer" "${limits[@]}" -max_total_time="$seconds" "${runs_args[@]}" \
    -print_final_stats=1 -artifact_prefix="$work/artifacts/" "$work/corpus" \
    > "$work/log" 2>&1 || status=$?
  wall=$(($(date +%s) - start))
  executions=$(sed -n 's/^stat::number_of_executed_units: *//p' "$work/log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$work/log" | tail -1)
  # Edge coverage of femup's instrumented code at the end ("cov: N").
  cov=$(grep -o 'cov: [0-9]*' "$work/log" | tail -1 | cut -d' ' -f2 || true)
  crashes=$(find "$work/artifacts" -type f | wc -l)
  if [ "$status" != 0 ] && [ "$crashes" = 0 ]; then crashes=1; fi
  printf '%-14s %12s %10s %8s %8s %8s\n' "$p" "${executions:-?}" "${rate:-?}" "$wall" \
    "${cov:-?}" "$crashes"
  if [ "$crashes" != 0 ]; then
    failed=1
    echo "  $p: the fuzzer stopped with status $status; log: $work/log" >&2
    grep -m 3 -E "ERROR|SUMMARY|terminate|uncaught|runtime error" "$work/log" | sed 's/^/    /' >&2 || true
    for a in "$work"/artifacts/*; do
      [ -e "$a" ] || continue
      echo "  reproduce: $build/fuzz/${p}_fuzzer ${limits[*]} $a" >&2
    done
  elif [ -n "${FEMUP_FUZZ_KEEP:-}" ]; then
    echo "  $p: work folder kept: $work"
  else
    rm -rf "$work"
  fi
done
exit "$failed"
