`default_nettype none
// isqrt_pipe: pipelined integer square root, one result bit per stage, one
// radicand a clock. The restoring digit-by-digit method of hls/isqrt.h
// (IsqrtState::step), unrolled: stage s brings down radicand bits
// 2(W-1-s)+1 .. 2(W-1-s) and tries root digit 1, so after W stages
//   out_root = floor(sqrt(in_rad)), in_rad < 2^(2W).
// Each stage's registers have the widths the method needs there (root s+1
// bits, partial remainder s+2 bits, the radicand bits not yet consumed), so
// nothing constant is kept; the widest compare is W+2 bits (last stage).
//
// Timing: W clocks of latency counted in enabled clocks: a radicand taken
// at an edge with en = 1 is at out_root after W such edges. `en` low holds
// every stage (the caller's stall); `side` (SW bits) travels with its
// radicand, `in_valid` as out_valid (cleared by rst). `busy` is high while
// any stage holds a valid radicand.
module isqrt_pipe #(
    parameter integer W = 16,   // root bits (radicand 2W bits)
    parameter integer SW = 1    // side-band bits carried alongside
) (
    input  wire            clk,
    input  wire            rst,
    input  wire            en,
    input  wire            in_valid,
    input  wire [2*W-1:0]  in_rad,
    input  wire [SW-1:0]   in_side,
    output wire            out_valid,
    output wire [W-1:0]    out_root,
    output wire [SW-1:0]   out_side,
    output wire            busy
);
  generate
    if (W < 1 || W > 32 || SW < 1) begin : g_bad
      isqrt_pipe_illegal_parameters u_stop ();  // no such module: stops elaboration
    end
  endgenerate

  wire [W-1:0] valids;
  genvar s;
  generate
    for (s = 0; s < W; s = s + 1) begin : g_st
      // This stage's two radicand bits, the previous root and remainder.
      wire [1:0] top;
      wire [s+2:0] r;      // {rem_prev, top}
      wire [s+2:0] trial;  // {root_prev, 01}
      wire [s:0] root_d;
      wire [SW-1:0] side_d;
      wire v_d;
      wire ge = r >= trial;
      reg  [s:0] root_q;
      reg  [SW-1:0] side_q;
      reg  v_q;
      if (s == 0) begin : g_first
        assign top = in_rad[2*W-1 -: 2];
        assign r = {1'b0, top};
        assign trial = 3'b001;
        assign root_d = ge;
        assign side_d = in_side;
        assign v_d = in_valid;
      end else begin : g_next
        assign top = g_st[s-1].g_rest.rad_q[2*(W-s)-1 -: 2];
        assign r = {g_st[s-1].g_rest.rem_q, top};
        assign trial = {1'b0, g_st[s-1].root_q, 2'b01};
        assign root_d = {g_st[s-1].root_q, ge};
        assign side_d = g_st[s-1].side_q;
        assign v_d = g_st[s-1].v_q;
      end
      // The remainder and the radicand bits later stages consume (none
      // after the last stage).
      if (s < W - 1) begin : g_rest
        // After this step root < 2^(s+1) and rem <= 2 root < 2^(s+2): the
        // difference's top bit is always zero.
        /* verilator lint_off UNUSEDSIGNAL */
        wire [s+2:0] diff = ge ? r - trial : r;
        /* verilator lint_on UNUSEDSIGNAL */
        wire [2*(W-1-s)-1:0] rad_d;
        reg  [s+1:0] rem_q;
        reg  [2*(W-1-s)-1:0] rad_q;
        if (s == 0) begin : g_r0
          assign rad_d = in_rad[2*(W-1)-1:0];
        end else begin : g_rn
          assign rad_d = g_st[s-1].g_rest.rad_q[2*(W-1-s)-1:0];
        end
        always @(posedge clk)
          if (en) begin
            rem_q <= diff[s+1:0];
            rad_q <= rad_d;
          end
      end
      always @(posedge clk) begin
        if (en) begin
          root_q <= root_d;
          side_q <= side_d;
        end
        if (rst) v_q <= 1'b0;
        else if (en) v_q <= v_d;
      end
      assign valids[s] = v_q;
    end
  endgenerate

  assign out_valid = g_st[W-1].v_q;
  assign out_root = g_st[W-1].root_q;
  assign out_side = g_st[W-1].side_q;
  assign busy = |valids;
endmodule
`default_nettype wire
