`default_nettype none
// sdft_bank: exact sliding DFT of up to K_MAX carriers over an N-sample
// window. Bit-exact implementation of hls/sdft_bank.h (number formats,
// rounding and the exactness argument are stated there; R rounds x*c to
// 2^-FB sample LSB, FB = 0 by default):
//   acc_k += R(x[n] * C(th)) - R(x[n-N] * C(th - N inc))      (re)
//   acc_k += R(x[n] * -S(th)) - R(x[n-N] * -S(th - N inc))    (im)
//
// Datapath: one signed (XW+1) x CW multiplier (one SB_MAC16 / MULT18X18D
// for XW < 16, CW <= 16) used four times per carrier, one quarter-sine ROM
// read per cycle, all state in block RAM: window buffer N x XW, phase and
// increment K x 32, sums K x ACC_W (re and im). The ROM is filled at
// elaboration by qsin(), the same integer function as sdft_quarter_sine()
// in the HLS header. Three register stages per term, so that no path runs
// from the ROM through the multiplier into the sums (on ECP5 that path was
// the whole DTMF top's critical one, ~22.4 ns: 5.6 ns block RAM clock-to-out,
// coefficient negation, 3.9 ns multiplier, rounding adder, sum adder):
//   issue: phase -> ROM address (ROM registered: rom_q, full_q, neg_q)
//   mul:   rom_q -> |c| (one LUT) x (+-x) -> prod_q; the coefficient's sign
//          is moved to the sample (x * -m = (-x) * m: -x_new, -x_old are
//          registered in OLD and C1), so the ROM reaches the multiplier
//          through a single LUT
//   acc:   sum +- R(prod_q), one adder for re and im, R's rounding bit as
//          its carry-in: R(p) = (p >>> SH) + p[SH-1]
//
// Schedule per sample (state: cycles):
//   IDLE  in_ready = 1 (configured, no cfg_valid); handshake latches x[n];
//         carrier 0 is read (k = 0 in IDLE)
//   OLD   1: x[n-N] <- window[wp]; window[wp] <- x[n]; -x[n]; issue
//         cos(th_0); th_old_0 = th_0 - N inc_0 (OLD plays the previous
//         carrier's C6 for carrier 0)
//   C1..C6 per carrier k, 6 cycles (issue / multiply / accumulate):
//     C1 issue -sin(th); mul x[n] C(th); latch th + inc and the sums; -x[n-N]
//     C2 issue cos(th_old); mul x[n] -S(th);        re += R(x[n] C)
//     C3 issue -sin(th_old); mul x[n-N] C(th_old);  im += R(x[n] -S)
//     C4                     mul x[n-N] -S(th_old); re -= R(x[n-N] C)
//     C5 read carrier k+1                          im -= R(x[n-N] -S)
//     C6 write back th + inc and the sums, load the output register (waits
//        here while a previous token is not taken); read carrier k+1, issue
//        its cos(th) and compute its th_old (repeated while waiting: the
//        reads and the issue are idempotent, nothing else is in flight)
// The pipelining overlaps carrier k+1's first lookup with carrier k's C6
// (and carrier 0's with OLD), so the cycle count is the unpipelined one.
// Timing without back-pressure: token k is valid 8 + 6 k cycles after the
// input handshake cycle (latency 8); the next sample is accepted 6 K + 2
// cycles after the previous one (II = 38 for K = 6, 194 for K = 32; at
// 12 MHz and 35 kHz there are 342 cycles per sample).
// Skipped samples (in_skip, taken with in_x): the window, phases and sums
// advance as for any sample, but no token comes out and C6 never waits for
// the output register, so such a sample takes 6 K + 2 cycles whatever the
// consumer does (a token of the previous sample still in the register is
// kept until taken). rtl/frame_capture.v keeps only the frames' samples,
// every STEP-th: dtmf_top skips the others, so that only those samples
// pay for the token stream (in rtl/sdft_lanes.v, the merger's K clocks).
//
// Resources, iCE40 (scripts/synth_ice40.sh sdft_bank [--param K_MAX=32
// --param N=128], Yosys 0.23 synth_ice40 -dsp): K_MAX 6, N 32: 420 LUT4,
// 229 FF, 1 SB_MAC16 (ice40_dsp folds the product register into it),
// 10 SB_RAM40_4K; K_MAX 32, N 128 (16x16 skin): 429 LUT4, 239 FF, 1 SB_MAC16,
// 10 SB_RAM40_4K (before in_skip: 418 / 228 and 428 / 238; with the CLEAR
// state before the lazy clear: 486 / 227 and 502 / 237; unpipelined: 490 /
// 231 and 504 / 241).
// ECP5-85F out of context (scripts/synth_ecp5.sh sdft_bank --pnr --freq 50,
// seed 1): 333 LUT4, 367 FF, 73 CCU2C, 36 DPR16X4, 1 MULT18X18D, 1 DP16KD,
// Fmax 72.5 MHz (unpipelined: 43.4 MHz); its critical path is now ROM
// clock-to-out (5.6 ns) -> |c| LUT -> multiplier (3.9 ns) -> prod_q, 13.8 ns.
// In the ULX3S DTMF top (`eskin bitstream --board ulx3s`) the top's Fmax
// went from 44.6 to 50.3 MHz, the critical path moving to frame_engine.
//
// Configuration: write the increments through cfg (valid/ready, accepted in
// IDLE), one carrier per token, cfg_k < K_MAX; the token with cfg_last sets
// K = cfg_k + 1 and clears the window, phases and sums, as
// SdftBank::configure() does. Until the first cfg_last no sample is
// accepted. The clear takes no clock (a sample may come in the next one):
// the memories are not written; instead, until every carrier has been
// updated once (`fresh`), phases and sums read as 0, and until N samples
// have entered (`nfill`), the sample leaving the window reads as 0. So the
// ADC loses nothing at a carrier reload even when a sample period is
// shorter than the window (at 1 MS/s and 40 MHz: 40 clocks, N = 128).
module sdft_bank #(
    parameter integer K_MAX = 6,
    parameter integer N = 32,
    parameter integer XW = 13,
    parameter integer CW = 16,
    parameter integer TW = 10,
    parameter integer ACC_W = 24,
    parameter integer FB = 0,      // term fraction bits (sums in 2^-FB LSB)
    parameter integer K_W = 8,
    // 1: the window RAM is here. 0: none; x[n-N] comes from win_ext, another
    // bank's win_rd, which must take every sample in the same clock as this
    // one and clear with it (rtl/sdft_lanes.v: its lanes share lane 0's).
    parameter integer OWN_WIN = 1
) (
    input  wire             clk,
    input  wire             rst,        // synchronous, active high
    input  wire             in_valid,
    output wire             in_ready,
    input  wire [XW-1:0]    in_x,       // signed sample (code - mid)
    input  wire             in_skip,    // with in_x: this sample's tokens are not wanted
    input  wire             cfg_valid,
    output wire             cfg_ready,
    /* verilator lint_off UNUSEDSIGNAL */
    input  wire [K_W-1:0]   cfg_k,      // low KB bits used (cfg_k < K_MAX)
    /* verilator lint_on UNUSEDSIGNAL */
    input  wire [31:0]      cfg_inc,    // phase increment, 2^32 = one cycle
    input  wire             cfg_last,
    output reg              out_valid,
    input  wire             out_ready,
    output reg  [K_W-1:0]   out_k,
    output reg  [ACC_W-1:0] out_re,     // signed window sum
    output reg  [ACC_W-1:0] out_im,     // signed window sum
    output reg              out_last,
    /* verilator lint_off UNUSEDSIGNAL */
    input  wire [XW-1:0]    win_ext,    // OWN_WIN = 0: the window's read register
    /* verilator lint_on UNUSEDSIGNAL */
    output wire [XW-1:0]    win_rd      // the window's read register (x[n-N] in OLD)
);
  // The width rules of hls/sdft_bank.h's static_asserts: no window sum can
  // overflow (N * 2^(XW-1+FB) < 2^(ACC_W-1)), k fits K_W bits.
  generate
    if (K_MAX < 1 || K_MAX > 256 || K_MAX > (1 << K_W) || N < 2 || N > 65536 || XW < 2 || XW > 24 ||
        CW < 3 || CW > 24 || TW < 3 || TW > 14 || ACC_W > 32 || FB < 0 || FB > CW - 2 ||
        ACC_W - XW - FB < 1 || N >= (1 << (ACC_W - XW - FB)) || OWN_WIN < 0 || OWN_WIN > 1)
    begin : g_bad_params
      sdft_bank_illegal_parameters u_stop ();  // no such module: stops elaboration
    end
  endgenerate

  localparam integer KB = (K_MAX > 1) ? $clog2(K_MAX) : 1;  // carrier address
  localparam integer KD = 1 << KB;                          // RAM depth
  localparam integer NB = (N > 1) ? $clog2(N) : 1;          // window address
  localparam integer QB = TW - 2;                           // ROM address
  localparam integer Q = 1 << QB;
  localparam integer PW = XW + CW;                          // product width
  localparam [CW-1:0] AMP = {1'b0, {(CW - 1){1'b1}}};       // A = 2^(CW-1)-1
  localparam [TW-1:0] QUARTER = {2'b01, {QB{1'b0}}};        // Q as TW bits
  // Plain Verilog (no SV casts): modules found by `hierarchy -libdir` are
  // read without -sv. Sized copies of the integer parameters:
  localparam integer N_M1 = N - 1;
  localparam [31:0] N32 = N;
  localparam [NB-1:0] WP_LAST = N_M1[NB-1:0];
  localparam [NB:0] N_FILL = N32[NB:0];
  localparam signed [63:0] Q64 = {32'd0, Q[31:0]};
  localparam integer SH = CW - 1 - FB;                      // term shift >= 1

  localparam [3:0] S_IDLE = 4'd1, S_OLD = 4'd2, S_C1 = 4'd3,
                   S_C2 = 4'd4, S_C3 = 4'd5, S_C4 = 4'd6, S_C5 = 4'd7, S_C6 = 4'd8;
  reg [3:0] state;
  reg configured;
  reg fresh;          // since the clear, not every carrier was updated yet
  reg [NB:0] nfill;   // samples since the clear, up to N
  reg [KB-1:0] k, klast;
  reg [NB-1:0] wp;
  reg skip;           // the sample being computed gives no tokens (in_skip)

  // Quarter-sine ROM value i: the integer Taylor series of
  // sdft_quarter_sine() (Q.30, eight terms, truncating division).
  function automatic [CW-2:0] qsin(input integer i);
    reg signed [63:0] x, x2, t, s, a, dv;
    integer n, d;
    begin
      x = {{32{i[31]}}, i};
      x = (64'sd1686629713 * x + Q64 / 64'sd2) / Q64;
      x2 = (x * x) >>> 30;
      t = x;
      s = x;
      for (n = 1; n <= 8; n = n + 1) begin
        d = (2 * n) * (2 * n + 1);
        dv = {{32{d[31]}}, d};  // a signed reg: keeps the division signed
        t = -(((t * x2) >>> 30) / dv);
        s = s + t;
      end
      a = (64'sd1 <<< (CW - 1)) - 64'sd1;
      s = (s * a + (64'sd1 <<< 29)) >>> 30;
      qsin = s[CW-2:0];
    end
  endfunction

  // v * N mod 2^32 as shifts and adds (no DSP for a constant; one shift
  // when N is a power of two).
  function automatic [31:0] times_n(input [31:0] v);
    integer b;
    begin
      times_n = 32'd0;
      for (b = 0; b < 32; b = b + 1)
        if (N32[b]) times_n = times_n + (v << b);
    end
  endfunction

  reg [CW-2:0] rom [0:Q-1];
  integer ri;
  initial begin
    for (ri = 0; ri < Q; ri = ri + 1) rom[ri] = qsin(ri);
  end

  // ---- memories (one write port, one registered read port each) ----
  // no_rw_check: no read result is used from a cycle that writes the same
  // address (window: OLD writes wp after x_old was latched; state: C6 writes
  // k while reading k + 1; config writes precede the reads in C1), so Yosys
  // needs no collision bypass logic.
  (* no_rw_check *) reg [31:0] inc_mem [0:KD-1];
  (* no_rw_check *) reg [31:0] ph_mem [0:KD-1];
  (* no_rw_check *) reg [ACC_W-1:0] re_mem [0:KD-1];
  (* no_rw_check *) reg [ACC_W-1:0] im_mem [0:KD-1];
  wire [XW-1:0] win_q;
  reg [31:0] inc_q, ph_q;
  reg [ACC_W-1:0] re_q, im_q;

  reg [XW-1:0] x_new, x_old;
  reg [XW:0] xn_new, xn_old;        // -x_new, -x_old (XW + 1 bits: -(-2^(XW-1)))
  reg [31:0] ph_r, pho_r;           // ph_r: th + inc (write-back), pho_r: th_old
  reg [ACC_W-1:0] re_r, im_r;

  wire in_fire = in_valid && in_ready;
  wire cfg_fire = cfg_valid && cfg_ready;
  wire out_free = !out_valid || out_ready;
  /* verilator lint_off UNUSEDSIGNAL */
  wire [K_W+KB-1:0] k_ext = {{K_W{1'b0}}, k};  // k zero-extended to K_W bits
  /* verilator lint_on UNUSEDSIGNAL */
  // C6 writes a carrier back and moves on when its token has a place in the
  // output register, or at once when the sample gives no tokens.
  wire c6_go = out_free || skip;
  wire advance = (state == S_C6) && c6_go;

  // Read address: carrier k + 1 from C5 on, so that its phase, increment and
  // sums are in the *_q registers in C6 (its first sine lookup is issued
  // there) and still in C1 (latched). k is 0 in IDLE and OLD: carrier 0 is
  // read there. C5 and C6 read k + 1 while C6 writes k (k + 1 != k: KD >= 2).
  wire [KB-1:0] ra = (state == S_C5 || state == S_C6) ? k + 1'b1 : k;
  // The window: written in OLD, read every clock (the read of IDLE is
  // x[n-N] in OLD). Banks that take every sample in the same clock and
  // clear together have the same window and the same wp, so one RAM serves
  // them all (OWN_WIN = 0 reads another's).
  generate
    if (OWN_WIN != 0) begin : g_win
      (* no_rw_check *) reg [XW-1:0] win [0:N-1];
      reg [XW-1:0] q;
      always @(posedge clk) begin
        if (state == S_OLD) win[wp] <= x_new;
        q <= win[wp];
      end
      assign win_q = q;
    end else begin : g_ext_win
      assign win_q = win_ext;
    end
  endgenerate
  assign win_rd = win_q;
  always @(posedge clk) begin
    if (cfg_fire) inc_mem[cfg_k[KB-1:0]] <= cfg_inc;
    inc_q <= inc_mem[ra];
  end
  // Phases and sums read as 0 while `fresh` (the clear): the read register
  // is reset instead of loaded.
  always @(posedge clk) begin
    if (advance) ph_mem[k] <= ph_r;
    ph_q <= fresh ? 32'd0 : ph_mem[ra];
  end
  always @(posedge clk) begin
    if (advance) re_mem[k] <= re_r;
    re_q <= fresh ? {ACC_W{1'b0}} : re_mem[ra];
  end
  always @(posedge clk) begin
    if (advance) im_mem[k] <= im_r;
    im_q <= fresh ? {ACC_W{1'b0}} : im_mem[ra];
  end

  // ---- sine lookup: issue (address) one cycle, ROM value the next ----
  // Issue slots of a carrier: cos(th) in the previous carrier's C6 (OLD for
  // carrier 0), -sin(th) in C1 (th from ph_q in both), cos(th_old) in C2,
  // -sin(th_old) in C3 (from pho_r).
  wire lk_sin = state == S_C1 || state == S_C3;
  /* verilator lint_off UNUSEDSIGNAL */
  wire [31:0] lk_ph = (state == S_C2 || state == S_C3) ? pho_r : ph_q;  // top TW+1 bits used
  wire [TW:0] lk_top = lk_ph[31:31-TW] + 1'b1;  // round half up to TW bits
  /* verilator lint_on UNUSEDSIGNAL */
  wire [TW-1:0] lk_idx = lk_sin ? lk_top[TW:1] : lk_top[TW:1] + QUARTER;
  wire [QB-1:0] lk_o = lk_idx[QB-1:0];
  wire lk_mirror = lk_idx[TW-2];                 // quadrants 1 and 3
  wire [QB-1:0] rom_a = lk_mirror ? -lk_o : lk_o;
  reg [CW-2:0] rom_q;
  reg full_q, neg_q;
  always @(posedge clk) begin
    rom_q <= rom[rom_a];
    full_q <= lk_mirror && lk_o == {QB{1'b0}};  // sin(pi/2) = A, not in ROM
    neg_q <= lk_idx[TW-1] ^ lk_sin;             // quadrants 2, 3; -sin
  end

  // th_old = th - N inc for the carrier whose cos(th) is issued now (C6 /
  // OLD: its phase and increment are in ph_q and inc_q); used from C2 on.
  always @(posedge clk)
    if (state == S_OLD || state == S_C6) pho_r <= ph_q - times_n(inc_q);

  // ---- the one multiplier, registered product (the cycle after the ROM) ----
  // The ROM output (a block RAM read, ~5.6 ns clock-to-out on ECP5) feeds the
  // multiplier through one LUT only: the coefficient's sign is applied to
  // the sample instead (x * -m = (-x) * m, the same integer product), from
  // -x registers precomputed in OLD and C1. The product is registered and
  // accumulated one cycle later, so ROM -> multiplier and product ->
  // accumulator are separate register-to-register paths. Multiplies: C1
  // x_new C(th), C2 x_new -S(th), C3 x_old C(th_old), C4 x_old -S(th_old).
  wire use_old = state == S_C3 || state == S_C4;
  wire [XW:0] x_pos = use_old ? {x_old[XW-1], x_old} : {x_new[XW-1], x_new};
  wire [XW:0] x_neg = use_old ? xn_old : xn_new;
  wire signed [XW:0] mul_x = neg_q ? x_neg : x_pos;
  wire signed [CW-1:0] mul_m = full_q ? AMP : {1'b0, rom_q};  // |coefficient|
  wire signed [PW-1:0] prod = mul_x * mul_m;  // |prod| < 2^(PW-2): no wrap
  /* verilator lint_off UNUSEDSIGNAL */
  reg [PW-1:0] prod_q;  // bits below SH-1 do not reach the term
  /* verilator lint_on UNUSEDSIGNAL */
  always @(posedge clk) prod_q <= prod;

  // ---- accumulate: one adder, acc +- R(p) with R(p) = (p >>> SH) + p[SH-1]
  // ((p + 2^(SH-1)) >> SH carries into bit SH exactly when p[SH-1] is set),
  // the rounding bit entering as the carry-in; subtraction adds ~(p >>> SH)
  // and the complement of the rounding bit: a - (h + r) = a + ~h + 1 - r.
  // C2 re += , C3 im += , C4 re -= , C5 im -= .
  wire acc_im = state == S_C3 || state == S_C5;
  wire acc_sub = state == S_C4 || state == S_C5;
  wire [ACC_W-1:0] t_hi = {{(ACC_W - PW + SH){prod_q[PW-1]}}, prod_q[PW-1:SH]};
  wire [ACC_W-1:0] acc_a = acc_im ? im_r : re_r;
  wire [ACC_W-1:0] acc_b = acc_sub ? ~t_hi : t_hi;
  wire acc_cin = prod_q[SH-1] ^ acc_sub;
  /* verilator lint_off UNUSEDSIGNAL */
  wire [ACC_W:0] acc_s = {acc_a, 1'b1} + {acc_b, acc_cin};  // bit 0: the carry-in
  /* verilator lint_on UNUSEDSIGNAL */
  wire [ACC_W-1:0] acc_sum = acc_s[ACC_W:1];

  // ---- control ----
  assign cfg_ready = state == S_IDLE;
  assign in_ready = state == S_IDLE && configured && !cfg_valid;

  always @(posedge clk) begin
    if (rst) begin
      state <= S_IDLE;
      fresh <= 1'b1;
      nfill <= {(NB + 1){1'b0}};
      configured <= 1'b0;
      klast <= {KB{1'b0}};
      k <= {KB{1'b0}};
      wp <= {NB{1'b0}};
    end else begin
      case (state)
        S_IDLE: begin
          if (cfg_fire && cfg_last) begin
            klast <= cfg_k[KB-1:0];
            configured <= 1'b1;
            wp <= {NB{1'b0}};
            fresh <= 1'b1;
            nfill <= {(NB + 1){1'b0}};
          end else if (in_fire) begin
            x_new <= in_x;
            skip <= in_skip;
            state <= S_OLD;
          end
        end
        S_OLD: begin
          x_old <= nfill == N_FILL ? win_q : {XW{1'b0}};  // x[n-N], 0 for n < N
          if (nfill != N_FILL) nfill <= nfill + 1'b1;
          xn_new <= -{x_new[XW-1], x_new};
          wp <= (wp == WP_LAST) ? {NB{1'b0}} : wp + 1'b1;
          state <= S_C1;
        end
        S_C1: begin
          ph_r <= ph_q + inc_q;  // the phase of the next sample, written in C6
          re_r <= re_q;
          im_r <= im_q;
          xn_old <= -{x_old[XW-1], x_old};
          state <= S_C2;
        end
        S_C2: begin
          re_r <= acc_sum;
          state <= S_C3;
        end
        S_C3: begin
          im_r <= acc_sum;
          state <= S_C4;
        end
        S_C4: begin
          re_r <= acc_sum;
          state <= S_C5;
        end
        S_C5: begin
          im_r <= acc_sum;
          state <= S_C6;
        end
        S_C6: begin
          if (c6_go) begin
            k <= (k == klast) ? {KB{1'b0}} : k + 1'b1;  // 0 in IDLE: read carrier 0
            state <= (k == klast) ? S_IDLE : S_C1;
            if (k == klast) fresh <= 1'b0;
          end
        end
        default: state <= S_IDLE;
      endcase
    end
  end

  always @(posedge clk) begin
    if (rst) begin
      out_valid <= 1'b0;
    end else if (advance && !skip) begin
      out_valid <= 1'b1;
      out_k <= k_ext[K_W-1:0];
      out_re <= re_r;
      out_im <= im_r;
      out_last <= k == klast;
    end else if (out_ready) begin
      out_valid <= 1'b0;
    end
  end
endmodule
`default_nettype wire
