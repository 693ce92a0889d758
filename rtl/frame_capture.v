`default_nettype none
// frame_capture: picks the frames out of sdft_bank's per-sample token stream
// and hands them to the frame engine in a double-buffered block RAM.
//
// Frames (hls/dtmf_chain.h): once the DFT window is full (N samples since
// reset or since the last carrier reload, `clr`) and then every STEP samples:
// with `filled` counting samples since the clear (saturating at N),
//   filled < N:  filled + 1; the sample is a frame when that reaches N (phase 0)
//   filled == N: phase = (phase + 1) mod STEP; a frame when phase == 0.
// The decision is taken at the sample's handshake into sdft_bank
// (smp_fire, with its counter smp_t); that sample's KS tokens follow.
// smp_frame is that decision for a sample entering now (from registers
// only): dtmf_top skips the DFT's tokens of every other sample
// (rtl/sdft_lanes.v, in_skip = !smp_frame), and tokens of a sample that is
// not a frame, should they come, are not stored.
//
// Buffer: 2 banks x KS entries of {im, re} (2 W bits), one entry written
// per token, in the token's clock: tok_ready is always high, so the stream
// may offer a token every clock (sdft_lanes from 6 lanes on does:
// rtl/sdft_lanes.v, G = 1). The engine sees 32-bit words, re at 2k and im
// at 2k + 1, sign-extended: it reads rd_data one clock after rd_addr (the
// entry's read is registered, and so is the half it picks). Tokens of a
// frame go to the bank the engine is not reading.
// When the frame's last token is written: if the engine has released its
// bank (no frame pending, or `done` in that clock), the banks swap and
// `pending` rises with frame_t = the sample's t; else the frame is lost and
// `overruns` counts it (16-bit, saturating; cleared by `clear`). The engine
// releases with `done`.
// The last token is stored and judged in its own clock, so the next
// sample's handshake may come in that same clock (sdft_bank's tightest
// pace, 6 KS + 2): cur_frame changes only after it.
module frame_capture #(
    parameter integer KS = 7,      // tokens per sample (carriers + DC channel)
    parameter integer W = 18,      // signed token width (sdft_bank ACC_W)
    parameter integer N = 32,      // DFT window
    parameter integer STEP = 35    // samples per frame
) (
    input  wire         clk,
    input  wire         rst,
    input  wire         clr,        // the DFT window was cleared (carrier reload)
    input  wire         smp_fire,   // a sample entered sdft_bank
    input  wire [31:0]  smp_t,
    output wire         smp_frame,  // a sample entering now would be a frame
    input  wire         tok_valid,
    output wire         tok_ready,
    input  wire         tok_last,
    input  wire [W-1:0] tok_re,
    input  wire [W-1:0] tok_im,
    input  wire [7:0]   rd_addr,    // 2k (re) or 2k + 1 (im) of the engine's bank
    output wire [31:0]  rd_data,
    output reg          pending,
    output reg  [31:0]  frame_t,
    input  wire         done,
    input  wire         clear,      // zero `overruns`
    output reg  [15:0]  overruns
);
  localparam integer FW = $clog2(N + 1);
  localparam integer PW = (STEP > 1) ? $clog2(STEP) : 1;
  localparam integer STEP_M1_I = STEP - 1;
  localparam [FW-1:0] N_F = N[FW-1:0];
  localparam [PW-1:0] STEP_M1 = STEP_M1_I[PW-1:0];
  generate
    if (KS < 1 || 2 * KS > 256 || W < 2 || W > 32 || N < 2 || STEP < 1) begin : g_bad_params
      frame_capture_illegal_parameters u_stop ();  // no such module: stops elaboration
    end
  endgenerate

  // ---- frame decision per sample ----
  reg [FW-1:0] filled;
  reg [PW-1:0] phase;
  reg          cur_frame;   // the sample whose tokens arrive now is a frame
  reg [31:0]   cur_t;
  assign smp_frame = (filled != N_F) ? (filled + 1'b1 == N_F) : (phase == STEP_M1);
  always @(posedge clk) begin
    if (rst || clr) begin
      filled <= {FW{1'b0}};
      phase <= {PW{1'b0}};
      if (rst) begin
        cur_frame <= 1'b0;
        cur_t <= 32'd0;
      end
    end else if (smp_fire) begin
      cur_t <= smp_t;
      cur_frame <= smp_frame;
      if (filled != N_F) begin
        filled <= filled + 1'b1;
        phase <= {PW{1'b0}};
      end else begin
        phase <= (phase == STEP_M1) ? {PW{1'b0}} : phase + 1'b1;
      end
    end
  end

  // ---- buffer ----
  localparam integer TB = (KS > 1) ? $clog2(KS) : 1;  // token index bits
  reg [2*W-1:0] mem [0:(1 << (TB + 1)) - 1];          // {bank, k}: {im, re}
  reg          eb;           // bank the engine reads
  reg [TB-1:0] widx;         // k of the next token
  reg [2*W-1:0] rd_word;
  reg          rd_im;        // the read asked for im (odd address)
  assign tok_ready = 1'b1;
  wire tok_fire = tok_valid;
  /* verilator lint_off UNUSEDSIGNAL */
  wire [7:0] ra = rd_addr;   // bits 0..TB used (2 KS <= 256 words)
  /* verilator lint_on UNUSEDSIGNAL */
  wire [W-1:0] rd_half = rd_im ? rd_word[2*W-1:W] : rd_word[W-1:0];
  assign rd_data = {{(32 - W){rd_half[W-1]}}, rd_half};

  always @(posedge clk) begin
    if (cur_frame && tok_fire) mem[{!eb, widx}] <= {tok_im, tok_re};
    rd_word <= mem[{eb, ra[TB:1]}];
    rd_im <= ra[0];
  end

  always @(posedge clk) begin
    if (rst) begin
      eb <= 1'b0;
      widx <= {TB{1'b0}};
      pending <= 1'b0;
      frame_t <= 32'd0;
      overruns <= 16'd0;
    end else begin
      if (clear) overruns <= 16'd0;
      if (done) pending <= 1'b0;
      if (tok_fire) begin
        widx <= tok_last ? {TB{1'b0}} : widx + 1'b1;
        if (tok_last && cur_frame) begin
          if (!pending || done) begin
            eb <= !eb;
            pending <= 1'b1;
            frame_t <= cur_t;
          end else if (overruns != 16'hFFFF && !clear) begin
            overruns <= overruns + 16'd1;
          end
        end
      end
    end
  end
endmodule
`default_nettype wire
