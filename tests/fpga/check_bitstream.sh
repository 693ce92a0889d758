#!/usr/bin/env bash
# Runs `eskin bitstream ARGS --out OUT` and checks what it says against its
# own report (OUT/bitstream_report.json), for the bitstream.* ctests.
#
#   check_bitstream.sh ESKIN OUT fits -- ARGS...
#     exit 0; the report says it fits and meets timing, every resource's use
#     is within what the device has, every clock's Fmax reaches its
#     requirement, and the bitstream is there, in OUT, as are the $readmemh
#     files the core wrapper names. A Hall build on the iCE40
#     must also have its I2C pins as tristates in the bitstream: icebox_vlog
#     of the placed design shows each as an inout driven `? ... : 1'bz`, one
#     per bus line the report lists.
#   check_bitstream.sh ESKIN OUT fails REGEX -- ARGS...
#     exit 1, the message matches REGEX (the limit and the numbers), and the
#     report says it does not fit (or misses timing) and has no bitstream.
set -euo pipefail
eskin=$1 out=$2 want=$3
shift 3
regex=""
if [ "$want" = fails ]; then regex=$1; shift; fi
[ "$1" = "--" ] && shift
rm -rf "$out"
set +e
msg=$("$eskin" bitstream "$@" --out "$out" 2>&1)
status=$?
set -e
echo "$msg"
report=$out/bitstream_report.json
fail() { echo "check_bitstream.sh: $*" >&2; exit 1; }
[ -f "$report" ] || fail "no $report"
if [ "$want" = fits ]; then
  [ "$status" -eq 0 ] || fail "eskin bitstream exited $status"
  jq -e '.fits and .meets_timing' "$report" >/dev/null || fail "report: fits/meets_timing not true"
  over=$(jq -r '.resources | to_entries[] | select(.value.used > .value.available) | .key' "$report")
  [ -z "$over" ] || fail "report: over capacity: $over"
  jq -e '(.clocks | length) > 0 and all(.clocks[]; .fmax_mhz >= .required_mhz)' "$report" \
    >/dev/null || fail "report: a clock below its requirement"
  bit=$(jq -r .bitstream "$report")
  [ -s "$bit" ] || fail "no bitstream at '$bit'"
  # Everything it names is in OUT (an ECP5 build under /tmp too, whose
  # tools have a private /tmp of their own: synth_ecp5.sh mounts OUT for
  # them).
  outdir=$(realpath "$out")
  case "$(realpath "$bit")" in "$outdir"/*) ;; *) fail "bitstream '$bit' is not in $outdir" ;; esac
  for v in "$out"/*.v; do
    [ -f "$v" ] || continue
    # One name a line: OUT's path may hold spaces.
    while IFS= read -r hex; do
      [ -s "$hex" ] || fail "$v names $hex, which is not there"
      case "$hex" in "$outdir"/*) ;; *) fail "$v names $hex, outside $outdir" ;; esac
    done < <(grep -o '"/[^"]*\.hex"' "$v" | tr -d '"')
  done
  lines=$(jq '[.hall.pins // [] | .[] | select(.open_drain)] | length' "$report")
  asc=${bit%.bin}.asc
  if [ "$lines" -gt 0 ] && [ -f "$asc" ]; then
    tri=$(icebox_vlog "$asc" | grep -cE "^assign io_[0-9_]+ = .* \? .* : 1'bz;" || true)
    [ "$tri" -eq "$lines" ] || fail "$tri tristate pins in the bitstream, the report lists $lines I2C lines"
    echo "check_bitstream.sh: $tri I2C lines are tristate pins (icebox_vlog)"
  fi
  jq -r '"check_bitstream.sh: fits and meets timing: " + ([.resources | to_entries[] | select(.value.used > 0) | "\(.key) \(.value.used)/\(.value.available)"] | join(", ")) + "; " + ([.clocks[] | "\(.net) \(.fmax_mhz | floor) MHz (need \(.required_mhz))"] | join(", ")) + "; \(.tool_seconds | floor) s of tools"' "$report"
else
  [ "$status" -eq 1 ] || fail "eskin bitstream exited $status, expected 1"
  echo "$msg" | grep -qE "$regex" || fail "message does not match '$regex'"
  jq -e '(.fits and .meets_timing) | not' "$report" >/dev/null || fail "report says it passed"
  [ "$(jq -r .bitstream "$report")" = "" ] || fail "report names a bitstream"
  echo "check_bitstream.sh: refused as expected"
fi
