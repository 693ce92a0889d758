`default_nettype none
// crc16: one byte of CRC-16/CCITT-FALSE (polynomial 0x1021, MSB first, not
// reflected), combinational: crc_out = CRC register after shifting in
// `data` starting from `crc_in`. Start a frame with 16'hFFFF. Appending the
// final register high byte first makes the register over the whole frame
// (CRC bytes included) 0, which is how receivers check a frame.
module crc16 (
    input  wire [15:0] crc_in,
    input  wire [7:0]  data,
    output reg  [15:0] crc_out
);
  integer i;
  always @(*) begin
    crc_out = crc_in ^ {data, 8'h00};
    for (i = 0; i < 8; i = i + 1)
      crc_out = crc_out[15] ? ({crc_out[14:0], 1'b0} ^ 16'h1021) : {crc_out[14:0], 1'b0};
  end
endmodule
`default_nettype wire
