#!/usr/bin/env bash
# build.sh DIR [CMAKE OPTIONS...] [-- TARGETS...]: configures and builds femup
# in DIR with the project's one set of Release flags (unless the options say
# otherwise), through ccache where it is installed. Both README commands build
# with it, into the same build/ folder with the same compile flags, so the
# second finds the first's objects. Any compiler warning fails the build (the
# log is scanned rather than compiling with -Werror, which would change the
# flags and defeat the sharing); ccache replays a cached object's warnings.
set -euo pipefail
cd "$(dirname "$0")/.."
dir="$1"; shift
options=(); targets=()
while [ $# -gt 0 ]; do
  if [ "$1" = "--" ]; then shift; targets=("$@"); break; fi
  options+=("$1"); shift
done
# Paths relative to the project folder in ccache's keys, so that a copy of the
# project elsewhere (CI's clean checkouts) finds the same objects.
export CCACHE_BASEDIR="$PWD" CCACHE_NOHASHDIR=1
cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Release "${options[@]}" > /dev/null
log="$dir/build.log"
target_args=()
[ ${#targets[@]} -gt 0 ] && target_args=(--target "${targets[@]}")
if ! cmake --build "$dir" -j "$(nproc)" "${target_args[@]}" 2>&1 | tee "$log"; then
  echo "build.sh: the build in $dir failed (log: $log)" >&2
  exit 1
fi
if grep -q "warning:" "$log"; then
  echo "build.sh: the build in $dir printed compiler warnings (log: $log):" >&2
  grep "warning:" "$log" | sort -u | head -20 >&2
  exit 1
fi
