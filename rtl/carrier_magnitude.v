// carrier_magnitude: complex window sum {k, re, im} -> {k, mag}.
// Bit-exact implementation of hls/carrier_magnitude.h (formats, rounding and
// saturation are stated there):
//   mag = min(floor(sqrt(re^2 + im^2) / 2^SHIFT + 1/2), 2^MAG_W - 1).
//
// Datapath, one token at a time (iterative, one unsigned HxH multiplier,
// H = ceil(ACC_W/2) <= 16, so one SB_MAC16 with `synth_ice40 -dsp`):
//   IDLE  in_ready = 1; the handshake latches k, last, re, im.
//   MUL   6 cycles: P += lo*lo, 2*hi*lo << H, hi*hi << 2H for |re| then |im|.
//   PREP  1 cycle : Q = (4 P) >> 2 SHIFT, overflow flag if Q >= 4^NB.
//   SQRT  NB = MAG_W+1 cycles of the restoring square root (1 bit/cycle).
//   OUT   out_valid = 1 until out_ready; then back to IDLE.
// Timing without back-pressure: out_valid rises NB + 8 cycles after the
// input handshake cycle (latency 25 for MAG_W = 16); the next input is
// accepted NB + 9 cycles after the previous one (II = 26). K = 6 carriers at
// 35 kHz need <= 57 cycles per token at 12 MHz.
// Area (Yosys 0.23 synth_ice40 -dsp, defaults): 314 SB_LUT4, 199 flip-flops,
// 122 SB_CARRY, 1 SB_MAC16.
module carrier_magnitude #(
    parameter integer ACC_W = 24,
    parameter integer MAG_W = 16,
    parameter integer SHIFT = ACC_W - MAG_W,
    parameter integer K_W = 8
) (
    input  wire             clk,
    input  wire             rst,        // synchronous, active high
    input  wire             in_valid,
    output wire             in_ready,
    input  wire [K_W-1:0]   in_k,
    input  wire [ACC_W-1:0] in_re,      // signed
    input  wire [ACC_W-1:0] in_im,      // signed
    input  wire             in_last,
    output wire             out_valid,
    input  wire             out_ready,
    output reg  [K_W-1:0]   out_k,
    output reg  [MAG_W-1:0] out_mag,    // unsigned
    output reg              out_last
);
  localparam integer H = (ACC_W + 1) / 2;  // half width of |re|, |im|
  localparam integer AW = 2 * H;           // |re| register width (>= ACC_W)
  localparam integer PW = 2 * AW;          // P = re^2 + im^2
  localparam integer NB = MAG_W + 1;       // square-root result bits
  localparam integer QX = (PW + 2 > 2 * NB + 1) ? PW + 2 : 2 * NB + 1;
  localparam integer RW = NB + 2;          // remainder width

  localparam [2:0] S_IDLE = 3'd0, S_MUL = 3'd1, S_PREP = 3'd2, S_SQRT = 3'd3,
                   S_OUT = 3'd4;
  reg [2:0] state;
  reg [4:0] cnt;

  // The inputs are latched signed; |x| is taken of the operand in use (one
  // negator shared by re and im), as an unsigned AW-bit value.
  reg [ACC_W-1:0] re_q, im_q;
  reg [PW-1:0] p;
  wire [ACC_W-1:0] src_s = (cnt < 5'd3) ? re_q : im_q;
  wire [AW:0] src_sx = {{(AW + 1 - ACC_W){src_s[ACC_W-1]}}, src_s};
  wire [AW-1:0] src_neg = -src_sx[AW-1:0];  // 2^(ACC_W-1) still fits AW bits

  // Partial products: step 0..2 on |re|, 3..5 on |im|.
  wire [AW-1:0] src = src_sx[AW] ? src_neg : src_sx[AW-1:0];
  wire [1:0] part = (cnt < 5'd3) ? cnt[1:0] : cnt[1:0] - 2'd3;
  wire [H-1:0] lo = src[H-1:0];
  wire [H-1:0] hi = src[AW-1:H];
  wire [H-1:0] mul_a = (part == 2'd2) ? hi : lo;
  wire [H-1:0] mul_b = (part == 2'd0) ? lo : hi;
  wire [AW-1:0] prod = mul_a * mul_b;
  wire [PW-1:0] prod_x = {{(PW - AW){1'b0}}, prod};
  wire [PW-1:0] addend = (part == 2'd0) ? prod_x :
                         (part == 2'd1) ? (prod_x << (H + 1)) : (prod_x << AW);

  // Q = floor(4 P / 4^SHIFT) and its overflow of the NB-bit root range.
  wire [QX-1:0] p4 = {{(QX - PW){1'b0}}, p} << 2;
  wire [QX-1:0] qfull = p4 >> (2 * SHIFT);
  wire q_ovf = |qfull[QX-1:2*NB];

  reg [2*NB-1:0] qsh;   // Q, consumed two bits per step from the top
  reg [NB-1:0] rem;     // < 2^NB before every step (rem <= 2 root)
  reg [NB-1:0] root;
  reg ovf;

  wire [RW-1:0] rem_sh = {rem, qsh[2*NB-1:2*NB-2]};
  wire [RW-1:0] trial = {root, 2'b01};
  wire take = rem_sh >= trial;

  // Root after this step, and the rounded magnitude (root + 1) >> 1.
  wire [NB-1:0] root_next = {root[NB-2:0], take};
  // Bit 0 of root + 1 is dropped by the >> 1, and the top remainder bits
  // are only nonzero after the final step, whose remainder is not needed.
  /* verilator lint_off UNUSEDSIGNAL */
  wire [NB:0] root_inc = {1'b0, root_next} + {{NB{1'b0}}, 1'b1};
  wire [RW-1:0] rem_next = take ? rem_sh - trial : rem_sh;
  /* verilator lint_on UNUSEDSIGNAL */
  wire [MAG_W:0] mag_next = root_inc[NB:1];
  localparam integer LAST_STEP = NB - 1;

  assign in_ready = (state == S_IDLE);
  assign out_valid = (state == S_OUT);

  always @(posedge clk) begin
    if (rst) begin
      state <= S_IDLE;
      cnt <= 5'd0;
    end else begin
      case (state)
        S_IDLE:
          if (in_valid) begin
            out_k <= in_k;
            out_last <= in_last;
            re_q <= in_re;
            im_q <= in_im;
            p <= {PW{1'b0}};
            cnt <= 5'd0;
            state <= S_MUL;
          end
        S_MUL: begin
          p <= p + addend;
          cnt <= cnt + 5'd1;
          if (cnt == 5'd5) state <= S_PREP;
        end
        S_PREP: begin
          qsh <= qfull[2*NB-1:0];
          ovf <= q_ovf;
          rem <= {NB{1'b0}};
          root <= {NB{1'b0}};
          cnt <= 5'd0;
          state <= S_SQRT;
        end
        S_SQRT: begin
          qsh <= qsh << 2;
          rem <= rem_next[NB-1:0];
          root <= root_next;
          cnt <= cnt + 5'd1;
          if (cnt == LAST_STEP[4:0]) begin
            out_mag <= (ovf | mag_next[MAG_W]) ? {MAG_W{1'b1}} : mag_next[MAG_W-1:0];
            state <= S_OUT;
          end
        end
        S_OUT:
          if (out_ready) state <= S_IDLE;
        default: state <= S_IDLE;
      endcase
    end
  end

endmodule
