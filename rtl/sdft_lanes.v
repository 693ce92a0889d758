`default_nettype none
// sdft_lanes: rtl/sdft_bank.v's sliding DFT with its channels spread over
// LANES sdft_bank instances that run in parallel, for sample rates at which
// one multiplier (6 clocks per channel) is too slow. Same ports, parameters
// and token contract as sdft_bank (bit-exact spec: hls/sdft_bank.h), plus
// LANES (1..64, at most K_MAX).
//
// LANES = 1 is sdft_bank itself (the instance's ports are this module's),
// so a 1-lane top is sdft_bank clock for clock, area for area.
//
// LANES >= 2: channel k lives in lane k mod LANES at local index
// k / LANES (interleaved: the lanes' j-th tokens, global k = j LANES + l,
// come out of every lane at the same clock, in the order the merger needs
// them). Lanes hold ceil(K_MAX / LANES) channels each; the N-sample
// window is lane 0's alone (sdft_bank OWN_WIN): every active lane takes
// each sample in the same clock and clears at the same cfg_last, so the
// other lanes read x[n-N] from lane 0's window read register (one RAM
// instead of LANES copies; lane 0 is active in every configuration).
//  - Samples: accepted when every active lane is ready (a lane is active
//    when it has a channel, l < K) and the previous sample's last token was
//    taken from out_* or is taken in this clock (out_ready reaches in_ready
//    combinationally); broadcast to the active lanes. Waiting for the last
//    token keeps sdft_bank's order for rtl/frame_capture.v: every token of
//    a sample has left by the next sample's handshake, the last one at the
//    latest in its clock (frame_capture stores and judges it there).
//  - Configuration (accepted when every lane is idle and no token is in
//    flight): a token without cfg_last goes to lane cfg_k mod LANES as
//    local cfg_k / LANES, and that lane remembers it (index and increment)
//    when its index is the highest the lane got since the last cfg_last.
//    The token with cfg_last (K = cfg_k + 1) goes to its lane, and in the
//    same clock every other lane with a channel gets its remembered token
//    again with cfg_last set (rewriting that increment changes nothing), so
//    every active lane learns its own K and clears its state, as
//    SdftBankConfig's configure() clears the whole bank. Contract: since
//    the previous cfg_last, every channel 0..K-1 was written (any order),
//    none above K-1. With K < LANES the lanes l >= K stay inactive: they
//    take no sample and no token, and do not hold the input back.
//  - Merger: one output register; it takes lane `sel`'s token when free,
//    sel runs 0..LANES-1 and restarts at 0 after the global last token;
//    out_k counts 0..K-1, out_last on K-1.
//
// Schedule (LANES >= 2). Handshake of a sample at clock t; each lane's
// local token j is valid at t + 8 + 6 j (sdft_bank) unless its output
// register is still full at its C6 (t + 7 + 6 j). The consumer takes a
// token whenever out_valid and then needs G clocks before the next (G = 1:
// out_ready always high, as rtl/frame_capture.v keeps it in dtmf_top;
// G = 2: a consumer that stores a token in two clocks).
// With R = ceil(K / LANES) rows, global token k is taken at
//   t + 9 + G k + max(0, 6 - G LANES) floor(k / LANES)
// (the merger holds each token one clock, then one every G clocks; when
// G LANES < 6 a row waits for the lanes' next row, 6 - G LANES idle
// clocks per row boundary; when G LANES >= 6 the lanes' next row is always
// ready before the merger gets to it, so the stream never pauses). The
// next sample is accepted in the clock the last token is taken, so
//   II = 9 + G (K - 1) + max(0, 6 - G LANES) (ceil(K / LANES) - 1).
// G = 1: II = 6 R + 3 + (K - 1) mod LANES while LANES <= 6 (K = 9, 2
// lanes: 33 clocks, against 56 for sdft_bank), K + 8 from 6 lanes on: the
// merger's one token a clock, so more than 6 lanes cannot make a sample
// with tokens faster (K = 24, a 12x12 skin: 32; K = 32, a 16x16 skin: 40,
// one sample a microsecond at 40 MHz); they do make skipped ones faster
// (below).
// G = 2: II = 2 K + 7 from 3 lanes on.
// Skipped samples (in_skip, taken with in_x): every active lane computes
// the sample but gives no token, and the merger has nothing to do; the
// next sample is accepted when the fullest lane is idle again:
//   II_skip = 6 ceil(K / LANES) + 2   (LANES = 1: sdft_bank's 6 K + 2).
// After a sample with tokens the next one still waits for its last token
// (II above). rtl/dtmf_top.v skips every sample but the frames' (one in
// STEP), so the merger's K + 8 is paid once a frame and the other samples
// go at the lanes' pace: more than 6 lanes do shorten those (K = 64, a
// 32x32 skin, in 11 lanes: 38 clocks; its frame samples take 72, which the
// ADC's one-sample hold absorbs, common/eskin/dtmf_top_plan.h's budget;
// K = 128, a 64x64 skin, in 32 lanes: 26 clocks, its frame samples 136,
// more than three sample periods at 40 MHz and 1 MS/s, which
// rtl/sdft_front.v's sample FIFO absorbs).
// hls/sdft_bank.h's sdft_lanes_interval() and sdft_skip_interval() are
// these formulas; the test (tests/rtl/sdft_lanes_test.cpp) asserts them
// clock for clock.
//
// Resources (K_MAX 9, N 32, XW 12, ACC_W 18; Yosys 0.70 synth_ecp5; measured
// before sdft_bank's pipelining, which moved its size by a few LUTs and FFs,
// and while every lane had its own window, here in DPR16X4):
//   1 lane:   301 LUT4,  97 CCU2C,  320 FF, 32 DPR16X4, 1 MULT18X18D, 1 DP16KD
//   2 lanes:  733 LUT4, 198 CCU2C,  764 FF, 64 DPR16X4, 2 MULT18X18D, 2 DP16KD
//   3 lanes: 1112 LUT4, 299 CCU2C, 1106 FF, 96 DPR16X4, 3 MULT18X18D, 3 DP16KD
// (merger and routing: 130 / 210 LUT4 beyond the lanes). Yosys 0.23
// synth_ice40, 2 lanes: 1000 LUT4, 2 SB_MAC16, 20 SB_RAM40_4K. Placed in
// dtmf_top (4x4 skin, 1 MS/s, 2 lanes, with the neuron unit, ECP5-85F,
// nextpnr seed 1; `eskin bitstream --scale-table --targets ecp5-85k --rates
// 1000000 --sizes 4`): 6980 TRELLIS_COMB, 4 MULT18X18D, 11 DP16KD, Fmax
// 49.6 MHz at 40 MHz; the critical path is frame_engine's (the lanes' sine
// ROM -> multiplier -> sum path, 43.5 MHz before, is cut by sdft_bank's
// product register).
module sdft_lanes #(
    parameter integer K_MAX = 6,
    parameter integer N = 32,
    parameter integer XW = 13,
    parameter integer CW = 16,
    parameter integer TW = 10,
    parameter integer ACC_W = 24,
    parameter integer FB = 0,
    parameter integer K_W = 8,
    parameter integer LANES = 1    // parallel sdft_bank instances, 1..64
) (
    input  wire             clk,
    input  wire             rst,        // synchronous, active high
    input  wire             in_valid,
    output wire             in_ready,
    input  wire [XW-1:0]    in_x,       // signed sample (code - mid)
    input  wire             in_skip,    // with in_x: no tokens for this sample
    input  wire             cfg_valid,
    output wire             cfg_ready,
    input  wire [K_W-1:0]   cfg_k,      // cfg_k < K_MAX
    input  wire [31:0]      cfg_inc,    // phase increment, 2^32 = one cycle
    input  wire             cfg_last,
    output wire             out_valid,
    input  wire             out_ready,
    output wire [K_W-1:0]   out_k,
    output wire [ACC_W-1:0] out_re,     // signed window sum
    output wire [ACC_W-1:0] out_im,     // signed window sum
    output wire             out_last
);
  generate
    if (LANES < 1 || LANES > 64 || LANES > K_MAX || K_MAX > (1 << K_W)) begin : g_bad_params
      sdft_lanes_illegal_parameters u_stop ();  // no such module: stops elaboration
    end
  endgenerate

  generate
    if (LANES == 1) begin : g_one
      /* verilator lint_off UNUSEDSIGNAL */
      wire [XW-1:0] win_unused;
      /* verilator lint_on UNUSEDSIGNAL */
      sdft_bank #(.K_MAX(K_MAX), .N(N), .XW(XW), .CW(CW), .TW(TW), .ACC_W(ACC_W), .FB(FB),
                  .K_W(K_W)) u_bank (
          .clk(clk), .rst(rst), .in_valid(in_valid), .in_ready(in_ready), .in_x(in_x),
          .in_skip(in_skip), .cfg_valid(cfg_valid), .cfg_ready(cfg_ready), .cfg_k(cfg_k),
          .cfg_inc(cfg_inc), .cfg_last(cfg_last), .out_valid(out_valid), .out_ready(out_ready),
          .out_k(out_k), .out_re(out_re), .out_im(out_im), .out_last(out_last),
          .win_ext({XW{1'b0}}), .win_rd(win_unused));
    end else if (LANES >= 2) begin : g_lanes
      localparam integer KL = (K_MAX + LANES - 1) / LANES;      // channels per lane
      localparam integer KB = (K_MAX > 1) ? $clog2(K_MAX) : 1;  // global index bits used
      localparam integer JB = (KL > 1) ? $clog2(KL) : 1;        // local index bits
      localparam integer LB = $clog2(LANES);                    // lane number bits
      localparam integer DB = KB + 1;                           // LANES <= K_MAX < 2^DB
      localparam [DB-1:0] L_DB = LANES[DB-1:0];
      localparam integer L_M1 = LANES - 1;
      localparam [LB-1:0] SEL_LAST = L_M1[LB-1:0];

      // ---- configuration routing: lane cfg_k mod LANES, index cfg_k / LANES
      // (constant divisor: bit slices when LANES is a power of two).
      /* verilator lint_off UNUSEDSIGNAL */
      wire [DB-1:0] ck = {1'b0, cfg_k[KB-1:0]};  // cfg_k < K_MAX: the low KB bits
      wire [DB-1:0] c_lane_w = ck % L_DB;
      wire [DB-1:0] c_idx_w = ck / L_DB;
      /* verilator lint_on UNUSEDSIGNAL */
      wire [LB-1:0] c_lane = c_lane_w[LB-1:0];
      wire [JB-1:0] c_idx = c_idx_w[JB-1:0];

      reg busy;        // a sample's tokens are not all out yet (never for a skipped one)
      reg configured;  // a cfg_last was taken
      wire [LANES-1:0] act;                 // lane l has a channel (l < K)
      wire [LANES-1:0] l_in_ready, l_cfg_ready, l_out_valid, l_take;
      wire [LANES*ACC_W-1:0] l_re, l_im;
      // Lane 0's window serves every lane (one RAM, not LANES copies): the
      // active lanes take every sample in the same clock and clear at the
      // same cfg_last (lane 0 always has a channel), so their windows and
      // write pointers are equal.
      /* verilator lint_off UNUSEDSIGNAL */
      wire [LANES*XW-1:0] l_win;  // lanes >= 1 only pass win0 back
      /* verilator lint_on UNUSEDSIGNAL */
      wire [XW-1:0] win0 = l_win[0 +: XW];
      wire cfg_fire = cfg_valid && cfg_ready;
      wire in_fire = in_valid && in_ready;
      assign cfg_ready = (&l_cfg_ready) && !busy;
      // The last token leaving the merger in this clock frees it for the
      // next sample in the same clock (the lanes are idle by then: each went
      // idle when its last token entered its own output register).
      wire last_leaving = m_valid && m_last && out_ready;
      assign in_ready = configured && (!busy || last_leaving) && !cfg_valid &&
                        (&(l_in_ready | ~act));

      // ---- merger state
      reg [LB-1:0] sel;
      reg [K_W-1:0] gk, klast;
      reg m_valid, m_last;
      reg [K_W-1:0] m_k;
      reg [ACC_W-1:0] m_re, m_im;
      wire m_free = !m_valid || out_ready;
      reg [ACC_W-1:0] sel_re, sel_im;  // lane sel's token (sel decoded one-hot)
      reg sel_valid;
      wire take = m_free && sel_valid;
      integer i;
      always @(*) begin
        sel_valid = 1'b0;
        sel_re = {ACC_W{1'b0}};
        sel_im = {ACC_W{1'b0}};
        for (i = 0; i < LANES; i = i + 1)
          if (l_take[i]) begin
            sel_valid = l_out_valid[i];
            sel_re = l_re[i*ACC_W +: ACC_W];
            sel_im = l_im[i*ACC_W +: ACC_W];
          end
      end

      genvar l;
      for (l = 0; l < LANES; l = l + 1) begin : g_lane
        localparam integer LI = l;
        localparam [LB-1:0] LID = LI[LB-1:0];
        localparam [KB:0] LK = LI[KB:0];
        wire is_tgt = c_lane == LID;
        wire has_ch;  // l < K = cfg_k + 1 (of a cfg_last token); lane 0 always
        if (l == 0) begin : g_first
          assign has_ch = 1'b1;
        end else begin : g_other
          assign has_ch = LK <= {1'b0, cfg_k[KB-1:0]};
        end
        reg act_r, rem_ok;
        reg [JB-1:0] rem_idx;
        reg [31:0] rem_inc;
        always @(posedge clk) begin
          if (rst) begin
            rem_ok <= 1'b0;
            act_r <= 1'b0;
          end else if (cfg_fire) begin
            if (cfg_last) begin
              rem_ok <= 1'b0;  // a new configuration starts
              act_r <= has_ch;
            end else if (is_tgt && (!rem_ok || c_idx >= rem_idx)) begin
              rem_ok <= 1'b1;
              rem_idx <= c_idx;
              rem_inc <= cfg_inc;
            end
          end
        end
        wire resend = cfg_last && !is_tgt;
        wire b_cfg_valid = cfg_fire && (cfg_last ? has_ch : is_tgt);
        wire [JB-1:0] b_idx = resend ? rem_idx : c_idx;
        assign act[l] = act_r;
        assign l_take[l] = sel == LID;
        /* verilator lint_off PINCONNECTEMPTY */
        sdft_bank #(.K_MAX(KL), .N(N), .XW(XW), .CW(CW), .TW(TW), .ACC_W(ACC_W), .FB(FB),
                    .K_W(K_W), .OWN_WIN(l == 0 ? 1 : 0)) u_bank (
            .clk(clk), .rst(rst), .in_valid(in_fire && act[l]), .in_ready(l_in_ready[l]),
            .in_x(in_x), .in_skip(in_skip), .cfg_valid(b_cfg_valid), .cfg_ready(l_cfg_ready[l]),
            .cfg_k({{(K_W - JB){1'b0}}, b_idx}), .cfg_inc(resend ? rem_inc : cfg_inc),
            .cfg_last(cfg_last),
            .out_valid(l_out_valid[l]), .out_ready(l_take[l] && m_free), .out_k(),
            .out_re(l_re[l*ACC_W +: ACC_W]), .out_im(l_im[l*ACC_W +: ACC_W]), .out_last(),
            .win_ext(win0), .win_rd(l_win[l*XW +: XW]));
        /* verilator lint_on PINCONNECTEMPTY */
      end

      always @(posedge clk) begin
        if (rst) begin
          busy <= 1'b0;
          configured <= 1'b0;
          sel <= {LB{1'b0}};
          gk <= {K_W{1'b0}};
          klast <= {K_W{1'b0}};
          m_valid <= 1'b0;
        end else begin
          if (cfg_fire && cfg_last) begin
            configured <= 1'b1;
            klast <= cfg_k;
          end
          if (in_fire) busy <= !in_skip;  // a skipped sample sends no token
          else if (m_valid && out_ready && m_last) busy <= 1'b0;
          if (take) begin
            m_valid <= 1'b1;
            m_k <= gk;
            m_re <= sel_re;
            m_im <= sel_im;
            m_last <= gk == klast;
            gk <= (gk == klast) ? {K_W{1'b0}} : gk + 1'b1;
            sel <= (gk == klast || sel == SEL_LAST) ? {LB{1'b0}} : sel + 1'b1;
          end else if (out_ready) begin
            m_valid <= 1'b0;
          end
        end
      end
      assign out_valid = m_valid;
      assign out_k = m_k;
      assign out_re = m_re;
      assign out_im = m_im;
      assign out_last = m_last;
    end
  endgenerate
endmodule
`default_nettype wire
