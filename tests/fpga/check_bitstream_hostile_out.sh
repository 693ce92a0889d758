#!/usr/bin/env bash
# The iCEBreaker's default bitstream into an --out a shell would read as
# code and Yosys's script as several words: a space, a single quote, $(...),
# backticks and ';' in one folder name. check_bitstream.sh checks the build
# (fits, meets timing, the bitstream and its $readmemh files in OUT); then
# no canary the name holds may have run (a file it would create, looked
# for in the folder above OUT, the current directory and /tmp).
#   check_bitstream_hostile_out.sh ESKIN PARENT_DIR
set -euo pipefail
eskin=${1:?usage: check_bitstream_hostile_out.sh ESKIN PARENT_DIR} parent=${2:?}
here=$(cd "$(dirname "$0")" && pwd)
c=eskin_canary_$$
out="$parent/test icebreaker it's \$(touch ${c}_1) \`touch ${c}_2\`; touch ${c}_3; '; touch ${c}_4; echo '"
mkdir -p "$parent"
"$here/check_bitstream.sh" "$eskin" "$out" fits -- --board icebreaker
found=$(find "$parent" . /tmp -maxdepth 2 -name "${c}_*" 2>/dev/null || true)
[ -z "$found" ] || { echo "check_bitstream_hostile_out.sh: an injected command ran: $found" >&2; exit 1; }
echo "check_bitstream_hostile_out.sh: built into '$out', nothing injected ran"
