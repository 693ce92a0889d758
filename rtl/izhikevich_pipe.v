`default_nettype none
// izhikevich_pipe: a layer of N Izhikevich neurons as a pipeline, one neuron
// update a clock, the layer's state (v, U, x_prev) in its own RAM: the
// streaming form of hls/izhikevich_layer.h for rtl/dtmf_chain.v, where the
// taxel stream feeds the receptor layer directly. Bit-exact with
// IzhikevichLayer<N>::update(n, x) (the kernel's header is the spec of the
// Q formats, the rounding rnd(y >> s) = floor((y + 2^(s-1)) / 2^s) and the
// saturations); rtl/izhikevich_layer.v computes the same update in 13
// clocks on one multiplier for the frame engine, this block in 7 stages on
// eight (MULT18X18D), which is what one neuron a clock costs.
//
// Configuration: the unit's constant words (cfg_we/cfg_addr/cfg_data; the
// block hls::neuron_block makes, words 0..16: v_init, u_init, v_reset,
// u_jump, u_frac - 22, C, m2, s2, m3, s3, m4, s4, gain, gain_shift's right
// and left parts, x_shift, input_change); held while updates are in flight.
// init: every neuron := (v_init, u_init, x_prev 0), IzhikevichLayer::reset,
// one neuron a clock (N clocks, in_ready low meanwhile; `busy`).
//
// Stream: {n, x, last} in (valid/ready), {n, spike, v, U, last} out, one a
// clock, in input order; n any neuron index, any order. Each update reads
// its neuron's state at its handshake and writes it back as its result
// enters the output register; an input whose neuron is still in the
// pipeline waits (in_ready low) until that one is written back, so a
// neuron updated twice in a row is updated in order (a layer of fewer
// neurons than stages does that every frame).
//
// Stages (all move together while en = !out_valid || out_ready):
//   0  the handshake: n, x; the state read (registered RAM read)
//   a  the state registered again (the RAM's clock-to-out and its output
//      mux at 4096 neurons would otherwise share stage 1's clock)
//   1  drive = input_change ? clamp(x - x_prev, 0, 2^31-1) : x;
//      w = v + 62.5 mV: wh = w[30:15], wl = w[14:0]; vh = rnd(v >> 14);
//      Uh = U[30:15], Ul = U[14:0]; U22 = rnd(U >> (FU - 22))
//   2  xs = sat16(rnd(drive >> x_shift)); wh wh, wh wl, m4 Uh, m4 Ul, m3 vh;
//      vc = v + C - U22
//   3  p = xs gain; sq = wh wh + rnd(wh wl >> 14); c3v = rnd(m3 vh >> s3);
//      c4U = rnd((m4 Uh 2^15 + m4 Ul) >> s4)
//   4  J = sat32(rnd(p >> gsr) or p << gsl); m2 sqh, m2 sql (sq = sqh 2^15 +
//      sql); ua = U + c3v - c4U
//   5  c2w2 = int32(rnd((m2 sqh 2^15 + m2 sql) >> s2)); vj = vc + J;
//      un = sat(ua) to [-2^30, 2^30)
//   6  (the output register, and the write-back) v' = vj + c2w2; spike =
//      v' >= 30 mV; v = spike ? v_reset : max(v', V_MIN); U = spike ?
//      sat(un + u_jump) : un; x_prev = input_change ? x : x_prev
// Latency: an update taken at edge E is on the outputs after edge E + 7.
// Domain: as the unit's (rtl/izhikevich_layer.v): the operand fields equal
// the C++'s values for v in [-2^29 - 2^13, 2^29 - 2^13) and U in [-2^30,
// 2^30), which holds every stored state; x any 32-bit value.
module izhikevich_pipe #(
    parameter integer N = 9,
    parameter integer NB = (N > 1) ? $clog2(N) : 1
) (
    input  wire          clk,
    input  wire          rst,
    input  wire          cfg_we,
    input  wire [4:0]    cfg_addr,
    input  wire [31:0]   cfg_data,
    input  wire          init,
    output wire          busy,
    input  wire          in_valid,
    output wire          in_ready,
    input  wire [NB-1:0] in_n,
    input  wire [31:0]   in_x,
    input  wire          in_last,
    output reg           out_valid,
    input  wire          out_ready,
    output reg  [NB-1:0] out_n,
    output reg           out_spike,
    output reg  [31:0]   out_v,
    output reg  [31:0]   out_u,
    output reg           out_last
);
  generate
    if (N < 1 || N > 65536 || (1 << NB) < N) begin : g_bad_params
      izhikevich_pipe_illegal_parameters u_stop ();  // no such module: stops elaboration
    end
  endgenerate

  localparam signed [34:0] V_PEAK = 35'sd125829120;    // 30 mV in Q9.22
  localparam signed [34:0] V_MIN = -35'sd536870912;    // -128 mV
  localparam [15:0] W_OFF_H = 16'd8000;                // 62.5 mV = 8000 2^15
  localparam signed [47:0] U_MAX = 48'sd1073741823, U_MIN = -48'sd1073741824;

  // ---- configuration words (hls::neuron_block) ------------------------------
  `include "neuron_config.vh"

  // ---- state RAM: {x_prev, U, v} ---------------------------------------------
  reg [95:0] mem [0:N-1];
  reg [95:0] rd_q;
  reg [NB-1:0] init_n;
  reg initing;
  assign busy = initing;

  wire en = !out_valid || out_ready;
  // Valid stages 0, a, 1..5 and their neurons (the ones not yet written back).
  reg v0, v1, v2, v3, v4, v5;
  reg [NB-1:0] n0, n1, n2, n3, n4, n5;
  wire hit = (v0 && n0 == in_n) || (va && na == in_n) || (v1 && n1 == in_n) || (v2 && n2 == in_n) ||
             (v3 && n3 == in_n) || (v4 && n4 == in_n) || (v5 && n5 == in_n);
  assign in_ready = en && !initing && !hit;
  wire take = in_valid && in_ready;

  // ---- stage 0 ---------------------------------------------------------------
  reg [31:0] x0;
  reg l0;
  // Stage a: the read data registered once more (a block RAM's clock-to-out
  // and the output mux of a deep RAM get a clock of their own).
  reg [95:0] sa;
  reg [31:0] xa;
  reg [NB-1:0] na;
  reg la, va;
  wire signed [31:0] sv0 = sa[31:0], su0 = sa[63:32], sxp0 = sa[95:64];

  // ---- stage 1 ---------------------------------------------------------------
  wire signed [32:0] dx = {xa[31], xa} - {sxp0[31], sxp0};
  wire [31:0] drive_d = !c_ic ? xa : dx[32] ? 32'd0 : dx[31] ? 32'h7fffffff : dx[31:0];
  wire signed [32:0] u22_t = $signed({su0, 1'b0}) >>> c_fu;
  reg  [31:0] drive1, x1, xp1;
  reg  signed [31:0] v1r, u1r, u22_1;
  reg  signed [15:0] wh1, vh1, uh1;
  reg  [14:0] wl1, ul1;
  reg l1;

  // ---- stage 2 ---------------------------------------------------------------
  wire signed [32:0] xs_t = $signed({drive1, 1'b0}) >>> c_xsh;
  wire signed [32:0] xs_r = {xs_t[32], xs_t[32:1]} + {32'd0, xs_t[0]};
  wire xs_ovf = xs_r[32:15] != {18{xs_r[32]}};
  wire signed [15:0] xs_d = xs_ovf ? {xs_r[32], {15{!xs_r[32]}}} : xs_r[15:0];
  reg  signed [15:0] xs2;
  reg  signed [31:0] p_ww2, p_wl2, p_m4h2, p_m4l2, p_m33;
  reg  signed [34:0] vc2;
  reg  [31:0] x2, xp2;
  reg  signed [31:0] u2r;
  reg l2;

  // ---- stage 3 ---------------------------------------------------------------
  wire signed [32:0] wl_t = $signed({p_wl2, 1'b0}) >>> 14;        // rnd(wh wl >> 14)
  wire signed [31:0] sq_d = p_ww2 + (wl_t[32:1] + {31'd0, wl_t[0]});
  wire signed [32:0] c3_t = $signed({p_m33, 1'b0}) >>> c_s3;
  wire signed [46:0] m4acc = {p_m4h2, 15'd0} + {{15{p_m4l2[31]}}, p_m4l2};
  wire signed [47:0] c4_t = $signed({m4acc, 1'b0}) >>> c_s4;
  reg  signed [31:0] pg3, sq3, c3v3;
  reg  signed [46:0] c4u3;
  reg  signed [34:0] vc3;
  reg  [31:0] x3, xp3;
  reg  signed [31:0] u3r;
  reg l3;

  // ---- stage 4 ---------------------------------------------------------------
  wire signed [32:0] jr_t = $signed({pg3, 1'b0}) >>> c_gsr;
  wire signed [32:0] jr = {jr_t[32], jr_t[32:1]} + {32'd0, jr_t[0]};
  wire signed [46:0] jl = $signed({{15{pg3[31]}}, pg3}) <<< c_gsl;
  wire signed [46:0] jw = (c_gsl != 6'd0) ? jl : {{14{jr[32]}}, jr};
  wire j_ovf = jw[46:31] != {16{jw[46]}};
  wire signed [31:0] j_d = j_ovf ? {jw[46], {31{!jw[46]}}} : jw[31:0];
  wire signed [15:0] sqh = sq3[30:15];
  wire signed [15:0] sql = {1'b0, sq3[14:0]};
  wire signed [47:0] ua_d = {{16{u3r[31]}}, u3r} + {{16{c3v3[31]}}, c3v3} - {c4u3[46], c4u3};
  reg  signed [31:0] j4, p_m2h4, p_m2l4;
  reg  signed [47:0] ua4;
  reg  signed [34:0] vc4;
  reg  [31:0] x4, xp4;
  reg l4;

  // ---- stage 5 ---------------------------------------------------------------
  wire signed [46:0] m2acc = {p_m2h4, 15'd0} + {{15{p_m2l4[31]}}, p_m2l4};
  wire signed [47:0] c2_t = $signed({m2acc, 1'b0}) >>> c_s2;
  wire signed [47:0] c2_r = c2_t[47:1] + {46'd0, c2_t[0]};
  wire signed [47:0] un_d = ua4 > U_MAX ? U_MAX : ua4 < U_MIN ? U_MIN : ua4;
  reg  signed [31:0] c2w2_5, un5;
  reg  signed [34:0] vj5;
  reg  [31:0] x5, xp5;
  reg l5;

  // ---- stage 6: results and write-back ----------------------------------------
  wire signed [34:0] vn = vj5 + {{3{c2w2_5[31]}}, c2w2_5};
  wire spike = vn >= V_PEAK;
  wire signed [32:0] uj = {un5[31], un5} + {c_ujump[31], c_ujump};
  wire signed [31:0] uj_sat = (uj > 33'sd1073741823) ? 32'sd1073741823 :
                              (uj < -33'sd1073741824) ? -32'sd1073741824 : uj[31:0];
  wire [31:0] v_res = spike ? c_vreset : (vn < V_MIN) ? V_MIN[31:0] : vn[31:0];
  wire [31:0] u_res = spike ? uj_sat : un5;
  wire [31:0] xp_res = c_ic ? x5 : xp5;

  always @(posedge clk) begin
    // RAM: the write-back (or init) and the read of the next input.
    if (initing) mem[init_n] <= {32'd0, c_uinit, c_vinit};
    else if (en && v5) mem[n5] <= {xp_res, u_res, v_res};
    if (en) rd_q <= mem[in_n];
    if (en) begin
      n0 <= in_n; x0 <= in_x; l0 <= in_last;
      // a
      na <= n0; xa <= x0; la <= l0; sa <= rd_q;
      // 1
      n1 <= na; l1 <= la; x1 <= xa; xp1 <= sxp0; drive1 <= drive_d;
      v1r <= sv0; u1r <= su0;
      wh1 <= sv0[30:15] + W_OFF_H;
      wl1 <= sv0[14:0];
      vh1 <= sv0[29:14] + {15'd0, sv0[13]};
      uh1 <= su0[30:15];
      ul1 <= su0[14:0];
      u22_1 <= u22_t[32:1] + {31'd0, u22_t[0]};
      // 2
      n2 <= n1; l2 <= l1; x2 <= x1; xp2 <= xp1; u2r <= u1r;
      xs2 <= xs_d;
      p_ww2 <= wh1 * wh1;
      p_wl2 <= wh1 * $signed({1'b0, wl1});
      p_m4h2 <= $signed(c_m4) * uh1;
      p_m4l2 <= $signed(c_m4) * $signed({1'b0, ul1});
      p_m33 <= $signed(c_m3) * vh1;
      vc2 <= {{3{v1r[31]}}, v1r} + {{3{c_const[31]}}, c_const} - {{3{u22_1[31]}}, u22_1};
      // 3
      n3 <= n2; l3 <= l2; x3 <= x2; xp3 <= xp2; u3r <= u2r; vc3 <= vc2;
      pg3 <= xs2 * $signed(c_gain);
      sq3 <= sq_d;
      c3v3 <= c3_t[32:1] + {31'd0, c3_t[0]};
      c4u3 <= c4_t[47:1] + {46'd0, c4_t[0]};
      // 4
      n4 <= n3; l4 <= l3; x4 <= x3; xp4 <= xp3; vc4 <= vc3;
      j4 <= j_d;
      p_m2h4 <= $signed(c_m2) * sqh;
      p_m2l4 <= $signed(c_m2) * sql;
      ua4 <= ua_d;
      // 5
      n5 <= n4; l5 <= l4; x5 <= x4; xp5 <= xp4;
      c2w2_5 <= c2_r[31:0];
      vj5 <= vc4 + {{3{j4[31]}}, j4};
      un5 <= un_d[31:0];
      // 6
      out_n <= n5; out_last <= l5; out_spike <= spike;
      out_v <= v_res; out_u <= u_res;
    end
    if (rst) begin
      v0 <= 1'b0; va <= 1'b0; v1 <= 1'b0; v2 <= 1'b0; v3 <= 1'b0; v4 <= 1'b0; v5 <= 1'b0;
      out_valid <= 1'b0;
      initing <= 1'b0;
      init_n <= {NB{1'b0}};
    end else begin
      if (en) begin
        v0 <= take; va <= v0; v1 <= va; v2 <= v1; v3 <= v2; v4 <= v3; v5 <= v4;
        out_valid <= v5;
      end
      if (init && !initing) begin
        initing <= 1'b1;
        init_n <= {NB{1'b0}};
      end else if (initing) begin
        init_n <= init_n + 1'b1;
        if (init_n == NB'(N - 1)) initing <= 1'b0;
      end
    end
  end

  /* verilator lint_off UNUSEDSIGNAL */
  wire unused = &{1'b0, sq3[31], sv0[31], su0[31], c2_r[47:32], un_d[47:32], ua4[0], uj[0],
                  m4acc[0], c2_t[0]};
  /* verilator lint_on UNUSEDSIGNAL */
endmodule
`default_nettype wire
