`default_nettype none
// uart_rx: UART receiver, 8N1, LSB first, idle high.
//
// rx passes a two-flop synchroniser (it is asynchronous to clk). A falling
// edge starts a frame; the start bit is re-checked HALF = CPB/2 clocks later
// (a shorter low glitch is ignored), then every bit is sampled CPB clocks
// after the previous one, i.e. near the middle of each bit, CPB =
// round(CLK_HZ / BAUD) (must be >= 2).
// Latency (exact): if the first posedge that sees rx low is edge 0, m_valid
// is high after edge 2 + HALF + 9 * CPB (2 synchroniser stages, half a bit to
// the start-bit middle, 9 bits to the stop-bit middle). The receiver is
// ready for the next start bit right after the stop-bit sample, so a
// transmitter up to ~(CPB/2 - 1)/ (9.5 CPB) faster still works back to back.
// A stop bit read as 0 is a framing error: frame_err pulses one clock, the
// byte is dropped and the receiver waits for the line to return high.
// Output: valid/ready with a one-byte holding register; a byte completing
// while the previous one is still not taken is dropped (overrun pulses).
module uart_rx #(
    parameter integer CLK_HZ = 12_000_000,
    parameter integer BAUD   = 3_000_000
) (
    input  wire       clk,
    input  wire       rst,
    input  wire       rx,
    output reg        m_valid,
    input  wire       m_ready,
    output reg  [7:0] m_data,
    output reg        frame_err,
    output reg        overrun
);
  localparam integer CPB = (CLK_HZ + BAUD / 2) / BAUD;
  // At least 2 clocks per bit (HALF >= 1), and the rounded bit period within
  // 3 % of the baud rate: the stop bit is sampled 9.5 bits after the start
  // edge, so 3 % drifts 0.29 bit and leaves 0.2 bit for sampling jitter.
  generate
    if (BAUD < 1 || CPB < 2 || 100 * (CLK_HZ > CPB * BAUD ? CLK_HZ - CPB * BAUD : CPB * BAUD - CLK_HZ) >
        3 * CPB * BAUD) begin : g_bad_params
      uart_rx_illegal_parameters u_stop ();  // no such module: stops elaboration
    end
  endgenerate
  localparam integer HALF = CPB / 2;
  localparam integer CW = (CPB > 2) ? $clog2(CPB) : 1;
  localparam [CW-1:0] CNT_LAST = CPB[CW-1:0] - 1'b1;
  localparam [CW-1:0] HALF_LAST = HALF[CW-1:0] - 1'b1;

  localparam [2:0] S_IDLE = 3'd0, S_START = 3'd1, S_DATA = 3'd2, S_STOP = 3'd3,
                   S_WAIT = 3'd4;

  reg rx_s1, rx_s2;
  reg [2:0] state;
  reg [CW-1:0] cnt;
  reg [2:0] bitn;
  reg [7:0] shreg;

  always @(posedge clk) begin
    if (rst) begin
      rx_s1 <= 1'b1;
      rx_s2 <= 1'b1;
    end else begin
      rx_s1 <= rx;
      rx_s2 <= rx_s1;
    end
  end

  always @(posedge clk) begin
    frame_err <= 1'b0;
    overrun   <= 1'b0;
    if (m_valid && m_ready) m_valid <= 1'b0;
    if (rst) begin
      state   <= S_IDLE;
      cnt     <= {CW{1'b0}};
      bitn    <= 3'd0;
      shreg   <= 8'd0;
      m_valid <= 1'b0;
      m_data  <= 8'd0;
    end else begin
      case (state)
        S_IDLE:
          if (!rx_s2) begin
            state <= S_START;
            cnt   <= {CW{1'b0}};
          end
        S_START:
          if (cnt == HALF_LAST) begin
            cnt   <= {CW{1'b0}};
            bitn  <= 3'd0;
            state <= rx_s2 ? S_IDLE : S_DATA;
          end else begin
            cnt <= cnt + 1'b1;
          end
        S_DATA:
          if (cnt == CNT_LAST) begin
            cnt   <= {CW{1'b0}};
            shreg <= {rx_s2, shreg[7:1]};
            bitn  <= bitn + 3'd1;
            if (bitn == 3'd7) state <= S_STOP;
          end else begin
            cnt <= cnt + 1'b1;
          end
        S_STOP:
          if (cnt == CNT_LAST) begin
            cnt <= {CW{1'b0}};
            if (!rx_s2) begin
              frame_err <= 1'b1;
              state     <= S_WAIT;
            end else begin
              state <= S_IDLE;
              if (m_valid && !m_ready) begin
                overrun <= 1'b1;
              end else begin
                m_valid <= 1'b1;
                m_data  <= shreg;
              end
            end
          end else begin
            cnt <= cnt + 1'b1;
          end
        default:  // S_WAIT: line must return high before the next start bit
          if (rx_s2) state <= S_IDLE;
      endcase
    end
  end
`ifdef FORMAL
  // Properties (tests/formal/uart_rx.sby). The rx line is assumed to carry
  // what an 8N1 transmitter at the same bit period sends (the FPGA's own
  // uart_tx, or the host's bridge at the link's baud): frames of any byte,
  // back to back or after any idle time, a frame's stop bit possibly
  // spoiled (held low), and after a spoiled one at least one idle bit
  // (without it any UART can mis-frame the next byte; the link's COBS
  // framing recovers at its next delimiter). m_ready is free; the first
  // clock resets. Proven: each good frame's byte is delivered once, in
  // order, with its value (or overrun pulses if the previous byte was not
  // taken); each spoiled frame pulses frame_err and delivers nothing;
  // nothing is delivered or flagged without a frame.
  reg f_past = 1'b0;
  always @(posedge clk) f_past <= 1'b1;
  always @(*) if (!f_past) assume (rst);
  always @(*) if (f_past) assume (!rst);

  localparam [15:0] F_CPB = CPB, F_HALF = HALF;
  localparam [15:0] F_DONE = 16'd3 + F_HALF + 16'd9 * F_CPB;  // clocks from start bit to the stop sample + 1
  (* anyseq *) reg f_go;
  (* anyseq *) reg [7:0] f_new;
  (* anyseq *) reg f_newbad;
  reg f_on, f_hasp;           // a frame on the line; a previous frame exists
  reg [3:0] f_bit;            // 0 start, 1..8 data, 9 stop
  reg [15:0] f_bt;            // clock within the bit
  reg [15:0] f_sc, f_sp;      // clocks since the current / previous frame's start
  reg [7:0] f_bc, f_bp;
  reg f_badc, f_badp;
  reg [15:0] f_idle;          // idle clocks since the last frame ended
  reg f_l1, f_l2;             // the line one and two clocks ago
  wire f_line = !f_on ? 1'b1 : (f_bit == 4'd0) ? 1'b0 : (f_bit <= 4'd8) ? f_bc[f_bit[2:0] - 3'd1] : !f_badc;
  always @(*) assume (rx == f_line);
  wire f_end = f_on && f_bit == 4'd9 && f_bt == F_CPB - 16'd1;  // last clock of the stop bit
  wire f_start = f_go && (f_on ? (f_end && !f_badc) : (!f_badc || f_idle >= F_CPB));
  function automatic [15:0] f_inc(input [15:0] x);
    f_inc = (x == 16'hFFFF) ? x : x + 16'd1;
  endfunction
  always @(posedge clk)
    if (rst) begin
      f_on <= 1'b0;
      f_hasp <= 1'b0;
      f_sc <= 16'hFFFF;
      f_sp <= 16'hFFFF;
      f_badc <= 1'b0;
      f_badp <= 1'b0;
      f_idle <= 16'hFFFF;
      f_l1 <= 1'b1;
      f_l2 <= 1'b1;
      f_bit <= 4'd0;
      f_bt <= 16'd0;
    end else begin
      f_l1 <= f_line;
      f_l2 <= f_l1;
      f_sc <= f_inc(f_sc);
      f_sp <= f_inc(f_sp);
      if (f_start) begin
        f_on <= 1'b1;
        f_bit <= 4'd0;
        f_bt <= 16'd0;
        f_sc <= 16'd0;
        f_sp <= f_inc(f_sc);
        f_bc <= f_new;
        f_bp <= f_bc;
        f_badc <= f_newbad;
        f_badp <= f_badc;
        f_hasp <= f_sc != 16'hFFFF;
      end else if (f_on) begin
        if (f_end) begin
          f_on <= 1'b0;
          f_idle <= 16'd0;
        end else if (f_bt == F_CPB - 16'd1) begin
          f_bt <= 16'd0;
          f_bit <= f_bit + 4'd1;
        end else f_bt <= f_bt + 16'd1;
      end else f_idle <= f_inc(f_idle);
    end

  // The frame the receiver works on: the current one from its third
  // clock (two synchroniser stages and the edge), else the previous one.
  wire f_cur = f_sc >= 16'd3 || !f_hasp;
  wire [15:0] r_s = f_cur ? f_sc : f_sp;
  wire [7:0] r_byte = f_cur ? f_bc : f_bp;
  wire r_bad = f_cur ? f_badc : f_badp;
  wire [15:0] f_cnt = {{(16 - CW){1'b0}}, cnt};
  wire [15:0] f_bitn = {13'd0, bitn};
  wire [7:0] f_mask = (8'd1 << bitn) - 8'd1;
  always @(*)
    if (f_past) begin
      assert (rx_s1 == f_l1 && rx_s2 == f_l2);
      if (f_on) assert (f_bit <= 4'd9 && f_sc == {12'd0, f_bit} * F_CPB + f_bt && f_bt < F_CPB);
      if (f_hasp) assert (f_sp >= 16'd10 * F_CPB + f_sc || f_sp == 16'hFFFF);
      if (!f_on && f_sc != 16'hFFFF) assert (f_sc == 16'hFFFF || f_sc >= 16'd10 * F_CPB);
      if (!f_on && f_badc && f_sc != 16'hFFFF) assert (f_idle == 16'hFFFF || f_sc == 16'd10 * F_CPB + f_idle);
      if (r_s < 16'd3 || r_s == 16'hFFFF) assert (state == S_IDLE || (state == S_WAIT && r_bad));
      else if (r_s < 16'd3 + F_HALF) assert (state == S_START && f_cnt == r_s - 16'd3);
      else if (r_s < 16'd3 + F_HALF + 16'd8 * F_CPB)
        assert (state == S_DATA && f_bitn * F_CPB + f_cnt == r_s - 16'd3 - F_HALF && f_cnt < F_CPB &&
                ((shreg >> (4'd8 - {1'b0, bitn})) == (r_byte & f_mask)));
      else if (r_s < F_DONE)
        assert (state == S_STOP && f_cnt == r_s - 16'd3 - F_HALF - 16'd8 * F_CPB && shreg == r_byte);
      else assert (state == S_IDLE || (state == S_WAIT && r_bad));
      if (state == S_WAIT && r_s >= F_DONE && !f_cur) assert (r_bad);
    end

  // What leaves the receiver, checked against the model alone: the clock
  // after a frame's stop-bit sample, its byte (or overrun, or frame_err).
  reg f_chk = 1'b0, f_chk_bad, f_chk_full;
  reg [7:0] f_chk_byte;
  always @(posedge clk) begin
    f_chk <= !rst && r_s == F_DONE - 16'd1;
    f_chk_bad <= r_bad;
    f_chk_full <= m_valid && !m_ready;
    f_chk_byte <= r_byte;
  end
  reg f_prev_valid;
  always @(posedge clk) f_prev_valid <= !rst && m_valid && !m_ready;
  always @(*)
    if (f_past) begin
      if (f_chk && f_chk_bad) assert (frame_err && !overrun && (m_valid == f_prev_valid));
      if (f_chk && !f_chk_bad && f_chk_full) assert (overrun && !frame_err);
      if (f_chk && !f_chk_bad && !f_chk_full) assert (m_valid && m_data == f_chk_byte && !frame_err && !overrun);
      if (!f_chk) assert (!frame_err && !overrun && (m_valid == f_prev_valid));
    end

  always @(posedge clk)
    if (f_past) begin
      cover (f_chk && !f_chk_bad && !f_chk_full && f_hasp && f_sp == 16'd10 * F_CPB + f_sc);  // back to back
      cover (f_chk && f_chk_bad);                  // a spoiled frame flagged
      cover (f_chk && f_chk_full);                 // an overrun
      cover (f_chk && !f_chk_bad && f_badp);       // a good byte after a spoiled frame
    end
`endif
endmodule
`default_nettype wire
