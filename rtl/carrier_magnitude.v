`default_nettype none
// carrier_magnitude: the streaming block of hls/carrier_magnitude.h, one
// carrier a clock. Bit-exact with CarrierMagnitude<ACC_W, MAG_W, SHIFT>::push
// (number formats, rounding and saturation are stated there):
//   mag = min(floor(sqrt(re^2 + im^2) / 2^SHIFT + 1/2), 2^MAG_W - 1)
// by the kernel's method: P = re^2 + im^2, Q = floor(4 P / 4^SHIFT),
// root = floor(sqrt(Q)) on NB = MAG_W + 1 bits (saturate when Q >= 4^NB),
// mag = (root + 1) >> 1. k and last pass through unchanged.
//
// Pipeline (every register moves together; a clock with `en` low holds
// them all):
//   1       in_re, in_im, in_k, in_last registered
//   2       re^2 and im^2 (signed multiplies: the DSPs, MULT18X18D on the
//           ECP5, SB_MAC16 on the iCE40) registered
//   3       P = re^2 + im^2 registered
//   4..NB+3 isqrt_pipe, one root bit a stage, fed Q and the saturation flag
//   NB+4    mag = (root + 1) >> 1, saturated, into out_mag
// Latency: out_valid of a carrier taken at a clock's edge rises NB + 4 =
// MAG_W + 5 clocks later (21 at the defaults) when nothing stalls;
// throughput one carrier a clock.
// Handshake: en = !out_valid || out_ready (the output register is free or
// is being emptied) moves the whole pipeline; in_ready = en. So in_ready
// depends on out_ready through one gate and the same clock; a bubble inside
// the pipeline is not squeezed out while the output is stalled.
module carrier_magnitude #(
    parameter integer ACC_W = 24,
    parameter integer MAG_W = 16,
    parameter integer SHIFT = ACC_W - MAG_W
) (
    input  wire              clk,
    input  wire              rst,
    input  wire              in_valid,
    output wire              in_ready,
    input  wire [7:0]        in_k,
    input  wire [ACC_W-1:0]  in_re,    // signed
    input  wire [ACC_W-1:0]  in_im,    // signed
    input  wire              in_last,
    output reg               out_valid,
    input  wire              out_ready,
    output reg  [7:0]        out_k,
    output reg  [MAG_W-1:0]  out_mag,
    output reg               out_last
);
  // The kernel's static_asserts.
  generate
    if (ACC_W < 2 || ACC_W > 32 || MAG_W < 1 || MAG_W > 30 || SHIFT < 0 || SHIFT > ACC_W) begin : g_bad
      carrier_magnitude_illegal_parameters u_stop ();  // no such module: stops elaboration
    end
  endgenerate

  localparam integer NB = MAG_W + 1;              // root bits
  localparam integer PW = 2 * ACC_W;              // P < 2^(2 ACC_W - 1) + 1
  localparam integer QW = PW + 2 - 2 * SHIFT;     // floor(4 P / 4^SHIFT)

  wire en = !out_valid || out_ready;
  assign in_ready = en;

  // 1: inputs.
  reg signed [ACC_W-1:0] a_re, a_im;
  reg [7:0] a_k;
  reg a_last, a_v;
  // 2: squares.
  reg signed [PW-1:0] b_re2, b_im2;
  reg [7:0] b_k;
  reg b_last, b_v;
  // 3: P.
  reg [PW-1:0] c_p;
  reg [7:0] c_k;
  reg c_last, c_v;
  always @(posedge clk) begin
    if (en) begin
      a_re <= in_re;
      a_im <= in_im;
      a_k <= in_k;
      a_last <= in_last;
      b_re2 <= a_re * a_re;
      b_im2 <= a_im * a_im;
      b_k <= a_k;
      b_last <= a_last;
      // Both squares are >= 0 and their sum <= 2^(PW-1): no wrap in PW bits.
      c_p <= $unsigned(b_re2) + $unsigned(b_im2);
      c_k <= b_k;
      c_last <= b_last;
    end
    if (rst) begin
      a_v <= 1'b0;
      b_v <= 1'b0;
      c_v <= 1'b0;
    end else if (en) begin
      a_v <= in_valid;
      b_v <= a_v;
      c_v <= b_v;
    end
  end

  // Q = (P << 2) >> (2 SHIFT); saturate when Q >= 4^NB (the kernel's two
  // cases, SHIFT = 0 and not, are both this one test).
  wire [PW+1:0] p4 = {c_p, 2'b00};
  wire [QW-1:0] q = p4[PW+1 -: QW];
  wire [2*NB-1:0] rad;
  wire sat;
  generate
    if (QW > 2 * NB) begin : g_wide
      assign rad = q[2*NB-1:0];
      assign sat = |q[QW-1:2*NB];
    end else begin : g_narrow
      assign rad = {{(2*NB-QW){1'b0}}, q};
      assign sat = 1'b0;
    end
    // The bits below the shift are dropped (floor).
    if (2 * SHIFT > 0) begin : g_low
      /* verilator lint_off UNUSEDSIGNAL */
      wire [2*SHIFT-1:0] dropped = p4[2*SHIFT-1:0];
      /* verilator lint_on UNUSEDSIGNAL */
    end
  endgenerate

  // 4 .. NB+3: the root; side band {sat, last, k}.
  wire r_v;
  wire [NB-1:0] r_root;
  wire [9:0] r_side;
  /* verilator lint_off PINCONNECTEMPTY */
  isqrt_pipe #(.W(NB), .SW(10)) u_root (
      .clk(clk), .rst(rst), .en(en), .in_valid(c_v), .in_rad(rad),
      .in_side({sat, c_last, c_k}), .out_valid(r_v), .out_root(r_root), .out_side(r_side),
      .busy());
  /* verilator lint_on PINCONNECTEMPTY */

  // NB+4: round half up, saturate.
  wire [NB:0] up = {1'b0, r_root} + 1'b1;
  wire [NB-1:0] half = up[NB:1];
  localparam [MAG_W-1:0] MAG_MAX = {MAG_W{1'b1}};
  always @(posedge clk) begin
    if (en) begin
      out_k <= r_side[7:0];
      out_last <= r_side[8];
      out_mag <= (r_side[9] || half[NB-1]) ? MAG_MAX : half[MAG_W-1:0];
    end
    if (rst) out_valid <= 1'b0;
    else if (en) out_valid <= r_v;
  end
  /* verilator lint_off UNUSEDSIGNAL */
  wire unused_up0 = up[0];
  /* verilator lint_on UNUSEDSIGNAL */
endmodule
`default_nettype wire
