#!/usr/bin/env bash
# Installs, from Debian packages, everything eskin's build and tests need.
# Idempotent: only missing packages are installed (apt-get update first).
set -euo pipefail
pkgs=(
  build-essential cmake ninja-build pkg-config git
  verilator libsystemc-dev
  libeigen3-dev libgtest-dev libgmock-dev googletest
  libyaml-cpp-dev libcli11-dev libfmt-dev
  libfftw3-dev libsndfile1-dev
  yosys nextpnr-ice40 fpga-icestorm jq
  python3-venv
  # virtual board and `eskin simulate` (docs/vboard.md): JSON status lines,
  # Chart.js inlined into the report, GTKWave (and fst2vcd) for --trace
  nlohmann-json3-dev libjs-chart.js gtkwave
  # host/stream: HDF5 recording (eskin stream --hdf5)
  libhdf5-dev
  # host/stream: the live view's HTTP server (eskin stream --live; its
  # Chart.js is libjs-chart.js above, tests/stream parse JSON with nlohmann)
  libcpp-httplib-dev
  # tests/stream: the live view screenshot in headless Chromium
  chromium
  # tests/stream: PNG decoding of that screenshot
  libpng-dev
  # tests/stream: libFuzzer (clang) for the link decoder fuzz test
  clang libclang-rt-14-dev
  # eskin bench tradeoff --slurm and its test's one-node cluster (docs/bench.md)
  slurmctld slurmd slurm-client munge
)
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "bootstrap: all ${#pkgs[@]} packages present"
else
  echo "bootstrap: installing ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update
  $SUDO apt-get install -y --no-install-recommends "${missing[@]}"
fi
# ECP5 tools (no Debian package): PyPI, into build/venv.
"$(dirname "$0")/bootstrap_yowasp.sh"
