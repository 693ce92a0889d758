// The formal proofs' reference CRC-16/CCITT-FALSE (polynomial 0x1021, MSB
// first, start 16'hFFFF), one bit at a time: the LFSR form, independent of
// rtl/crc16.v's byte-wide loop that the proven modules use. Included
// inside the `ifdef FORMAL` blocks of rtl/cmd_decoder.v and
// rtl/link_framer.v.
function automatic [15:0] f_crc16(input [15:0] c, input [7:0] d);
  integer b;
  reg [15:0] r;
  begin
    r = c;
    for (b = 7; b >= 0; b = b - 1) r = {r[14:0], 1'b0} ^ ((r[15] ^ d[b]) ? 16'h1021 : 16'h0000);
    f_crc16 = r;
  end
endfunction
