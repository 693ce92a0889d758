`default_nettype none
// izhikevich_layer: one Izhikevich neuron update in 13 clocks, for the frame
// engine (which keeps the neurons' state and drives this unit over its IO
// bus). Bit-exact with IzhikevichLayer::update of hls/izhikevich_layer.h,
// whose header is the spec of the math, the Q formats (v Q9.22, U Q.FU,
// J Q9.22), the rounding rnd(y >> n) = floor((y + 2^(n-1)) / 2^n) and the
// saturations (xs int16, J int32, v >= V_MIN, U in [-2^30, 2^30)).
//
// Datapath: ONE signed 16x16 multiplier, product registered (p), and ONE
// round-shift unit: {q, qc} <= {y, 0} >>> n on a 47-bit y, n = 0..63 (the
// count fields' low 6 bits), so q = floor(y / 2^n) and qc = bit n-1 of y,
// the rounding carry: rnd = q + qc, added as the carry-in of the adder that
// consumes it (n >= 48 gives q + qc = 0, as the C++ does for |y| < 2^46).
// y doubles as the accumulator of the split products m (sh 2^15 + sl).
// Shifts of a product p by a count c use y = p 2^15 and c + 15 (exact: the
// low 15 bits are 0), which turns the gain's left shift into a right shift:
// J = rnd((p 2^15) >> (15 + gsr - gsl)) for gsl <= 15 (gain_shift >= -15).
// Schedule; E = the handshake edge, sK = the clock after edge E+K; a MUL in
// sK gives p in sK+1, a SH in sK gives {q, qc} in sK+1:
//   E   from the ports and words: y = ic ? clamp(x - x_prev, 0, 2^31-1) : x,
//       wh = (v + 62.5 mV)[30:15], wl = v[14:0], vh = rnd(v >> 14), uacc = U,
//       vacc = v + C (x_prev' = ic ? x : x_prev is the microcode's: it
//       knows both, and a copy here would have to outlive the update)
//   s0  MUL wh*wl    SH xs' = y >> x_shift        y = U
//   s1  MUL m4*Uh    SH U22 = y >> (FU-22)        xs = sat16(xs'), sq = p >> 14
//   s2  MUL m4*Ul    y = p 2^15                   vacc -= U22
//   s3  MUL wh*wh    y += p
//   s4  MUL m3*vh    SH c4U = y >> s4             sq += p (sq = wh^2 + rnd(wh wl >> 14))
//   s5  MUL xs*gain  y = p 2^15                   uacc -= c4U
//   s6  MUL m2*sqh   SH c3v = y >> (s3 + 15)      y = p 2^15
//   s7  MUL m2*sql   SH J = y >> (15 + gsr - gsl) y = p 2^15, uacc += c3v
//   s8  y += p       vacc += sat32(J)
//   s9  SH c2w2 = y >> s2
//   s10 vacc += int32(c2w2)                       (vacc = v' complete)
//   s11 spike = vacc >= V_PEAK; uacc = sat_u(uacc) + (spike ? u_jump : 0)
//   s12 out_v = spike ? v_reset : max(vacc, V_MIN), out_u = sat_u(uacc),
//       out_spike, out_valid = in_ready = 1 (edge E+13)
//   (13, not more: the engine's neuron loop takes 14 clocks a neuron.)
//
// Widths (the C++'s int64 intermediates; why nothing wraps, for ANY 32-bit
// x, x_prev, v, U and any config): the operands are 16-bit, so |p| <= 2^30;
// y = p 2^15 + p' < 2^45 + 2^30 < 2^46: 47 bits signed. vacc = v + C - U22
// + J + c2w2, five int32 terms: |vacc| < 5 2^31 < 2^34: 35 bits. uacc =
// U - c4U + c3v: |U| <= 2^31, |c4U| <= 2^45 + 2^30, |c3v| <= 2^30: 47 bits;
// then sat_u(.) + u_jump < 2^32. c2w2 is truncated to int32 as in the C++
// (square_term returns int32), including a rounding carry into bit 31.
// Operand fields as the engine's lt/mpy take them: wh = w[30:15], vh = the
// low 16 bits of rnd(v >> 14), sqh = sq[30:15], Uh = U[30:15]. They equal
// the C++'s values whenever those fit int16: v in [-2^29 - 2^13, 2^29 -
// 2^13) (the vh bound; it holds the stored range [V_MIN, V_PEAK) and every
// v_reset) and U in [-2^30, 2^30) (its saturation range). Beyond that the
// C++ itself overflows int32 (w^2, m3 vh: undefined behaviour), so that is
// the domain of the equivalence; the unit's outputs never leave it.
//
// Timing: an input accepted at edge E (in_valid && in_ready; in_ready =
// idle) drops in_ready and out_valid at E; results, out_valid and in_ready
// come at edge E+13: back to back, one update per 14 clocks. The results
// hold until the next update's replace them at its edge E+13, so the
// engine may read one neuron's results while the unit computes the next
// (the microcode's nu_layer does).
// The ports are used at E through the adders above: drive them from
// registers. Configuration: cfg_we writes a word while the unit is idle
// (in_ready) and not in the clock of the handshake; the unit reads its
// constants during the update, so a write while busy would mix two
// configurations. The microcode writes a layer's words only between
// layers (neuron_unit in rtl/ucode/dtmf_chain.fe), and the top's C++
// models (hls::IzhikevichUnitPort) throw on any write while busy, so every
// microcode test checks that contract.
//
// Resources (the unit alone; yosys 0.23 synth_ice40 -dsp -abc9 as
// scripts/synth_ice40.sh; yowasp yosys synth_ecp5 / nextpnr-ecp5 --85k
// out of context): iCE40 1407 SB_LUT4, 546 flip-flops, 1 SB_MAC16 (of
// which the 47-bit round-shift unit is ~335 LUT4; 203 of the flip-flops
// hold the configuration). ECP5 (scripts/synth_ecp5.sh izhikevich_layer
// --pnr --freq 50 --device 85k): 1234 LUT4 (1550 placed), 578 FF, 1
// MULT18X18D, Fmax 82.5 / 85.8 / 85.9 MHz at seeds 1-3. The constants are
// not copied at the handshake (the microcode writes them between updates,
// which ucode/engine_ports.h checks): on the iCE40 each such flip-flop
// would take a logic cell of its own.
module izhikevich_layer (
    input  wire        clk,
    input  wire        rst,
    input  wire        cfg_we,
    input  wire [4:0]  cfg_addr,
    input  wire [31:0] cfg_data,
    input  wire        in_valid,
    output wire        in_ready,
    input  wire [31:0] in_x,
    input  wire [31:0] in_x_prev,
    input  wire [31:0] in_v,
    input  wire [31:0] in_u,
    output reg         out_valid,
    output reg         out_spike,
    output reg  [31:0] out_v,
    output reg  [31:0] out_u
);
  localparam signed [34:0] V_PEAK = 35'sd125829120;    // 30 mV in Q9.22
  localparam signed [34:0] V_MIN = -35'sd536870912;    // -128 mV
  localparam [15:0] W_OFF_H = 16'd8000;                // 62.5 mV = 8000 2^15 (low 15 bits 0)

  // ---- configuration words (field use as the microcode reads DMEM) --------
  `include "neuron_config.vh"
  // v_init and u_init are the state's first values: the caller's (the
  // microcode's or rtl/izhikevich_lanes.v's), not this unit's.
  /* verilator lint_off UNUSEDSIGNAL */
  wire unused_init = ^{c_vinit, c_uinit};
  /* verilator lint_on UNUSEDSIGNAL */

  // ---- sequencer -----------------------------------------------------------
  reg       busy;
  reg [3:0] step;
  wire      go = in_valid && !busy;
  assign in_ready = !busy;
`ifndef SYNTHESIS
  // The configuration contract (header): no constant word in the clock of
  // the handshake or while an update runs, except in its last clock
  // (step 12: the word lands at edge E+13, where the results are taken).
  // hls::IzhikevichUnitPort and IzhikevichLanesPort check the same in the
  // C++ models; this is the check of every Verilated top (--assert).
  always @(posedge clk)
    if (!rst && cfg_we)
      assert (!go && !(busy && step != 4'd12))
      else $error("izhikevich_layer: constant word %0d written while an update runs (the unit reads its constants during the update)", cfg_addr);
`endif

  // The constants are read where they are used, from the configuration
  // words themselves (no copy: they must not change during an update, see
  // the header).
  wire [5:0] s3_n = c_s3 + 6'd15;            // c3v = rnd((p << 15) >> (s3 + 15))
  wire [5:0] j_n = 6'd15 + c_gsr - c_gsl;    // J = rnd((p << 15) >> (15 + gsr - gsl))

  // ---- registers ------------------------------------------------------------
  reg  [15:0] wh, vh, xs;            // multiplier operands: w[30:15], rnd(v >> 14), sat16(..)
  reg  [14:0] wl;                    // w[14:0] = v[14:0] (62.5 mV = 8000 2^15)
  reg  [30:0] sq;                    // wh^2 + rnd(wh wl >> 14) (< 2^30 in the domain)
  reg         sq_c;                  // its rounding carry, added with wh^2
  reg  signed [31:0] p;              // the product
  reg  signed [46:0] y;              // round-shift input / product accumulator
  reg  signed [46:0] q;              // floor(y >> n) ...
  reg         qc;                    // ... and the rounding carry: rnd = q + qc
  reg  signed [34:0] vacc;           // v' = v + C - U22 + J + c2w2
  reg  signed [46:0] uacc;           // U, then U - c4U + c3v

  // ---- multiplier: p = ma * mb, registered ----------------------------------
  reg  [15:0] ma, mb;
  always @* begin
    case (step)
      4'd0: begin ma = wh; mb = {1'b0, wl}; end
      4'd1: begin ma = c_m4; mb = uacc[30:15]; end
      4'd2: begin ma = c_m4; mb = {1'b0, uacc[14:0]}; end
      4'd3: begin ma = wh; mb = wh; end
      4'd4: begin ma = c_m3; mb = vh; end
      4'd5: begin ma = c_gain; mb = xs; end
      4'd6: begin ma = c_m2; mb = sq[30:15]; end
      default: begin ma = c_m2; mb = {1'b0, sq[14:0]}; end
    endcase
  end
  always @(posedge clk) p <= $signed(ma) * $signed(mb);
  wire signed [46:0] p47 = {{15{p[31]}}, p};
  wire signed [46:0] p15 = {p, 15'd0};             // |p| <= 2^30: no loss

  // ---- round-shift unit: (q, qc) = floor(y >> sn), bit sn-1 of y ------------
  reg  [5:0] sn;
  always @* begin
    case (step)
      4'd0: sn = c_xsh;
      4'd1: sn = c_fu;
      4'd4: sn = c_s4;
      4'd6: sn = s3_n;
      4'd7: sn = j_n;
      default: sn = c_s2;
    endcase
  end
  wire signed [47:0] sh = $signed({y, 1'b0}) >>> sn;
  always @(posedge clk) {q, qc} <= sh;

  // Saturations of rnd = q + qc to int16 (xs) and int32 (J): out of range
  // when q is (q = MAX rounding up also overflows; q = MIN - 1 rounding up
  // gives MIN, which the saturation gives too); the bound's low bits are all
  // !sign, its high bits the sign.
  wire xs_ovf = q[46:15] != {32{q[46]}} || (!q[46] && &q[14:0] && qc);
  wire j_ovf = q[46:31] != {16{q[46]}} || (!q[46] && &q[30:0] && qc);
  // c2w2 = int32(rnd): q[31:0] = 2^31 - 1 rounding up wraps to -2^31.
  wire c2_wrap = q[31] || (&q[30:0] && qc);

  // ---- vacc += addend + cin (one adder; the carry-in enters below bit 0) ------
  reg  [34:0] v_add;
  reg         v_cin;
  always @* begin
    v_cin = qc;
    case (step)
      4'd2: begin v_add = ~{{3{q[31]}}, q[31:0]}; v_cin = !qc; end  // - U22 (fits int32)
      4'd8: begin                                                    // + sat32(J)
        v_add = j_ovf ? {{4{q[46]}}, {31{!q[46]}}} : {{3{q[31]}}, q[31:0]};
        v_cin = qc && !j_ovf;
      end
      default: v_add = {{3{c2_wrap}}, q[31:0]};                     // + c2w2
    endcase
    if (go) begin v_add = {{3{c_const[31]}}, c_const}; v_cin = 1'b0; end
  end
  wire [35:0] v_sum = {go ? {{3{in_v[31]}}, in_v} : vacc, 1'b1} + {v_add, v_cin};

  // ---- uacc: U - c4U + c3v, then sat(.) + (spike ? u_jump : 0) ----------------
  wire [31:0] u_sat = (uacc[46:30] == {17{uacc[46]}}) ? uacc[31:0]
                                                       : {{2{uacc[46]}}, {30{!uacc[46]}}};
  wire spike = vacc >= V_PEAK;
  wire [46:0] u_base = step == 4'd11 ? {{15{u_sat[31]}}, u_sat} : uacc;
  wire [46:0] u_add = step == 4'd5 ? ~q : step == 4'd7 ? q
                    : spike ? {{15{c_ujump[31]}}, c_ujump} : 47'd0;
  wire        u_cin = step == 4'd5 ? !qc : step == 4'd7 && qc;
  wire [47:0] u_sum = {u_base, 1'b1} + {u_add, u_cin};
  wire unused_lsb = &{1'b0, v_sum[0], u_sum[0]};   // the carry-in positions

  // ---- input: drive = ic ? clamp(x - x_prev, 0, 2^31 - 1) : x ---------------
  wire [32:0] dx = {in_x[31], in_x} - {in_x_prev[31], in_x_prev};
  wire [31:0] drive = !c_ic ? in_x : dx[32] ? 32'd0 : dx[31] ? 32'h7fffffff : dx[31:0];

  always @(posedge clk) begin
    if (rst) begin
      busy <= 1'b0; step <= 4'd0;
      out_valid <= 1'b1; out_spike <= 1'b0;
      out_v <= 32'd0; out_u <= 32'd0;
    end else if (go) begin
      busy <= 1'b1; step <= 4'd0; out_valid <= 1'b0;
      y <= {{15{drive[31]}}, drive};
      wh <= in_v[30:15] + W_OFF_H;
      vh <= in_v[29:14] + {15'd0, in_v[13]};
      wl <= in_v[14:0];
      uacc <= {{15{in_u[31]}}, in_u};
      vacc <= v_sum[35:1];                         // v + C
    end else if (busy) begin
      step <= step + 4'd1;
      case (step)
        4'd0: y <= {{15{uacc[31]}}, uacc[31:0]};
        4'd1: begin
          xs <= xs_ovf ? {q[46], {15{!q[46]}}} : q[15:0] + {15'd0, qc};
          sq <= {{13{p[31]}}, p[31:14]}; sq_c <= p[13];
        end
        4'd2: begin y <= p15; vacc <= v_sum[35:1]; end
        4'd3: y <= y + p47;
        4'd4: sq <= sq + p[30:0] + {30'd0, sq_c};
        4'd5: begin y <= p15; uacc <= u_sum[47:1]; end
        4'd6: y <= p15;
        4'd7: begin y <= p15; uacc <= u_sum[47:1]; end
        4'd8: begin y <= y + p47; vacc <= v_sum[35:1]; end
        4'd10: vacc <= v_sum[35:1];
        4'd11: uacc <= u_sum[47:1];
        4'd12: begin
          busy <= 1'b0; out_valid <= 1'b1; out_spike <= spike;
          out_u <= u_sat;
          out_v <= spike ? c_vreset : vacc < V_MIN ? V_MIN[31:0] : vacc[31:0];
        end
        default: ;
      endcase
    end
  end
endmodule
`default_nettype wire
