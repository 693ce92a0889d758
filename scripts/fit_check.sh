#!/usr/bin/env bash
# The DTMF top's fit check on the iCE40 UP5K (issue 7's bar): the build of
# a scene (default: the default scene) must leave at least 10 % of the logic
# cells spare and meet its clock with at least 10 % slack at every one of
# several placement seeds, so that an unrelated edit cannot tip it over.
#
#   scripts/fit_check.sh ESKIN [--scene S.yaml] [--seeds "1 2 3"] [--out DIR]
#
# ESKIN is the built `eskin` (it writes the scene's microcode and constants
# and prints the top's parameters: `eskin ucode build`). Synthesis is
# scripts/synth_ice40.sh (Yosys, -abc9); each seed is one nextpnr-ice40 run
# on the same netlist, IO placed freely (the board's pins and PLL are the
# bitstream flow's: docs/bitstream.md). One line per seed, then a verdict;
# exits 1 naming the seed and figure that missed.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
eskin=${1:?usage: fit_check.sh ESKIN [--scene S.yaml] [--seeds "1 2 3"] [--out DIR]}
shift
scene=$root/scenes/neuroskin2.yaml seeds="1 2 3" out=$root/build/synth/dtmf_top_fit
while [ $# -gt 0 ]; do
  case "$1" in
    --scene) scene=$2; shift 2 ;;
    --seeds) seeds=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    *) echo "fit_check.sh: unknown argument '$1'" >&2; exit 2 ;;
  esac
done
mkdir -p "$out"
"$eskin" ucode build "$scene" --out "$out" >"$out/params.txt"
params=() clk_hz=""
while IFS= read -r kv; do
  params+=(--param "$kv")
  case "$kv" in CLK_HZ=*) clk_hz=${kv#CLK_HZ=} ;; esac
done <"$out/params.txt"
[ -n "$clk_hz" ] || { echo "fit_check.sh: no CLK_HZ in $out/params.txt" >&2; exit 1; }
need=$(awk -v c="$clk_hz" 'BEGIN {printf "%.3f", 1.1 * c / 1e6}')
"$root/scripts/synth_ice40.sh" dtmf_top "${params[@]}" --out "$out"
bad=0
for s in $seeds; do
  nextpnr-ice40 --up5k --package sg48 --json "$out/dtmf_top.json" --pcf-allow-unconstrained \
    --freq "$need" --seed "$s" --report "$out/report_seed$s.json" -q >"$out/nextpnr_seed$s.log" 2>&1 ||
    true  # a timing miss makes nextpnr fail; the figures below say by how much
  if [ ! -s "$out/report_seed$s.json" ]; then
    echo "seed $s: nextpnr failed (does not fit?):" >&2; tail -5 "$out/nextpnr_seed$s.log" >&2; bad=1
    continue
  fi
  used=$(jq '.utilization.ICESTORM_LC.used' "$out/report_seed$s.json")
  avail=$(jq '.utilization.ICESTORM_LC.available' "$out/report_seed$s.json")
  fmax=$(jq '[.fmax[].achieved] | min' "$out/report_seed$s.json")
  spare=$(awk -v u="$used" -v a="$avail" 'BEGIN {printf "%.1f", 100 * (a - u) / a}')
  slack=$(awk -v f="$fmax" -v c="$clk_hz" 'BEGIN {printf "%.1f", 100 * (f * 1e6 / c - 1)}')
  echo "seed $s: LC $used/$avail ($spare % spare), Fmax $(printf '%.2f' "$fmax") MHz ($slack % slack at $((clk_hz / 1000000)) MHz)"
  if awk -v x="$spare" 'BEGIN {exit !(x < 10)}'; then
    echo "seed $s: only $spare % of the logic cells spare, need 10 %" >&2; bad=1
  fi
  if awk -v x="$slack" 'BEGIN {exit !(x < 10)}'; then
    echo "seed $s: Fmax $fmax MHz is only $slack % above the clock, need 10 % ($need MHz)" >&2; bad=1
  fi
done
[ "$bad" -eq 0 ] && echo "fit check: pass (seeds $seeds)"
exit "$bad"
