#!/usr/bin/env bash
# The README's first command: set up, build, and run the main job on a bundled
# example (the reference paper's numerical study), writing out/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DFEMUP_BUILD_TESTS=OFF \
  -DFEMUP_BUILD_BENCHMARKS=OFF > /dev/null
cmake --build build --target femup_cli
./build/femup run examples/paper_chain_masses_1-3_wet.yaml -o out/paper_chain_masses_1-3_wet
./build/femup noise examples/paper_chain_noise.yaml -o out/paper_chain_noise
