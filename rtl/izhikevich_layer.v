`default_nettype none
// izhikevich_layer: one Izhikevich neuron update in 14 clocks, for the frame
// engine (which keeps the neurons' state and drives this unit over its IO
// bus). Bit-exact with IzhikevichLayer::update of hls/izhikevich_layer.h,
// whose header is the spec of the math, the Q formats (v Q9.22, U Q.FU,
// J Q9.22), the rounding rnd(y >> n) = floor((y + 2^(n-1)) / 2^n) and the
// saturations (xs int16, J int32, v >= V_MIN, U in [-2^30, 2^30)).
//
// Datapath: ONE signed 16x16 multiplier with a registered product p (SB_MAC16
// / MULT18X18D) and ONE round-shift unit r <= rnd(y >> n) on a 47-bit y,
// n = 0..63 (the count fields' low 6 bits): bit 0 of {y, 0} >>> n is bit
// n-1 of y, the rounding carry, so rnd = ({y,0} >>> n)[47:1] + bit 0; for
// n >= 48 this gives 0 as in the C++ (|y| < 2^46 < 2^(n-1)). y doubles as the
// accumulator of the split products (m * s with s = sh 2^15 + sl).
// Schedule (s0 = the clock after the handshake edge; MUL at sK: p is ready
// in sK+1; SH at sK: r is ready in sK+1):
//   s0  drive = ic ? clamp(x - x_prev, 0, 2^31-1) : x; wh = (v + 62.5 mV) >> 15,
//       vh = rnd(v >> 14) (fixed shifts: adders, not the shifter)
//   s1  MUL wh*wl             SH xs' = rnd(drive >> x_shift)      y = U
//   s2  MUL m3*vh             SH U22 = rnd(U >> (FU-22))          xs = sat16(r), sq = rnd(p >> 14)
//   s3  MUL wh*wh             y = m3*vh                           vacc -= U22
//   s4  MUL xs*gain           SH c3v = rnd(y >> s3)               sq += p; vacc += v
//   s5  MUL m2*sqh            y = p << 15                         uacc = U + c3v
//   s6  MUL m2*sql            SH J' = rnd(y >> (15 + gsr - gsl)) y = p << 15
//   s7  MUL m4*Uh             y += p                              vacc += sat32(J')
//   s8  MUL m4*Ul             SH c2w2 = rnd(y >> s2)              y = p << 15
//   s9                        y += p                              vacc += int32(c2w2)
//   s10                       SH c4U = rnd(y >> s4)
//   s11 uacc -= c4U
//   s12 spike = vacc >= V_PEAK; uacc = sat_u(uacc) + (spike ? u_jump : 0)
//   s13 out_v = spike ? v_reset : max(vacc, V_MIN), out_u = sat_u(uacc), out_spike
// The input gain shift is one right shift: (p << gsl) >> gsr = (p << 15) >>
// (15 - gsl + gsr), exact for gsl <= 15 (gain_shift >= -15) as the low 15
// bits of p << 15 are 0, and the two roundings coincide. vacc starts as the
// constant C; out_v and out_u hold v_reset and u_jump while busy (out_valid
// is 0 then), so only the 16 bits used after the handshake edge are copied.
//
// Widths (why nothing wraps, for ANY 32-bit x, x_prev, v, U and any config):
//   the multiplier's operands are 16-bit, so |p| <= 2^30; y = p 2^15 + p'
//   < 2^45 + 2^30 < 2^46: 47 bits signed (C++: int64). vacc = v + c2w2 + C -
//   U22 + J, five int32 terms: |vacc| < 5 2^31 < 2^34: 35 bits (int64).
//   uacc = U + c3v - c4U: |U| <= 2^31, |c3v| <= 2^30, |c4U| <= 2^45 + 2^30:
//   47 bits (int64); then sat(.) + u_jump < 2^32: fits too.
//   Operand fields (as the engine's lt/mpy take them): wh = w[30:15],
//   vh = low 16 bits of rnd(v >> 14), sqh = sq[30:15], Uh = U[30:15]. They
//   equal the C++ values (U >> 15 etc.) whenever those fit int16:
//   v in [-2^29 - 2^13, 2^29 - 2^13) (the vh bound; four times the stored
//   range [V_MIN, V_PEAK), v_reset included) and U in [-2^30, 2^30) (its
//   saturation range). Outside that the C++ itself overflows int32 (w^2,
//   m3 * vh: undefined behaviour), so this is the domain of the equivalence;
//   the unit's own outputs never leave it.
//
// Timing: an input accepted at edge E (in_valid && in_ready; in_ready = idle)
// drops in_ready and out_valid at E; the results are registered at edge E+14,
// where out_valid and in_ready rise: one update per 15 clocks back to back.
// Configuration: cfg_we writes a word any time; the words are copied at the
// handshake edge (a write at that very edge applies to the next update), so
// writes while busy never touch the update in flight.
//
// Resources (unit alone, Yosys 0.23 / yowasp nextpnr-ecp5): see the end of
// this comment block in the commit history; figures:
//   iCE40 (synth_ice40 -dsp): TBD
//   ECP5  (synth_ecp5):       TBD
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
    output reg  [31:0] out_u,
    output reg  [31:0] out_x_prev
);
  localparam signed [34:0] V_PEAK = 35'sd125829120;    // 30 mV in Q9.22
  localparam signed [34:0] V_MIN = -35'sd536870912;    // -128 mV
  localparam [15:0] W_OFF_H = 16'd8000;                // 62.5 mV = 8000 2^15 (low 15 bits 0)

  // ---- configuration words (field use as the microcode reads DMEM) --------
  reg [31:0] c_vreset, c_ujump, c_const;
  reg [15:0] c_m2, c_m3, c_m4, c_gain;
  reg [5:0]  c_fu, c_s2, c_s3, c_s4, c_gsr, c_gsl, c_xsh;
  reg        c_ic;
  always @(posedge clk)
    if (rst) begin
      c_vreset <= 0; c_ujump <= 0; c_const <= 0;
      c_m2 <= 0; c_m3 <= 0; c_m4 <= 0; c_gain <= 0;
      c_fu <= 0; c_s2 <= 0; c_s3 <= 0; c_s4 <= 0; c_gsr <= 0; c_gsl <= 0; c_xsh <= 0;
      c_ic <= 0;
    end else if (cfg_we)
      case (cfg_addr)
        5'd2: c_vreset <= cfg_data;
        5'd3: c_ujump <= cfg_data;
        5'd4: c_fu <= cfg_data[5:0];
        5'd5: c_const <= cfg_data;
        5'd6: c_m2 <= cfg_data[15:0];
        5'd7: c_s2 <= cfg_data[5:0];
        5'd8: c_m3 <= cfg_data[15:0];
        5'd9: c_s3 <= cfg_data[5:0];
        5'd10: c_m4 <= cfg_data[15:0];
        5'd11: c_s4 <= cfg_data[5:0];
        5'd12: c_gain <= cfg_data[15:0];
        5'd13: c_gsr <= cfg_data[5:0];
        5'd14: c_gsl <= cfg_data[5:0];
        5'd15: c_xsh <= cfg_data[5:0];
        5'd16: c_ic <= |cfg_data;
        default: ;
      endcase

  // ---- sequencer -----------------------------------------------------------
  reg       busy;
  reg [3:0] step;
  wire      go = in_valid && !busy;
  assign in_ready = !busy;

  // Copy of the words used after the handshake edge.
  reg [15:0] k_m2, k_m3, k_m4, k_gain;
  reg [5:0]  k_fu, k_s2, k_s3, k_s4, k_nj, k_xsh;
  reg        k_ic;
  always @(posedge clk)
    if (go) begin
      k_m2 <= c_m2; k_m3 <= c_m3; k_m4 <= c_m4; k_gain <= c_gain;
      k_fu <= c_fu; k_s2 <= c_s2; k_s3 <= c_s3; k_s4 <= c_s4; k_xsh <= c_xsh;
      k_nj <= 6'd15 + c_gsr - c_gsl;
      k_ic <= c_ic;
    end

  // ---- multiplier: p = ma * mb, registered --------------------------------
  reg  [31:0] v_r, u_r, xp_r;
  reg  [15:0] wh, vh, xs;
  reg  [30:0] sq;                    // sq = wh^2 + rnd(wh wl >> 14) (< 2^30 in the domain)
  reg  [15:0] ma, mb;
  reg  signed [31:0] p;
  reg  signed [34:0] vacc;           // v' = v + c2w2 + C - U22 + J
  reg  signed [46:0] uacc;           // U + c3v - c4U
  always @* begin
    case (step)
      4'd1: begin ma = wh; mb = {1'b0, v_r[14:0]}; end
      4'd2: begin ma = k_m3; mb = vh; end
      4'd3: begin ma = wh; mb = wh; end
      4'd4: begin ma = k_gain; mb = xs; end
      4'd5: begin ma = k_m2; mb = sq[30:15]; end
      4'd6: begin ma = k_m2; mb = {1'b0, sq[14:0]}; end
      4'd7: begin ma = k_m4; mb = u_r[30:15]; end
      default: begin ma = k_m4; mb = {1'b0, u_r[14:0]}; end
    endcase
  end
  always @(posedge clk) p <= $signed(ma) * $signed(mb);

  // ---- round-shift unit: r = rnd(y >> sn), registered ----------------------
  reg  signed [46:0] y, r;
  reg  [5:0] sn;
  always @* begin
    case (step)
      4'd1: sn = k_xsh;
      4'd2: sn = k_fu;
      4'd4: sn = k_s3;
      4'd6: sn = k_nj;
      4'd8: sn = k_s2;
      default: sn = k_s4;
    endcase
  end
  wire signed [47:0] sh = $signed({y, 1'b0}) >>> sn;
  always @(posedge clk) r <= sh[47:1] + {46'd0, sh[0]};

  // ---- helpers ---------------------------------------------------------------
  wire signed [46:0] p47 = {{15{p[31]}}, p};
  wire signed [46:0] p15 = {p, 15'd0};              // p 2^15 (|p| <= 2^30: no loss)
  wire signed [32:0] dx = $signed({y[31], y[31:0]}) - $signed({xp_r[31], xp_r});
  wire [31:0] drive = dx[32] ? 32'd0 : (dx[31] ? 32'h7fffffff : dx[31:0]);
  wire [15:0] xs_sat = (r[46:15] == {32{r[46]}}) ? r[15:0] : {r[46], {15{!r[46]}}};
  wire [31:0] j_sat = (r[46:31] == {16{r[46]}}) ? r[31:0] : {r[46], {31{!r[46]}}};
  wire [17:0] t14 = p[31:14] + {17'd0, p[13]};     // rnd(wh wl >> 14), |wh wl| < 2^30
  wire signed [34:0] sum_add = $signed({{3{r[31]}}, r[31:0]});
  wire signed [34:0] j_add = $signed({{3{j_sat[31]}}, j_sat});
  wire [31:0] u_sat = (uacc[46:30] == {17{uacc[46]}}) ? uacc[31:0]
                                                       : {{2{uacc[46]}}, {30{!uacc[46]}}};
  wire spike = vacc >= V_PEAK;

  always @(posedge clk) begin
    if (rst) begin
      busy <= 1'b0; step <= 4'd0;
      out_valid <= 1'b1; out_spike <= 1'b0;
      out_v <= 32'd0; out_u <= 32'd0; out_x_prev <= 32'd0;
    end else if (go) begin
      busy <= 1'b1; step <= 4'd0; out_valid <= 1'b0;
      v_r <= in_v; u_r <= in_u; xp_r <= in_x_prev;
      y <= {{15{in_x[31]}}, in_x};
      vacc <= {{3{c_const[31]}}, c_const};
      out_v <= c_vreset;                           // the spike's v
      out_u <= c_ujump;                            // kd, added on a spike
      out_x_prev <= c_ic ? in_x : in_x_prev;
    end else if (busy) begin
      step <= step + 4'd1;
      case (step)
        4'd0: begin
          if (k_ic) y <= {15'd0, drive};
          wh <= v_r[30:15] + W_OFF_H;
          vh <= v_r[29:14] + {15'd0, v_r[13]};
        end
        4'd1: y <= {{15{u_r[31]}}, u_r};
        4'd2: begin xs <= xs_sat; sq <= {{13{t14[17]}}, t14}; end
        4'd3: begin y <= p47; vacc <= vacc - sum_add; end
        4'd4: begin sq <= sq + p[30:0]; vacc <= vacc + $signed({{3{v_r[31]}}, v_r}); end
        4'd5: begin y <= p15; uacc <= $signed({{15{u_r[31]}}, u_r}) + r; end
        4'd6: y <= p15;
        4'd7: begin y <= y + p47; vacc <= vacc + j_add; end
        4'd8: y <= p15;
        4'd9: begin y <= y + p47; vacc <= vacc + sum_add; end
        4'd11: uacc <= uacc - r;
        4'd12: uacc <= $signed({{15{u_sat[31]}}, u_sat})
                       + (spike ? $signed({{15{out_u[31]}}, out_u}) : 47'sd0);
        4'd13: begin
          busy <= 1'b0; out_valid <= 1'b1; out_spike <= spike;
          out_u <= u_sat;
          if (!spike) out_v <= vacc < V_MIN ? V_MIN[31:0] : vacc[31:0];
        end
        default: ;
      endcase
    end
  end
endmodule
`default_nettype wire
