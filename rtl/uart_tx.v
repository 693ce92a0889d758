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
`ifdef FORMAL
  // Properties (tests/formal/uart.sby): for any input bytes and
  // handshakes, the line is idle high, then per byte taken a start bit,
  // the 8 bits LSB first and a stop bit, each exactly CPB clocks, from the
  // clock after the handshake; the next byte is taken only in the stop
  // bit's last clock or later. The first clock resets.
  reg f_past = 1'b0;
  always @(posedge clk) f_past <= 1'b1;
  always @(*) if (!f_past) assume (rst);
  always @(*) if (f_past) assume (!rst);

  localparam [15:0] F_CPB = CPB;
  reg f_on;
  reg [3:0] f_bit;
  reg [15:0] f_bt;
  reg [7:0] f_byte;
  wire f_last = f_on && f_bit == 4'd9 && f_bt == F_CPB - 16'd1;
  always @(posedge clk)
    if (rst) begin
      f_on <= 1'b0;
      f_bit <= 4'd0;
      f_bt <= 16'd0;
    end else if (s_valid && s_ready) begin
      f_on <= 1'b1;
      f_bit <= 4'd0;
      f_bt <= 16'd0;
      f_byte <= s_data;
    end else if (f_on) begin
      if (f_last) f_on <= 1'b0;
      else if (f_bt == F_CPB - 16'd1) begin
        f_bt <= 16'd0;
        f_bit <= f_bit + 4'd1;
      end else f_bt <= f_bt + 16'd1;
    end
  always @(*)
    if (f_past) begin
      assert (s_ready == (!f_on || f_last));
      if (!f_on) assert (tx);
      else if (f_bit == 4'd0) assert (!tx);
      else if (f_bit <= 4'd8) assert (tx == f_byte[f_bit[2:0] - 3'd1]);
      else assert (tx && f_bit == 4'd9);
      // The state, for induction: the counters are the model's.
      assert (busy == f_on);
      if (f_on) assert (bitn == f_bit && {{(16 - CW){1'b0}}, cnt} == f_bt && f_bt < F_CPB &&
                        shreg == (f_byte >> f_bit));
    end
  always @(posedge clk)
    if (f_past) begin
      cover (f_last && s_valid);           // back to back
      cover (f_on && f_bit == 4'd8 && tx);  // a 1 in the last data bit
    end
`endif
endmodule
`default_nettype wire
