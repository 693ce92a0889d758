`default_nettype none
// sdft_front: the DFT front end for many carriers at a high sample rate:
// a small sample FIFO (DEPTH samples, each with its tag, the ADC's t) in
// front of rtl/sdft_lanes.v, so that a frame's sample, whose K tokens leave
// one a clock (longer than a sample period once K exceeds it), no longer
// has to fit in what the ADC's one output register can wait: the samples
// that arrive meanwhile queue, and the skipped samples after it, which the
// lanes compute in S < P clocks, catch up. Tokens, configuration and the
// arithmetic are sdft_lanes' (bit-exact spec: hls/sdft_bank.h).
//
// Why a FIFO, and why lanes rather than a wider merger: rtl/frame_capture.v
// (the consumer in rtl/dtmf_top.v) stores one token a clock and decides at
// a sample's handshake into the DFT whether that sample is a frame's
// (smp_fire, smp_frame); every token of a sample must be out by the next
// sample's handshake (rtl/sdft_lanes.v). So a frame's sample holds the DFT
// for F = K + 8 clocks however many lanes there are (K = 128: 136 clocks,
// 2.7 to 3.4 sample periods at 40-50 MHz and 1 MS/s), and only a queue in
// front of the handshake lets the ADC go on. The lanes set every other
// sample's pace, S = 6 ceil(K / L) + 2: K = 128 needs L >= 22 for S <= 40
// (38), L = 32 gives 26 (35 % of a 40-clock period spare, and S <= P down
// to a 26 MHz clock). Each lane has its multiplier and its quarter-sine
// ROM; the N-sample window is one, lane 0's (rtl/sdft_lanes.v).
//
// Ports: s_* from the ADC (valid/ready, the sample and its tag); dft_fire
// is high in the clock a sample enters the lanes (the handshake
// rtl/frame_capture.v calls smp_fire), dft_t that sample's tag, dft_skip
// that sample's in_skip (read in dft_fire's clock only, from registers:
// frame_capture's !smp_frame). backlog: samples in the FIFO.
//
// FIFO: a sample that finds the FIFO empty and the lanes ready enters the
// lanes in its own clock (no added latency; DEPTH = 0 is sdft_lanes with
// these ports, as rtl/dtmf_top.v wires the ADC today); otherwise it is
// stored, and the lanes take the oldest stored sample first. s_ready is
// low only when the FIFO is full and no sample leaves it in this clock (a
// sample leaving makes room for one in the same clock).
//
// Schedule and backlog (the ADC converts every P clocks whatever the DFT
// does, holds one sample, and drops a new one that finds the previous
// still held: rtl/adc_ad7476.v). F = sdft_lanes_interval(K, L, 1) clocks
// from a frame's sample's handshake to the next, S = sdft_skip_interval(K,
// L) after any other (rtl/sdft_lanes.v, frame_capture taking a token a
// clock). Sample j arrives at a_j = a_0 + j P and enters the lanes at
//   h_j = max(a_j, h_{j-1} + I_{j-1}),   I = F after a frame's, else S
// (in FIFO order; exact, tests/rtl/sdft_front_test.cpp). With the frame's
// sample entering on arrival (h_0 = a_0), the samples arriving before the
// lanes are free at a_0 + F wait: the FIFO holds at most
//   B = floor((F - 1) / P)                       (sdft_front_backlog)
// of them (at clock a_0 + F - 1), then one leaves every S clocks while
// one arrives every P. A sample is lost when the one before it is still in
// the ADC's register at its arrival; that register is taken into the FIFO
// whenever there is room, so it holds a sample only with the FIFO full,
// and the arrival at a_0 + j P finds j - 1 samples waiting as long as j P
// <= F. No sample is lost iff
//   S <= P,   F < (DEPTH + 2) P,   F - P <= (STEP - 1)(P - S)
// (STEP = 1, every sample a frame's: F <= P): the last condition brings
// the delay h_j - a_j = F - P - (j - 1)(P - S) back to 0 before the next
// frame's sample, so each frame starts from an empty FIFO.
// hls/sdft_bank.h's sdft_front_backlog() and sdft_front_min_period() are
// these; common/eskin/dtmf_top_plan.h's budget takes them. K = 128 (a
// 64x64 skin), 32 lanes: F = 136, S = 26; at P = 40 (40 MHz, 1 MS/s) B = 3,
// DEPTH >= 2; with DEPTH 4, F < 6 P holds down to P = 23 and the least
// period, 27, is the catch-up's at STEP 1000 (tests/rtl/sdft_front_test.cpp
// runs 27 and 26).
//
// Resources, the 64x64 front end (K_MAX 128, N 512, XW 12, ACC_W 22,
// LANES 32, DEPTH 4, TAG_W 32; scripts/synth_ecp5.sh sdft_front --param
// ..., Yosys 0.70 synth_ecp5, out of context): 9288 LUT4, 2305 CCU2C,
// 11842 FF, 907 DPR16X4 (each lane's phases, increments and sums; the
// FIFO), 32 MULT18X18D, 33 DP16KD (each lane's sine ROM, and the one
// window). Before the lanes shared lane 0's window (a copy per lane):
// 9607 LUT4, 2460 CCU2C, 12121 FF, 64 DP16KD, and placed on the ECP5-85F
// (--pnr --freq 50 --device 85k, nextpnr seed 1) 21247 of its 83640
// TRELLIS_COMB, Fmax 67.2 MHz against 50, the critical path a lane's ROM
// -> multiplier -> product register (14.9 ns), as in sdft_bank alone: the
// 32-way merger is not on it. Pairs of lanes could share a ROM through its
// second port (16 DP16KD more).
module sdft_front #(
    parameter integer K_MAX = 6,
    parameter integer N = 32,
    parameter integer XW = 13,
    parameter integer CW = 16,
    parameter integer TW = 10,
    parameter integer ACC_W = 24,
    parameter integer FB = 0,
    parameter integer K_W = 8,
    parameter integer LANES = 1,   // sdft_lanes' LANES, 1..64
    parameter integer DEPTH = 4,   // FIFO samples: 0 (none) or a power of two, 1..64
    parameter integer TAG_W = 32   // a sample's tag (the ADC's t), 1..32 bits
) (
    input  wire             clk,
    input  wire             rst,        // synchronous, active high
    input  wire             s_valid,
    output wire             s_ready,
    input  wire [XW-1:0]    s_x,        // signed sample (code - mid)
    input  wire [TAG_W-1:0] s_t,
    output wire             dft_fire,   // a sample enters the lanes in this clock
    output wire [TAG_W-1:0] dft_t,      // its tag
    input  wire             dft_skip,   // its in_skip (no tokens)
    output wire [6:0]       backlog,    // samples in the FIFO
    input  wire             cfg_valid,
    output wire             cfg_ready,
    input  wire [K_W-1:0]   cfg_k,
    input  wire [31:0]      cfg_inc,
    input  wire             cfg_last,
    output wire             out_valid,
    input  wire             out_ready,
    output wire [K_W-1:0]   out_k,
    output wire [ACC_W-1:0] out_re,
    output wire [ACC_W-1:0] out_im,
    output wire             out_last
);
  generate
    if (DEPTH < 0 || DEPTH > 64 || (DEPTH & (DEPTH - 1)) != 0 || TAG_W < 1 || TAG_W > 32)
    begin : g_bad_params
      sdft_front_illegal_parameters u_stop ();  // no such module: stops elaboration
    end
  endgenerate

  wire d_valid, d_ready;
  wire [XW-1:0] d_x;
  assign dft_fire = d_valid && d_ready;

  generate
    if (DEPTH == 0) begin : g_direct
      assign s_ready = d_ready;
      assign d_valid = s_valid;
      assign d_x = s_x;
      assign dft_t = s_t;
      assign backlog = 7'd0;
    end else begin : g_fifo
      localparam integer AB = (DEPTH > 1) ? $clog2(DEPTH) : 1;
      localparam integer D_M1 = DEPTH - 1;
      localparam [AB-1:0] LAST = D_M1[AB-1:0];
      localparam [6:0] FULL = DEPTH[6:0];
      reg [XW+TAG_W-1:0] mem [0:DEPTH-1];
      reg [AB-1:0] wp, rp;
      reg [6:0] count;
      wire empty = count == 7'd0;
      // A stored sample leaves (the lanes take the head; d_valid is high
      // whenever the FIFO is not empty, so this needs no s_valid) ...
      wire pop = d_ready && !empty;
      // ... which makes room for the ADC's sample in the same clock.
      assign s_ready = count != FULL || pop;
      // The ADC's sample goes straight into the lanes when nothing is stored
      // and they take it; else it is stored.
      wire push = s_valid && s_ready && !(empty && d_ready);
      assign d_valid = !empty || s_valid;
      assign d_x = empty ? s_x : mem[rp][XW-1:0];
      assign dft_t = empty ? s_t : mem[rp][XW+TAG_W-1:XW];
      assign backlog = count;
      always @(posedge clk)
        if (push) mem[wp] <= {s_t, s_x};
      always @(posedge clk) begin
        if (rst) begin
          wp <= {AB{1'b0}};
          rp <= {AB{1'b0}};
          count <= 7'd0;
        end else begin
          if (push) wp <= (wp == LAST) ? {AB{1'b0}} : wp + 1'b1;
          if (pop) rp <= (rp == LAST) ? {AB{1'b0}} : rp + 1'b1;
          if (push && !pop) count <= count + 7'd1;
          else if (pop && !push) count <= count - 7'd1;
        end
      end
    end
  endgenerate

  sdft_lanes #(.K_MAX(K_MAX), .N(N), .XW(XW), .CW(CW), .TW(TW), .ACC_W(ACC_W), .FB(FB),
               .K_W(K_W), .LANES(LANES)) u_lanes (
      .clk(clk), .rst(rst), .in_valid(d_valid), .in_ready(d_ready), .in_x(d_x),
      .in_skip(dft_skip), .cfg_valid(cfg_valid), .cfg_ready(cfg_ready), .cfg_k(cfg_k),
      .cfg_inc(cfg_inc), .cfg_last(cfg_last), .out_valid(out_valid), .out_ready(out_ready),
      .out_k(out_k), .out_re(out_re), .out_im(out_im), .out_last(out_last));
endmodule
`default_nettype wire
