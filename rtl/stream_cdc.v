`default_nettype none
// stream_cdc: a valid/ready stream of W-bit tokens from clock s_clk to clock
// m_clk, whatever the two frequencies, for sparse tokens (rtl/dtmf_top.v:
// one ADC sample a microsecond at 40 and 45 MHz). A toggle handshake: the
// data never passes a synchroniser, only the toggles do, and the data
// register they announce is stable for as long as the far side reads it.
//
//   s side: a token taken (s_valid && s_ready) goes into s_hold and req
//     toggles; s_ready is low until the m side has copied it (ack == req,
//     ack through SYNC flip-flops of s_clk).
//   m side: req through SYNC flip-flops of m_clk; when it differs from ack
//     and the output register is empty (or emptied in that clock), s_hold
//     is copied into m_data (it last changed with req, at least SYNC
//     whole m_clk periods earlier) and ack toggles.
// Two tokens can be held: one in m_data waiting for m_ready, the next in
// s_hold. Latency from the s-side take to m_valid: SYNC to SYNC + 1 m_clk
// edges. From the take to s_ready again, with m_data empty: that plus
// SYNC to SYNC + 1 s_clk edges (4 to 6 edges of the slower clock at SYNC
// = 2).
// Resets: s_rst and m_rst are each synchronous to their own clock and must
// overlap (one held until the other has been released once: dtmf_top's
// s_rst is m_rst through two s_clk flip-flops); no token is in flight
// across a reset.
module stream_cdc #(
    parameter integer W = 8,
    parameter integer SYNC = 2  // synchroniser flip-flops each way (2..4)
) (
    input  wire         s_clk,
    input  wire         s_rst,
    input  wire         s_valid,
    output wire         s_ready,
    input  wire [W-1:0] s_data,
    input  wire         m_clk,
    input  wire         m_rst,
    output reg          m_valid,
    input  wire         m_ready,
    output reg  [W-1:0] m_data
);
  generate
    if (W < 1 || SYNC < 2 || SYNC > 4) begin : g_bad_params
      stream_cdc_illegal_parameters u_stop ();  // no such module: stops elaboration
    end
  endgenerate

  reg         req, ack;  // toggles: a token announced (s side), copied (m side)
  reg [W-1:0] s_hold;
  (* ASYNC_REG = "TRUE" *) reg [SYNC-1:0] ack_sync;  // ack in s_clk, newest at bit 0
  (* ASYNC_REG = "TRUE" *) reg [SYNC-1:0] req_sync;  // req in m_clk, newest at bit 0

  // ---- s side
  assign s_ready = ack_sync[SYNC-1] == req;
  always @(posedge s_clk) begin
    if (s_rst) begin
      req <= 1'b0;
      s_hold <= {W{1'b0}};
      ack_sync <= {SYNC{1'b0}};
    end else begin
      ack_sync <= {ack_sync[SYNC-2:0], ack};
      if (s_valid && s_ready) begin
        s_hold <= s_data;
        req <= !req;
      end
    end
  end

  // ---- m side
  wire take = req_sync[SYNC-1] != ack && (!m_valid || m_ready);
  always @(posedge m_clk) begin
    if (m_rst) begin
      ack <= 1'b0;
      req_sync <= {SYNC{1'b0}};
      m_valid <= 1'b0;
      m_data <= {W{1'b0}};
    end else begin
      req_sync <= {req_sync[SYNC-2:0], req};
      if (take) begin
        m_data <= s_hold;
        ack <= !ack;
      end
      if (take) m_valid <= 1'b1;
      else if (m_ready) m_valid <= 1'b0;
    end
  end
`ifdef FORMAL
  // Properties (tests/formal/stream_cdc.sby, multiclock: s_clk and m_clk
  // are free inputs, so every ratio and every phase of the two clocks is
  // covered). Assumed: both resets held from the start until each side
  // has seen a clock edge in reset (the overlap this module requires),
  // and once released not raised again (no token in flight across a
  // reset). s_valid, s_data and m_ready are free.
  reg f_s_rstd = 1'b0, f_m_rstd = 1'b0;  // a clock edge seen in reset
  always @(posedge s_clk) if (s_rst) f_s_rstd <= 1'b1;
  always @(posedge m_clk) if (m_rst) f_m_rstd <= 1'b1;
  reg f_gpast = 1'b0;
  always @($global_clock) begin
    f_gpast <= 1'b1;
    if (!(f_s_rstd && f_m_rstd)) assume (s_rst && m_rst);
    if (f_gpast && !$past(s_rst)) assume (!s_rst);
    if (f_gpast && !$past(m_rst)) assume (!m_rst);
  end
  wire f_run = f_s_rstd && f_m_rstd && !s_rst && !m_rst;

  // Tokens counted apart: taken on the s side, copied into m_data,
  // delivered on the m side.
  reg [3:0] f_in = 4'd0, f_cp = 4'd0, f_out = 4'd0;
  always @(posedge s_clk)
    if (s_rst) f_in <= 4'd0;
    else if (s_valid && s_ready) f_in <= f_in + 4'd1;
  always @(posedge m_clk)
    if (m_rst) begin
      f_cp <= 4'd0;
      f_out <= 4'd0;
    end else begin
      if (take) f_cp <= f_cp + 4'd1;
      if (m_valid && m_ready) f_out <= f_out + 4'd1;
    end
  wire [3:0] f_pend = f_in - f_cp;    // announced, not yet copied (0 or 1)
  wire [3:0] f_held = f_cp - f_out;   // in m_data, not yet delivered (0 or 1)

  // The toggles along each synchroniser chain: a newer stage may differ
  // from the older ones only as one step, at most one change in flight.
  wire [SYNC:0] f_rchain = {req_sync, req};  // bit 0 newest
  wire [SYNC:0] f_achain = {ack_sync, ack};
  integer fk;
  reg f_rmono, f_amono;
  always @(*) begin
    f_rmono = 1'b1;
    f_amono = 1'b1;
    for (fk = 1; fk <= SYNC; fk = fk + 1) begin
      if (f_rchain[fk] == req && f_rchain[fk - 1] != req) f_rmono = 1'b0;
      if (f_achain[fk] == ack && f_achain[fk - 1] != ack) f_amono = 1'b0;
    end
  end

  // One token followed through: the f_idx-th taken must be the f_idx-th
  // delivered, with its data: none lost, none duplicated, order kept.
  (* anyconst *) reg [3:0] f_idx;
  reg [W-1:0] f_val;
  reg f_seen = 1'b0;  // the f_idx-th token was taken (in some lap of f_in)
  always @(posedge s_clk)
    if (s_rst) f_seen <= 1'b0;
    else if (s_valid && s_ready && f_in == f_idx) begin
      f_val <= s_data;
      f_seen <= 1'b1;
    end
  wire f_live = f_s_rstd && f_m_rstd;  // both sides reset once

  // In reset (after its first clock edge), a side holds its reset state.
  always @(*) begin
    if (f_s_rstd && s_rst) assert (req == 1'b0 && ack_sync == {SYNC{1'b0}} && f_in == 4'd0 && !f_seen);
    if (f_m_rstd && m_rst) assert (ack == 1'b0 && req_sync == {SYNC{1'b0}} && !m_valid &&
                                   f_cp == 4'd0 && f_out == 4'd0);
  end
  always @(*)
    if (f_live) begin
      if (!f_seen) assert (f_out <= f_cp && f_cp <= f_in && f_in <= f_idx);  // no lap yet
      if (f_seen && f_in - 4'd1 == f_idx) assert (s_hold == f_val);
      assert (f_pend <= 4'd1 && f_held <= 4'd1);
      assert ((f_pend == 4'd1) == (req != ack));
      assert ((f_held == 4'd1) == m_valid);
      assert (req == f_in[0] && ack == f_cp[0]);
      assert (f_rmono && f_amono);
      if (req != ack) assert (ack_sync == {SYNC{ack}});   // s side waits
      else assert (req_sync == {SYNC{req}});              // m side is idle
      if (m_valid && f_out == f_idx) assert (f_seen && m_data == f_val);
      assert (s_ready == (ack_sync[SYNC-1] == req));
    end

  // A shown token is held until taken.
  reg f_stall = 1'b0;  // at the last m_clk edge a token was shown and not taken
  reg [W-1:0] f_shown;
  always @(posedge m_clk) begin
    f_stall <= !m_rst && m_valid && !m_ready;
    f_shown <= m_data;
  end
  always @(*) begin
    if (f_m_rstd && m_rst) assert (!f_stall);
    if (f_m_rstd && !m_rst && f_stall) assert (m_valid && m_data == f_shown);
  end

  always @(*)
    if (f_run) begin
      cover (f_out == 4'd3);                             // three tokens through
      cover (m_valid && !s_ready && f_pend == 4'd1);     // two tokens held at once
    end
`endif
endmodule
`default_nettype wire
