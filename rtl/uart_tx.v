`default_nettype none
// uart_tx: UART transmitter, 8N1 (start bit 0, 8 data bits LSB first, stop
// bit 1), idle high.
//
// Bit period: CPB = round(CLK_HZ / BAUD) clocks, exactly, for every bit; the
// actual rate is CLK_HZ / CPB (baud error = CLK_HZ / (CPB * BAUD) - 1; 0 for
// the defaults 12 MHz / 3 Mbaud, CPB = 4). CPB must be >= 2.
// Stream input (valid/ready): a byte is taken when s_valid && s_ready. The
// start bit appears on tx the cycle after the handshake. s_ready is high when
// idle and in the last cycle of the stop bit, so back-to-back bytes leave
// with no idle gap: one byte every 10 * CPB clocks.
module uart_tx #(
    parameter integer CLK_HZ = 12_000_000,
    parameter integer BAUD   = 3_000_000
) (
    input  wire       clk,
    input  wire       rst,
    input  wire       s_valid,
    output wire       s_ready,
    input  wire [7:0] s_data,
    output reg        tx
);
  localparam integer CPB = (CLK_HZ + BAUD / 2) / BAUD;
  // At least 2 clocks per bit (the counter), and the rounded bit period within
  // 3 % of the baud rate: the stop bit is sampled 9.5 bits after the start
  // edge, so 3 % drifts 0.29 bit and leaves 0.2 bit for sampling jitter.
  generate
    if (BAUD < 1 || CPB < 2 || 100 * (CLK_HZ > CPB * BAUD ? CLK_HZ - CPB * BAUD : CPB * BAUD - CLK_HZ) >
        3 * CPB * BAUD) begin : g_bad_params
      uart_tx_illegal_parameters u_stop ();  // no such module: stops elaboration
    end
  endgenerate
  localparam integer CW = (CPB > 2) ? $clog2(CPB) : 1;
  localparam [CW-1:0] CNT_LAST = CPB[CW-1:0] - 1'b1;

  reg [CW-1:0] cnt;
  reg [3:0] bitn;  // 0 start, 1..8 data bits 0..7, 9 stop
  reg [7:0] shreg;
  reg busy;

  wire bit_end = (cnt == CNT_LAST);
  assign s_ready = !busy || (bitn == 4'd9 && bit_end);

  always @(posedge clk) begin
    if (rst) begin
      busy  <= 1'b0;
      tx    <= 1'b1;
      cnt   <= {CW{1'b0}};
      bitn  <= 4'd0;
      shreg <= 8'd0;
    end else if (s_valid && s_ready) begin
      busy  <= 1'b1;
      tx    <= 1'b0;
      shreg <= s_data;
      cnt   <= {CW{1'b0}};
      bitn  <= 4'd0;
    end else if (busy) begin
      if (bit_end) begin
        cnt <= {CW{1'b0}};
        if (bitn == 4'd9) begin
          busy <= 1'b0;
        end else begin
          bitn  <= bitn + 4'd1;
          tx    <= (bitn == 4'd8) ? 1'b1 : shreg[0];
          shreg <= {1'b0, shreg[7:1]};
        end
      end else begin
        cnt <= cnt + 1'b1;
      end
    end
  end
endmodule
`default_nettype wire
