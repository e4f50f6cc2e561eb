#!/usr/bin/env bash
# Installs what femup needs from Debian 12's packages, when it is missing:
# the toolchain and libraries (OpenBLAS's pthread flavour: the BLAS and LAPACK
# femup links, safe to call from several threads; CMakeLists.txt); pybind11
# and pytest for the Python module;
# Chromium, its driver and Selenium to render the HTML reports in the tests.
set -euo pipefail
PACKAGES=(build-essential cmake ninja-build pkg-config python3 clang-format
          libeigen3-dev libsuitesparse-dev libspectra-dev libyaml-cpp-dev
          nlohmann-json3-dev libcli11-dev libgtest-dev libbenchmark-dev gnuplot-nox
          libceres-dev coinor-libipopt-dev libboost-dev librandom123-dev liblapack-dev
          libopenblas-pthread-dev ccache python3-numpy python3-scipy clang libclang-rt-14-dev libssl-dev
          pybind11-dev python3-pybind11 python3-dev python3-pytest python3-setuptools
          python3-venv python3-pip chromium chromium-driver python3-selenium)
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg -s "$p" > /dev/null 2>&1 || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  SUDO=""; [ "$(id -u)" = 0 ] || SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends \
    "${missing[@]}" > /dev/null
fi
