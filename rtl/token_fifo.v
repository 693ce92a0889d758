// token_fifo: a valid/ready FIFO of DEPTH W-bit tokens in block RAM (one
// synchronous read port), with a one-token output register in front.
// dtmf_top puts one between sdft_bank and carrier_magnitude when the
// magnitudes of a frame take longer than a sample period (K = 32: 32 x 26
// cycles against 343): the DFT unloads a whole frame at its own pace and
// never stalls the ADC.
// Timing: a token that enters in cycle c (handshake) is offered from cycle
// c + 3 (read issued in c + 1, output register loaded in c + 2); an
// always-ready consumer gets one token per 2 cycles at most (carrier_
// magnitude takes one per 26).
// Capacity DEPTH in RAM + 1 in the output register; in_ready = RAM not full.
module token_fifo #(
    parameter integer W = 57,
    parameter integer DEPTH = 32   // power of two, >= 2
) (
    input  wire         clk,
    input  wire         rst,
    input  wire         in_valid,
    output wire         in_ready,
    input  wire [W-1:0] in_data,
    output reg          out_valid,
    input  wire         out_ready,
    output reg  [W-1:0] out_data
);
  localparam integer AW = $clog2(DEPTH);
  reg [W-1:0] mem [0:DEPTH-1];
  reg [W-1:0] rd_q;
  reg [AW:0] wp, rp;
  reg rd_pend;
  wire [AW:0] used = wp - rp;
  assign in_ready = (used != DEPTH[AW:0]);
  wire empty = (wp == rp);
  always @(posedge clk) begin
    if (in_valid && in_ready) mem[wp[AW-1:0]] <= in_data;
    rd_q <= mem[rp[AW-1:0]];
  end
  always @(posedge clk) begin
    if (rst) begin
      wp <= {(AW + 1){1'b0}};
      rp <= {(AW + 1){1'b0}};
      rd_pend <= 1'b0;
      out_valid <= 1'b0;
      out_data <= {W{1'b0}};
    end else begin
      if (in_valid && in_ready) wp <= wp + 1'b1;
      if (out_valid && out_ready) out_valid <= 1'b0;
      if (rd_pend) begin
        out_data <= rd_q;
        out_valid <= 1'b1;
        rd_pend <= 1'b0;
        rp <= rp + 1'b1;
      end else if (!empty && (!out_valid || out_ready)) begin
        rd_pend <= 1'b1;  // rd_q holds mem[rp] after this edge
      end
    end
  end
endmodule
