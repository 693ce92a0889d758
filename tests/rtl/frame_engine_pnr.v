// frame_engine_pnr: rtl/frame_engine.v with its wide buses folded onto a
// few pins, for place and route on the UP5K (tests/rtl/frame_engine_test.cmake,
// docs/frame_engine.md "Resources"). io_rdata comes from a 32-bit serial-in
// shift register, every output is XOR-folded into one registered pin, and
// KROM holds a fixed non-trivial pattern, so nothing of the core is optimised
// away; the wrapper itself costs 32 + 1 flip-flops and a dozen LUTs.
`default_nettype none

module frame_engine_pnr #(
    parameter integer IW = 10,
    parameter integer DW = 14,
    parameter integer KW = 8,
    parameter UCODE_HEX = ""
) (
    input  wire       clk,
    input  wire       rst,
    input  wire       din,
    input  wire [3:0] ev,
    output reg        dout
);
  function automatic [32*(1<<KW)-1:0] pattern(input integer seed);
    integer k;
    begin
      pattern = 0;
      for (k = 0; k < (1 << KW); k = k + 1) pattern[32*k +: 32] = 32'h9e3779b9 * (k + seed);
    end
  endfunction

  wire [15:0] io_raddr, io_waddr;
  wire        io_re, io_we;
  wire [31:0] io_wdata;
  reg  [31:0] rdata;
  always @(posedge clk) begin
    rdata <= {rdata[30:0], din};
    dout <= ^{io_re, io_we, io_wdata, io_raddr, io_waddr};
  end
  frame_engine #(.IW(IW), .DW(DW), .KW(KW), .UCODE_HEX(UCODE_HEX), .KROM_INIT(pattern(1))) u (
      .clk(clk), .rst(rst), .io_raddr(io_raddr), .io_re(io_re), .io_waddr(io_waddr), .io_rdata(rdata), .io_we(io_we),
      .io_wdata(io_wdata), .events({4{ev}}));
endmodule
`default_nettype wire
