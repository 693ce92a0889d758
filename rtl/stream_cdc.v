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
endmodule
`default_nettype wire
