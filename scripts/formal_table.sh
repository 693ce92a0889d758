#!/usr/bin/env bash
# Runs every task of every tests/formal/*.sby one after another (one core,
# as a reader would) and writes docs/formal.csv: each task's kind, depth,
# wall time and verdict. tests/formal/formal_table_test.cpp checks the file
# against the .sby files; docs/formal.md cites its figures.
#
#   scripts/formal_table.sh [BUILD_DIR]     (default: build)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$(realpath -m "${1:-$root/build}")
out=$root/docs/formal.csv
work=$build/formal-table
rows=()
for sby in "$root"/tests/formal/*.sby; do
  module=$(basename "$sby" .sby)
  tasks=$(awk '/^\[tasks\]/ { on = 1; next } /^\[/ { on = 0 } on && NF == 1 { print $1 }' "$sby")
  for task in $tasks; do
    "$root/tests/formal/run_sby.sh" "$sby" "$task" "$work/${module}_$task" "$root/rtl" "$build/venv" >/dev/null
    rows+=("$(cat "$work/${module}_$task/row.csv")")
    echo "${rows[-1]}"
  done
done
{
  echo "# The formal proofs' tasks (tests/formal/*.sby), run one after another by"
  echo "# scripts/formal_table.sh; checked by tests/formal/formal_table_test.cpp."
  echo "module,task,mode,depth,seconds,verdict"
  printf '%s\n' "${rows[@]}"
} >"$out"
echo "formal_table: wrote $out (${#rows[@]} tasks)"
