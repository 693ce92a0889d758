`default_nettype none
// dft_capture_tb: rtl/sdft_lanes.v into rtl/frame_capture.v, wired as
// rtl/dtmf_top.v wires them (the window cleared by the carrier write with
// `last`, t counting the samples taken, the tokens of every sample that is
// not a frame skipped), for tests/rtl/dft_capture_test.cpp.
// The merged token stream is brought out (tok_*) to watch its pace.
module dft_capture_tb #(
    parameter integer KS = 24,
    parameter integer N = 64,
    parameter integer ACC_W = 19,
    parameter integer STEP = 3,
    parameter integer LANES = 6
) (
    input  wire        clk,
    input  wire        rst,
    input  wire        in_valid,
    output wire        in_ready,
    input  wire [11:0] in_x,
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
  wire in_fire = in_valid && in_ready;
  wire cfg_done = cfg_valid && cfg_ready && cfg_last;
  reg [31:0] t;
  always @(posedge clk) begin
    if (rst) t <= 32'd0;
    else if (in_fire) t <= t + 32'd1;
  end
  wire [7:0] tok_k;
  wire [ACC_W-1:0] tok_re, tok_im;
  wire smp_frame;
  sdft_lanes #(.K_MAX(KS), .N(N), .XW(12), .CW(16), .TW(10), .ACC_W(ACC_W), .K_W(8),
               .LANES(LANES)) u_sdft (
      .clk(clk), .rst(rst), .in_valid(in_valid), .in_ready(in_ready), .in_x(in_x),
      .in_skip(!smp_frame), .cfg_valid(cfg_valid), .cfg_ready(cfg_ready), .cfg_k(cfg_k),
      .cfg_inc(cfg_inc), .cfg_last(cfg_last), .out_valid(tok_valid), .out_ready(tok_ready),
      .out_k(tok_k), .out_re(tok_re), .out_im(tok_im), .out_last(tok_last));
  frame_capture #(.KS(KS), .W(ACC_W), .N(N), .STEP(STEP)) u_cap (
      .clk(clk), .rst(rst), .clr(cfg_done), .smp_fire(in_fire), .smp_t(t),
      .smp_frame(smp_frame), .tok_valid(tok_valid), .tok_ready(tok_ready), .tok_last(tok_last),
      .tok_re(tok_re), .tok_im(tok_im), .rd_addr(rd_addr), .rd_data(rd_data), .pending(pending),
      .frame_t(frame_t), .done(done), .clear(clear), .overruns(overruns));
  /* verilator lint_off UNUSEDSIGNAL */
  wire [7:0] tok_k_unused = tok_k;  // tokens arrive in k order; the capture counts them
  /* verilator lint_on UNUSEDSIGNAL */
endmodule
`default_nettype wire
