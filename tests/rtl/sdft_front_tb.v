`default_nettype none
// sdft_front_tb: rtl/sdft_front.v into rtl/frame_capture.v, wired as a top
// with the FIFO would wire them (rtl/dtmf_top.v's DFT and capture with the
// ADC's samples queued in front of the lanes): the capture's smp_fire and
// smp_t are the samples' entry into the lanes and their ADC tag, the
// window is cleared by the carrier write with `last`, and every sample
// that is not a frame's is skipped. For tests/rtl/sdft_front_test.cpp, which
// plays the ADC (a conversion every P clocks, one held).
module sdft_front_tb #(
    parameter integer KS = 128,
    parameter integer N = 512,
    parameter integer ACC_W = 22,
    parameter integer STEP = 1000,
    parameter integer LANES = 32,
    parameter integer DEPTH = 4
) (
    input  wire        clk,
    input  wire        rst,
    input  wire        s_valid,
    output wire        s_ready,
    input  wire [11:0] s_x,
    input  wire [31:0] s_t,
    output wire        dft_fire,
    output wire [6:0]  backlog,
    input  wire        cfg_valid,
    output wire        cfg_ready,
    input  wire [7:0]  cfg_k,
    input  wire [31:0] cfg_inc,
    input  wire        cfg_last,
    input  wire [7:0]  rd_addr,
    output wire [31:0] rd_data,
    output wire        pending,
    output wire [31:0] frame_t,
    input  wire        done,
    input  wire        clear,
    output wire [15:0] overruns,
    output wire        tok_valid,
    output wire        tok_ready,
    output wire        tok_last
);
  wire cfg_done = cfg_valid && cfg_ready && cfg_last;
  wire [31:0] dft_t;
  wire [7:0] tok_k;
  wire [ACC_W-1:0] tok_re, tok_im;
  wire smp_frame;
  sdft_front #(.K_MAX(KS), .N(N), .XW(12), .CW(16), .TW(10), .ACC_W(ACC_W), .K_W(8),
               .LANES(LANES), .DEPTH(DEPTH), .TAG_W(32)) u_front (
      .clk(clk), .rst(rst), .s_valid(s_valid), .s_ready(s_ready), .s_x(s_x), .s_t(s_t),
      .dft_fire(dft_fire), .dft_t(dft_t), .dft_skip(!smp_frame), .backlog(backlog),
      .cfg_valid(cfg_valid), .cfg_ready(cfg_ready), .cfg_k(cfg_k), .cfg_inc(cfg_inc),
      .cfg_last(cfg_last), .out_valid(tok_valid), .out_ready(tok_ready), .out_k(tok_k),
      .out_re(tok_re), .out_im(tok_im), .out_last(tok_last));
  frame_capture #(.KS(KS), .W(ACC_W), .N(N), .STEP(STEP)) u_cap (
      .clk(clk), .rst(rst), .clr(cfg_done), .smp_fire(dft_fire), .smp_t(dft_t),
      .smp_frame(smp_frame), .tok_valid(tok_valid), .tok_ready(tok_ready), .tok_last(tok_last),
      .tok_re(tok_re), .tok_im(tok_im), .rd_addr(rd_addr), .rd_data(rd_data), .pending(pending),
      .frame_t(frame_t), .done(done), .clear(clear), .overruns(overruns));
  /* verilator lint_off UNUSEDSIGNAL */
  wire [7:0] tok_k_unused = tok_k;  // tokens arrive in k order; the capture counts them
  /* verilator lint_on UNUSEDSIGNAL */
endmodule
`default_nettype wire
