#!/usr/bin/env bash
# An ECP5 build asked for under /tmp, a plain user's first try, the
# smallest real run of the tools: scripts/synth_ecp5.sh --pnr on a small
# module whose source, $readmemh file and --out are all in a folder under
# /tmp, with a second source right in /tmp. The WebAssembly tools have a
# private /tmp of their own (a folder under $TMPDIR), so the script must let
# them see these (synth_ecp5.sh mounts /tmp/NAME folders for them, copies a
# file right in /tmp into OUT/inputs): Yosys reads both sources and the
# ROM's contents (a $readmemh file it cannot open is an error), nextpnr
# places the design and ecppack writes OUT/rom_reg.bit; every file is in OUT.
#   check_ecp5_tmp_out.sh SOURCE_DIR
set -euo pipefail
root=${1:?usage: check_ecp5_tmp_out.sh SOURCE_DIR}
dir=$(mktemp -d /tmp/eskin_ecp5_tmp_out.XXXXXX)
extra=$(mktemp /tmp/eskin_ecp5_tmp_out_inv.XXXXXX.v)
trap 'rm -rf "$dir" "$extra"' EXIT
fail() { echo "check_ecp5_tmp_out.sh: $*" >&2; exit 1; }
for i in $(seq 0 15); do printf '%02x\n' $(( (i * 37 + 5) & 255 )); done >"$dir/rom.hex"
mod=inv_$(basename "$extra" .v | tr -c 'a-zA-Z0-9_\n' _)
cat >"$extra" <<V
module $mod(input wire [7:0] a, output wire [7:0] y);
  assign y = ~a;
endmodule
V
cat >"$dir/rom_reg.v" <<V
module rom_reg(input wire clk, output reg [7:0] q);
  reg [7:0] rom [0:15];
  initial \$readmemh("$dir/rom.hex", rom);
  reg [3:0] addr = 0;
  wire [7:0] n;
  $mod inv(.a(rom[addr]), .y(n));
  always @(posedge clk) begin
    addr <= addr + 1'b1;
    q <= n ^ {q[6:0], q[7]};
  end
endmodule
V
out=$dir/out
"$root/scripts/synth_ecp5.sh" "$dir/rom_reg.v" --read "$extra" --pnr --freq 25 --device 25k \
  --out "$out" || fail "synth_ecp5.sh failed for --out $out"
[ -s "$out/rom_reg.bit" ] || fail "no bitstream at $out/rom_reg.bit"
for f in yosys.log stat.txt rom_reg.json nextpnr.log report.json; do
  [ -s "$out/$f" ] || fail "no $f in $out"
done
[ -s "$out/inputs/$(basename "$extra")" ] || fail "$extra was not copied into $out/inputs"
echo "check_ecp5_tmp_out.sh: ECP5 build into $out (under /tmp): bitstream and logs there"
