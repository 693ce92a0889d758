#!/usr/bin/env bash
# Synthesises one rtl/ module for the iCE40 UP5K with Yosys (multipliers on
# SB_MAC16: -dsp; timing-driven LUT mapping: -abc9, which knows the block
# RAMs' late outputs and gives the DTMF top 21-22.5 MHz instead of
# 19.6-20.7 over seeds 1-3) and, with --pnr, places and routes it with nextpnr-ice40
# and checks that it fits and meets the clock it needs; the bitstream is
# then packed with icepack into OUT/TOP.bin.
#
#   scripts/synth_ice40.sh TOP [--param NAME=VALUE]... [--pnr] [--freq MHZ]
#                              [--pcf FILE] [--out DIR] [--seed N]
#                              [--read FILE]... [--define NAME=VALUE]...
#
# --read adds a Verilog file (e.g. a generated wrapper module) read with the
# top; --define sets a Verilog macro for every file read (`eskin bitstream`
# uses both to put a scene's core into a board wrapper).
#
# Prints one line of figures: LUTs (ICESTORM_LC), DSPs, BRAMs, SPRAMs and,
# after place and route, the achieved Fmax against the requested clock.
# Exits non-zero if Yosys fails, the design does not fit, or Fmax < freq.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
top=${1:?usage: synth_ice40.sh TOP [--param N=V]... [--pnr] [--freq MHZ] [--pcf F] [--out DIR] [--seed N] [--read F]... [--define N=V]...}
shift
src="$root/rtl/$top.v"
case "$top" in *.v) src=$(realpath "$top"); top=$(basename "$top" .v) ;; esac
params=() reads=() defines="" pnr=0 freq=12 pcf="" out="" seed=1
while [ $# -gt 0 ]; do
  case "$1" in
    --param) params+=("$2"); shift 2 ;;
    --pnr) pnr=1; shift ;;
    --freq) freq=$2; shift 2 ;;
    --pcf) pcf=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --seed) seed=$2; shift 2 ;;
    --read) reads+=("$(realpath "$2")"); shift 2 ;;
    --define) defines+=" -D$2"; shift 2 ;;
    *) echo "synth_ice40.sh: unknown argument '$1'" >&2; exit 2 ;;
  esac
done
out=${out:-$root/build/synth/$top}
mkdir -p "$out"
# Yosys reads its -p script as words split at blanks and ';' (and a word
# starting with '!' runs a shell): a path in it must be one plain word or a
# "quoted" one, and only some commands take the quoted form (read_verilog,
# write_json and chparam's strings do; tee -o and hierarchy -libdir do not).
# So the files it reads are given quoted (a path holding '"' or a newline
# is refused), and it writes into a folder whose path is a plain word: OUT,
# or when OUT's path has other characters (a space, say), a fresh folder
# whose files are moved into OUT after.
plain_word() { case "$1" in ''|*[!A-Za-z0-9_./+,@%=-]*) return 1 ;; esac; }
quoted() {  # PATH: sets $q to PATH as one quoted Yosys word
  case "$1" in *'"'*|*$'\n'*)
    echo "synth_ice40.sh: '$1': a path with a double quote or a newline cannot be given to Yosys; rename it" >&2
    exit 2 ;; esac
  q="\"$1\""
}
# One chparam for all of them: each chparam re-elaborates the module, and
# a half-changed set (e.g. a PLL's new input divider with the old feedback
# divider) can trip the module's own parameter checks.
chparam=""
for p in "${params[@]+"${params[@]}"}"; do
  chparam+=" -set ${p%%=*} ${p#*=}"
done
if [ -n "$chparam" ]; then chparam="chparam$chparam $top; "; fi
# The top comes from rtl/TOP.v (or a path given as TOP); the modules it
# instantiates are found as rtl/NAME.v by `hierarchy -libdir`, read as
# SystemVerilog like the top (verilog_defaults: hall_top's casts, say), and
# only they: Yosys's own cell libraries, read during synthesis, are not SV
# (abc9_map.v names a wire `logic`).
# Parameters are set before elaboration, so `hierarchy` derives the
# submodules from the overridden values.
files=""
quoted "$src"; files+=" $q"
for f in "${reads[@]+"${reads[@]}"}"; do quoted "$f"; files+=" $q"; done
for p in "${params[@]+"${params[@]}"}"; do
  v=${p#*=}
  case "$v" in
    \"*\") case "${v:1:${#v}-2}" in *'"'*|*$'\n'*) bad=1 ;; *) bad=0 ;; esac ;;
    *) case "$v" in *[[:space:]\;\"]*|'') bad=1 ;; *) bad=0 ;; esac ;;
  esac
  if [ "$bad" -eq 1 ]; then echo "synth_ice40.sh: --param $p: not one Yosys word (a number, or a \"string\" without '\"')" >&2; exit 2; fi
done
plain_word "$root/rtl" || { echo "synth_ice40.sh: the source tree's path '$root' is not one plain word (letters, digits and _ . / + , @ % = -), which Yosys's hierarchy -libdir needs; move the tree" >&2; exit 2; }
ys_out=$out
if ! plain_word "$out"; then
  ys_out=$(mktemp -d /tmp/eskin-yosys.XXXXXX)
  trap 'rm -rf "$ys_out"' EXIT
fi
# Elaboration alone first, with hierarchy -check (the iCE40 cells known as
# black boxes): an illegal parameter set stops here, at its module's
# `MODULE_illegal_parameters` cell, in a fraction of a second instead of
# after the minutes a large design's synthesis takes (synth_ice40 checks the
# hierarchy only after its own passes). A separate run, so that the
# synthesis below sees exactly the design it always did.
yosys -q -l "$out/elaborate.log" -p "read_verilog -lib +/ice40/cells_sim.v; verilog_defaults -add -sv; read_verilog$defines$files; $chparam hierarchy -check -libdir $root/rtl -top $top" >/dev/null
yosys -q -l "$out/yosys.log" -p "verilog_defaults -add -sv; read_verilog$defines$files; $chparam hierarchy -libdir $root/rtl -top $top; verilog_defaults -clear; \
  synth_ice40 -dsp -spram -abc9 -top $top -json $ys_out/$top.json; tee -o $ys_out/stat.txt stat" >/dev/null
if [ "$ys_out" != "$out" ]; then mv "$ys_out/$top.json" "$ys_out/stat.txt" "$out/"; fi
cells() { { grep -E "^\s+$1\s" "$out/stat.txt" || true; } | awk '{s+=$2} END {print s+0}'; }
lc=$(cells SB_LUT4); dsp=$(cells SB_MAC16); bram=$(cells SB_RAM40_4K); spram=$(cells SB_SPRAM256KA)
ff=$({ grep -E "^\s+SB_DFF" "$out/stat.txt" || true; } | awk '{s+=$2} END {print s+0}')
line="$top: yosys LUT4 $lc, FF $ff, DSP $dsp/8, BRAM $bram/30, SPRAM $spram/4"
if [ "$pnr" -eq 1 ]; then
  pcfarg=(--pcf-allow-unconstrained)
  [ -n "$pcf" ] && pcfarg=(--pcf "$pcf")
  nextpnr-ice40 --up5k --package sg48 --json "$out/$top.json" --asc "$out/$top.asc" \
    "${pcfarg[@]}" --freq "$freq" --report "$out/report.json" --seed "$seed" \
    >"$out/nextpnr.log" 2>&1 || { tail -20 "$out/nextpnr.log" >&2; exit 1; }
  icepack "$out/$top.asc" "$out/$top.bin"
  used=$(jq '.utilization.ICESTORM_LC.used' "$out/report.json")
  avail=$(jq '.utilization.ICESTORM_LC.available' "$out/report.json")
  # Fmax is keyed by the internal clock net name, not the port name.
  fmax=$(jq '[.fmax[].achieved] | min' "$out/report.json")
  line+=", placed LC $used/$avail, Fmax $(printf '%.1f' "$fmax") MHz (need $freq)"
  if awk -v a="$fmax" -v f="$freq" 'BEGIN {exit !(a < f)}'; then
    echo "$line"; echo "synth_ice40.sh: $top misses timing: $fmax < $freq MHz" >&2; exit 1
  fi
fi
echo "$line"
