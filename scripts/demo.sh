#!/usr/bin/env bash
# The README's first command: set up, build, and run the main job on a bundled
# example (the reference paper's numerical study), writing out/.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/stages.sh
stage "set-up"
bash scripts/setup.sh
stage "build (femup)"
bash scripts/build.sh build -- femup_cli
stage "the paper's study"
./build/femup run examples/paper_chain_masses_1-3_wet.yaml -o out/paper_chain_masses_1-3_wet
./build/femup noise examples/paper_chain_noise.yaml -o out/paper_chain_noise
stage_end
echo "results: out/paper_chain_masses_1-3_wet/ and out/paper_chain_noise/"
