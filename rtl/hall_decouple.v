`default_nettype none
// hall_decouple: seed-001 decoupling parameters Rx, Ry, Sz of one sensor.
// Bit-exact implementation of hls/hall_decouple.h (formulas, formats,
// rounding and guards are stated there): no division anywhere; atan2 and
// magnitudes by CORDIC vectoring, logarithms by repeated squaring.
//
// Input: hall_baseline tokens; only sensor ID is used (others are ignored).
// GAIN_X/Y/Z (UQ16.16 uT/LSB, < 2^20) are the scene's setting; the
// compensation k1, c1, k2, c2 (Q2.14, 1/64 uT) come from the calibration
// (cfg_* ports, held by the command decoder).
// One signed 33 x 33 multiplier is shared by every product, one operation
// per cycle:
//   MUL  9 products: B_x, B_y, B_z, z1, z2, Bx^2, By^2, z1^2, z2^2
//   GUARD 1 cycle: z1, z2, den_x, den_y > 0, else an invalid token
//   RX   1 product (2 Bx z1), s1 prescale halvings, 24 CORDIC steps
//   RY   1 product (2 By z1), s2 halvings, 24 steps
//   SZ   1 product (2 By z2), 1 cycle for |N|, s3 halvings, 24 steps, then
//        two logarithms of 1 + 6 + 1 + 24 + 1 cycles each (normalise in six
//        fixed shift steps, 24 squarings) and the sum
// Latency (input handshake to out_valid, no back-pressure): 158 + s1 + s2
// + s3 cycles for a valid token (s: hls::cordic_prescale of each vector),
// 11 for a guarded one. (N and 2 By z2 cannot both be 0 after the guards,
// z2 > 0; the check stays as the kernel's own guard.)
// in_ready is high only while idle.
module hall_decouple #(
    parameter integer ID = 0,
    parameter [31:0] GAIN_X = 32'd9830,   // 0.150 uT/LSB (GAIN_SEL 7, RES 0)
    parameter [31:0] GAIN_Y = 32'd9830,
    parameter [31:0] GAIN_Z = 32'd15860   // 0.242 uT/LSB
) (
    input  wire        clk,
    input  wire        rst,
    input  wire        in_valid,
    output wire        in_ready,
    input  wire [7:0]  in_id,
    input  wire [31:0] in_t,
    input  wire [15:0] in_dx,
    input  wire [15:0] in_dy,
    input  wire [15:0] in_dz,
    input  wire [7:0]  in_flags,
    input  wire [15:0] cfg_k1,   // Q2.14 signed
    input  wire [31:0] cfg_c1,   // 1/64 uT signed
    input  wire [15:0] cfg_k2,
    input  wire [31:0] cfg_c2,
    output reg         out_valid,
    input  wire        out_ready,
    output reg  [31:0] out_t,
    output reg  [31:0] out_rx,   // Q8.24 signed
    output reg  [31:0] out_ry,
    output reg  [31:0] out_sz,
    output reg         out_ok,   // the parameters are valid
    output reg  [7:0]  out_flags
);
  generate
    if (ID < 0 || ID > 255) begin : g_bad_id
      illegal_parameter_ID_must_be_0_to_255 u_bad();
    end
    if (GAIN_X >= 32'h0010_0000 || GAIN_Y >= 32'h0010_0000 || GAIN_Z >= 32'h0010_0000) begin : g_bad_gain
      illegal_parameter_GAIN_must_be_below_16_uT_per_LSB u_bad();
    end
  endgenerate

  localparam signed [63:0] LN2_Q30 = 64'sd744261118;
  localparam signed [31:0] LNK_Q24 = 32'sd8368641;
  localparam signed [31:0] LN64_Q24 = 32'sd69774480;

  localparam [3:0] S_IDLE = 4'd0, S_MUL = 4'd1, S_GUARD = 4'd2, S_VEC = 4'd3, S_PRE = 4'd4,
                   S_ROT = 4'd5, S_POST = 4'd6, S_LNSTART = 4'd7, S_LNSQ = 4'd8, S_LNEND = 4'd9,
                   S_OUT = 4'd10, S_LNNORM = 4'd11, S_LNSET = 4'd12;
  reg [3:0] state;
  reg [4:0] step;       // product index in S_MUL, CORDIC step in S_ROT, squaring in S_LNSQ
  reg [1:0] which;      // CORDIC / logarithm in progress: 0 Rx, 1 Ry, 2 Sz (ln 0: |v|, 1: 2 z2)
  reg [5:0] sh;         // prescale halvings

  reg signed [15:0] d0, d1, d2;
  // |B| < 2^25 and |z| < 2^27 (the bounds of hls/hall_decouple.h), so the
  // multiplier's 33-bit operands hold them; squares and sums use 64 bits.
  reg signed [32:0] b0, b1, b2;
  reg signed [63:0] z1, z2, bx2, by2, z1sq, z2sq;
  reg signed [63:0] cx, cy;
  reg signed [31:0] cz;
  reg signed [31:0] ln_a;           // first logarithm (of |v|)
  reg [31:0] m;                     // Q1.30 mantissa
  reg [23:0] frac;
  reg [5:0] e;
  reg [63:0] v;                     // the logarithm's argument, normalised left
  reg [6:0] lz;                     // its leading zeros
  reg [5:0] sh_sz;                  // the Sz vector's prescale: ln(x << s) = ln x + s ln 2

  // ---- the shared multiplier ----
  reg signed [32:0] ma, mb;
  wire signed [65:0] mp = ma * mb;
  // Round half up by s bits (the products stay below 2^63: no bits lost).
  /* verilator lint_off UNUSEDSIGNAL */
  function signed [63:0] rnd(input signed [65:0] x, input integer s);
    reg signed [65:0] r;
    begin
      r = (x + (66'sd1 <<< (s - 1))) >>> s;
      rnd = r[63:0];
    end
  endfunction
  /* verilator lint_on UNUSEDSIGNAL */

  // Operands of S_MUL's products, by step.
  always @* begin
    ma = 33'sd0;
    mb = 33'sd0;
    case (state)
      S_MUL: case (step)
        5'd0: begin ma = 33'(d0); mb = $signed({1'b0, GAIN_X}); end
        5'd1: begin ma = 33'(d1); mb = $signed({1'b0, GAIN_Y}); end
        5'd2: begin ma = 33'(d2); mb = $signed({1'b0, GAIN_Z}); end
        5'd3: begin ma = b2; mb = 33'($signed(cfg_k1)); end
        5'd4: begin ma = b2; mb = 33'($signed(cfg_k2)); end
        5'd5: begin ma = b0; mb = b0; end
        5'd6: begin ma = b1; mb = b1; end
        5'd7: begin ma = z1[32:0]; mb = z1[32:0]; end
        default: begin ma = z2[32:0]; mb = z2[32:0]; end
      endcase
      S_VEC: case (which)
        2'd0: begin ma = b0; mb = z1[32:0]; end
        2'd1: begin ma = b1; mb = z1[32:0]; end
        default: begin ma = b1; mb = z2[32:0]; end
      endcase
      S_LNSQ: begin ma = $signed({1'b0, m}); mb = $signed({1'b0, m}); end
      S_LNEND: begin ma = $signed({3'b000, e, frac}); mb = LN2_Q30[32:0]; end
      default: ;
    endcase
  end

  // ---- CORDIC ----
  function signed [31:0] atan_q24(input [4:0] i);
    case (i)
      5'd0: atan_q24 = 32'sd13176795; 5'd1: atan_q24 = 32'sd7778716; 5'd2: atan_q24 = 32'sd4110060;
      5'd3: atan_q24 = 32'sd2086331;  5'd4: atan_q24 = 32'sd1047214; 5'd5: atan_q24 = 32'sd524117;
      5'd6: atan_q24 = 32'sd262123;   5'd7: atan_q24 = 32'sd131069;
      default: atan_q24 = 32'sd1 <<< (5'd24 - i);  // round(atan(2^-i) 2^24) = 2^(24-i) for i >= 8
    endcase
  endfunction
  // After the prescale |x|, |y| < 2^30 and the rotations keep them below
  // 2^32 (gain K < 1.65, |(x, y)| < 2^30.5): 34-bit shifters suffice.
  /* verilator lint_off UNUSEDSIGNAL */
  wire signed [33:0] xs = $signed(cx[33:0]) >>> step;
  wire signed [33:0] ys = $signed(cy[33:0]) >>> step;
  /* verilator lint_on UNUSEDSIGNAL */
  wire pre_more = (cx >= 64'sd1073741824) || (cy >= 64'sd1073741824) || (cy <= -64'sd1073741824);

  // ---- logarithm ----
  // Normalising left in six fixed steps (32, 16, ... 1 bits): with the top
  // bit at 63, the Q1.30 mantissa is v >> 33 and the exponent 63 - lz; the
  // Sz magnitude is used before its prescale is undone, which adds s to e.
  wire [63:0] ln_arg = (which == 2'd0) ? cx : (z2 <<< 1);
  wire [5:0] nstep = 6'd32 >> step;
  wire [63:0] v_top = v >> (7'd64 - {1'b0, nstep});  // the nstep top bits
  // e <= 62 (the kernel's argument stays below 2^63): bit 6 is never set.
  /* verilator lint_off UNUSEDSIGNAL */
  wire [6:0] e_sum = 7'd63 - lz + ((which == 2'd0) ? {1'b0, sh_sz} : 7'd0);
  /* verilator lint_on UNUSEDSIGNAL */
  // The normalised mantissa is below 2^31, its square >> 30 below 2^32, the
  // logarithm below 2^31 in Q8.24: the top bits of these are zero/sign.
  /* verilator lint_off UNUSEDSIGNAL */
  wire [63:0] sq = mp[63:0] >> 30;  // (m * m) >> 30 in Q2.30
  wire signed [63:0] mp_r30 = rnd(mp, 30);  // (e.frac) * ln 2, Q8.24
  wire signed [63:0] mp_r10 = rnd(mp, 10);
  /* verilator lint_on UNUSEDSIGNAL */

  wire signed [63:0] den_x = z1sq + by2 - bx2;
  wire signed [63:0] den_y = z1sq + bx2 - by2;
  wire signed [63:0] n_sz = z2sq - by2 + bx2;
  wire signed [63:0] n_abs = n_sz[63] ? -n_sz : n_sz;

  assign in_ready = (state == S_IDLE);

  always @(posedge clk) begin
    if (rst) begin
      state <= S_IDLE;
      out_valid <= 1'b0;
      step <= 5'd0;
      which <= 2'd0;
      sh <= 6'd0;
      {d0, d1, d2} <= 48'd0;
      {b0, b1, b2} <= 99'd0;
      {z1, z2} <= 128'd0;
      {bx2, by2, z1sq, z2sq} <= 256'd0;
      {cx, cy} <= 128'd0;
      cz <= 32'sd0;
      ln_a <= 32'sd0;
      m <= 32'd0;
      frac <= 24'd0;
      e <= 6'd0;
      v <= 64'd0;
      lz <= 7'd0;
      sh_sz <= 6'd0;
      out_t <= 32'd0;
      {out_rx, out_ry, out_sz} <= 96'd0;
      out_ok <= 1'b0;
      out_flags <= 8'd0;
    end else begin
      case (state)
        S_IDLE: if (in_valid && in_id == 8'(ID)) begin
          d0 <= in_dx; d1 <= in_dy; d2 <= in_dz;
          out_t <= in_t;
          out_flags <= in_flags;
          {out_rx, out_ry, out_sz} <= 96'd0;
          out_ok <= 1'b0;
          step <= 5'd0;
          state <= S_MUL;
        end
        S_MUL: begin
          case (step)
            5'd0: b0 <= mp_r10[32:0];
            5'd1: b1 <= mp_r10[32:0];
            5'd2: b2 <= mp_r10[32:0];
            5'd3: z1 <= rnd(mp, 14) + 64'($signed(cfg_c1));
            5'd4: z2 <= rnd(mp, 14) + 64'($signed(cfg_c2));
            5'd5: bx2 <= mp[63:0];
            5'd6: by2 <= mp[63:0];
            5'd7: z1sq <= mp[63:0];
            default: z2sq <= mp[63:0];
          endcase
          step <= step + 1'b1;
          if (step == 5'd8) state <= S_GUARD;
        end
        S_GUARD: begin
          if (z1 <= 0 || z2 <= 0 || den_x <= 0 || den_y <= 0) begin
            out_valid <= 1'b1;
            state <= S_OUT;
          end else begin
            which <= 2'd0;
            state <= S_VEC;
          end
        end
        S_VEC: begin
          // Load the vector of this CORDIC: (den, 2 B z1) or (|N|, 2 By z2).
          cy <= {mp[62:0], 1'b0};
          cz <= 32'sd0;
          sh <= 6'd0;
          if (which == 2'd0) cx <= den_x;
          else if (which == 2'd1) cx <= den_y;
          else cx <= (n_abs == 0) ? 64'sd1 : n_abs;
          if (which == 2'd2 && n_abs == 0 && mp == 0) begin
            out_valid <= 1'b1;  // a zero vector has no logarithm: invalid
            state <= S_OUT;
          end else begin
            state <= S_PRE;
          end
        end
        S_PRE: if (pre_more) begin
          cx <= cx >>> 1;
          cy <= cy >>> 1;
          sh <= sh + 1'b1;
        end else begin
          step <= 5'd0;
          state <= S_ROT;
        end
        S_ROT: begin
          if (!cy[63]) begin
            cx <= cx + 64'(ys); cy <= cy - 64'(xs); cz <= cz + atan_q24(step);
          end else begin
            cx <= cx - 64'(ys); cy <= cy + 64'(xs); cz <= cz - atan_q24(step);
          end
          step <= step + 1'b1;
          if (step == 5'd23) state <= S_POST;
        end
        S_POST: begin
          sh_sz <= sh;  // kept for the Sz logarithm (Rx, Ry need only the angle)
          case (which)
            2'd0: begin out_rx <= cz; which <= 2'd1; state <= S_VEC; end
            2'd1: begin out_ry <= cz; which <= 2'd2; state <= S_VEC; end
            default: begin which <= 2'd0; state <= S_LNSTART; end  // ln |v| first
          endcase
        end
        S_LNSTART: begin
          v <= ln_arg;
          lz <= 7'd0;
          step <= 5'd0;
          state <= S_LNNORM;
        end
        S_LNNORM: begin
          if (v_top == 64'd0) begin
            v <= v << nstep;
            lz <= lz + {1'b0, nstep};
          end
          step <= step + 1'b1;
          if (step == 5'd5) state <= S_LNSET;
        end
        S_LNSET: begin
          e <= e_sum[5:0];
          m <= {1'b0, v[63:33]};
          frac <= 24'd0;
          step <= 5'd0;
          state <= S_LNSQ;
        end
        S_LNSQ: begin
          frac <= {frac[22:0], sq[31]};
          m <= sq[31] ? sq[32:1] : sq[31:0];
          step <= step + 1'b1;
          if (step == 5'd23) state <= S_LNEND;
        end
        S_LNEND: begin
          if (which == 2'd0) begin
            ln_a <= mp_r30[31:0];
            which <= 2'd1;
            state <= S_LNSTART;
          end else begin
            out_sz <= ln_a - LNK_Q24 - mp_r30[31:0] - LN64_Q24;
            out_ok <= 1'b1;
            out_valid <= 1'b1;
            state <= S_OUT;
          end
        end
        default: if (out_ready) begin  // S_OUT
          out_valid <= 1'b0;
          state <= S_IDLE;
        end
      endcase
    end
  end
endmodule
`default_nettype wire
