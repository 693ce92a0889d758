#!/usr/bin/env bash
# Every Verilog file given starts its code with `default_nettype none (so an
# undeclared net is an error, not an implicit wire) and ends with
# `default_nettype wire (so files compiled after it are not affected).
set -euo pipefail
bad=0
for f in "$@"; do
  first=$(grep -m1 -n '^`default_nettype' "$f" | cut -d: -f2- || true)
  mod=$(grep -m1 -n '^module' "$f" | cut -d: -f1 || true)
  line=$(grep -m1 -n '^`default_nettype none' "$f" | cut -d: -f1 || true)
  last=$(grep '^`default_nettype' "$f" | tail -1 || true)
  if [ "$first" != '`default_nettype none' ] || [ -z "$line" ] || [ -z "$mod" ] || [ "$line" -gt "$mod" ]; then
    echo "$f: expected \`default_nettype none before the module" >&2; bad=1
  fi
  if [ "$last" != '`default_nettype wire' ]; then
    echo "$f: expected \`default_nettype wire after the module" >&2; bad=1
  fi
done
exit $bad
