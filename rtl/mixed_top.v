`default_nettype none
// mixed_top: the FPGA top of a scene with both a DTMF skin and Hall sensors
// (docs/fpga.md, "Mixed scenes"): dtmf_top (ADC, sliding DFT, frame engine)
// and hall_top (I2C buses, MLX90393 sequencers, Hall decoding) side by side
// on one clock, sharing one host link:
//
//   dtmf_top.pkt_*  --\
//                      packet_arbiter -> link_framer -> uart_tx --> host
//   hall_top.pkt_*  --/
//   host --> uart_rxd -> dtmf_top (every command type but 0x90-0x9F)
//                     -> hall_top (0x90-0x9F, when it takes commands: DELTAS)
//
// Whole packets are interleaved (a packet is never split), and one
// link_framer numbers them, so the host sees one seq sequence and detects a
// lost packet of either top. Both tops decode the command line with their
// own uart_rx and cmd_decoder; each keeps only its own types, so every
// command is judged once (an unknown type by the DTMF engine). A frame
// broken on the line is counted by both (each top's counters describe the
// line as it heard it).
//
// The parameters are the two tops' own, by the same names (CLK_HZ and BAUD
// are shared), so a scene's two generated parameter sets
// (common/eskin/dtmf_top_plan.h, sim/hall_top_spec.h) apply unchanged. The
// defaults: the default DTMF scene's top at 18 MHz beside hall_top's
// default two buses of two sensors, their conversion waits scaled to 18 MHz.
// Packet timestamps stay each top's own: DTMF packets carry ADC sample
// counts, Hall packets microseconds (docs/protocol.md).
module mixed_top #(
    parameter integer CLK_HZ = 18_000_000,
    parameter integer BAUD = 3_000_000,
    // dtmf_top
    parameter integer SAMPLE_HZ = 35_000,
    parameter integer KS = 7,
    parameter integer N = 32,
    parameter integer ACC_W = 18,
    parameter integer STEP = 35,
    parameter integer IW = 11,
    parameter integer IMEM_WORDS = 1280,
    parameter integer DW = 10,
    parameter integer KW = 9,
    parameter integer OUT_DEPTH = 512,
    parameter integer ENGINE_FAST_SHIFT = 0,
    parameter UCODE_HEX = "",
    parameter KROM_HEX = "",
    parameter integer SDFT_LANES = 1,
    parameter integer NEURON_UNIT = 0,
    parameter integer NEURON_LANES = 0,  // dtmf_top's neuron lanes (and their sizes)
    parameter integer NEURON_BITS = 11,
    parameter integer COLS = 32,
    // One clock here: the ADC runs on clk (dtmf_top's ADC_CLK_HZ 0; the
    // board flow gives mixed scenes no ADC clock of their own).
    parameter integer ADC_CLK_HZ = 0,
    // hall_top
    parameter integer SCL_HZ = 400_000,
    parameter integer NB = 2,
    parameter integer NSB = 2,
    parameter [NB*NSB*7-1:0] ADDR = {7'h0D, 7'h0C, 7'h0D, 7'h0C},
    parameter [NB*NSB*7-1:0] MUX_ADDR = {NB * NSB{7'h00}},
    parameter [NB*NSB*3-1:0] MUX_CH = {NB * NSB{3'd0}},
    parameter [15:0] REG0 = 16'h007C,
    parameter [15:0] REG1 = 16'hE000,
    parameter [15:0] REG2 = 16'h0008,
    parameter integer BURST = 1,
    parameter integer CONV_CYC = 44_346,
    parameter integer STALE_CYC = 55_431,
    parameter integer STATUS_EVERY = 64,
    parameter integer DELTAS = 0,
    parameter integer FT = 0,
    parameter integer FT_ID = 0,
    parameter integer DECOUPLE = 0,
    parameter integer DEC_ID = 0,
    parameter [31:0] DEC_GAIN_X = 32'd9830,
    parameter [31:0] DEC_GAIN_Y = 32'd9830,
    parameter [31:0] DEC_GAIN_Z = 32'd15860,
    parameter integer CURVE = 0,
    parameter integer CURVE_ID = 0,
    parameter integer NC = 1,
    parameter integer CURVE_NB = 13,
    parameter integer CURVE_NR = 3,
    parameter [15:0] CURVE_GAIN_X = 16'd1540,
    parameter [15:0] CURVE_GAIN_Y = 16'd1540,
    parameter [15:0] CURVE_GAIN_Z = 16'd2478,
    parameter [CURVE_NR*32-1:0] LOCK_MN = {32'sd16200, 32'sd4800, 32'sd900}
) (
    input  wire              clk,
    input  wire              rst_n,      // active low (button); power-on reset built in
    output wire              adc_cs_n,
    output wire              adc_sclk,
    input  wire              adc_sdata,
    input  wire [NB-1:0]     scl_i,
    input  wire [NB-1:0]     sda_i,
    output wire [NB-1:0]     scl_oe,
    output wire [NB-1:0]     sda_oe,
    input  wire [NB*NSB-1:0] drdy,
    output wire              uart_txd,   // to the host
    input  wire              uart_rxd    // from the host
);
  generate
    if (ADC_CLK_HZ != 0) begin : g_bad_params
      mixed_top_illegal_parameters u_stop ();  // no such module: stops elaboration
    end
  endgenerate

  // hall_top resets like dtmf_top (which has its own power_on_reset).
  wire rst;
  power_on_reset u_por (.clk(clk), .rst_n(rst_n), .rst(rst));

  wire [1:0]  pv, pr;
  wire [15:0] pd;
  /* verilator lint_off PINCONNECTEMPTY */
  dtmf_top #(
      .CLK_HZ(CLK_HZ), .SAMPLE_HZ(SAMPLE_HZ), .BAUD(BAUD), .KS(KS), .N(N), .ACC_W(ACC_W),
      .STEP(STEP), .IW(IW), .IMEM_WORDS(IMEM_WORDS), .DW(DW), .KW(KW), .OUT_DEPTH(OUT_DEPTH),
      .ENGINE_FAST_SHIFT(ENGINE_FAST_SHIFT), .UCODE_HEX(UCODE_HEX), .KROM_HEX(KROM_HEX), .EXT_LINK(1),
      .HALL_CMDS(DELTAS != 0 ? 1 : 0), .SDFT_LANES(SDFT_LANES), .NEURON_UNIT(NEURON_UNIT),
      .NEURON_LANES(NEURON_LANES), .NEURON_BITS(NEURON_BITS), .COLS(COLS)
  ) u_dtmf (
      .clk(clk), .adc_clk(clk), .rst_n(rst_n), .adc_cs_n(adc_cs_n), .adc_sclk(adc_sclk),
      .adc_sdata(adc_sdata), .uart_txd(), .uart_rxd(uart_rxd), .pkt_valid(pv[0]), .pkt_ready(pr[0]), .pkt_data(pd[7:0]));
  hall_top #(
      .CLK_HZ(CLK_HZ), .BAUD(BAUD), .SCL_HZ(SCL_HZ), .NB(NB), .NSB(NSB), .ADDR(ADDR),
      .MUX_ADDR(MUX_ADDR), .MUX_CH(MUX_CH), .REG0(REG0), .REG1(REG1), .REG2(REG2),
      .BURST(BURST), .CONV_CYC(CONV_CYC), .STALE_CYC(STALE_CYC), .STATUS_EVERY(STATUS_EVERY),
      .DELTAS(DELTAS), .FT(FT), .FT_ID(FT_ID), .DECOUPLE(DECOUPLE), .DEC_ID(DEC_ID),
      .DEC_GAIN_X(DEC_GAIN_X), .DEC_GAIN_Y(DEC_GAIN_Y), .DEC_GAIN_Z(DEC_GAIN_Z),
      .CURVE(CURVE), .CURVE_ID(CURVE_ID), .NC(NC), .CURVE_NB(CURVE_NB), .CURVE_NR(CURVE_NR),
      .CURVE_GAIN_X(CURVE_GAIN_X), .CURVE_GAIN_Y(CURVE_GAIN_Y), .CURVE_GAIN_Z(CURVE_GAIN_Z),
      .LOCK_MN(LOCK_MN), .EXT_LINK(1)
  ) u_hall (
      .clk(clk), .rst(rst), .scl_i(scl_i), .sda_i(sda_i), .scl_oe(scl_oe), .sda_oe(sda_oe),
      .drdy(drdy), .uart_txd(), .uart_rxd(uart_rxd), .pkt_valid(pv[1]), .pkt_ready(pr[1]),
      .pkt_data(pd[15:8]));
  /* verilator lint_on PINCONNECTEMPTY */

  // ---- the shared link: whole packets, one seq counter, one UART
  wire       a_valid, a_ready, l_valid, l_ready;
  wire [7:0] a_data, l_data, l_seq;
  packet_arbiter #(.NS(2)) u_arb (
      .clk(clk), .rst(rst), .s_valid(pv), .s_ready(pr), .s_data(pd), .m_valid(a_valid),
      .m_ready(a_ready), .m_data(a_data));
  link_framer u_framer (
      .clk(clk), .rst(rst), .s_valid(a_valid), .s_ready(a_ready), .s_data(a_data),
      .m_valid(l_valid), .m_ready(l_ready), .m_data(l_data), .seq(l_seq));
  uart_tx #(.CLK_HZ(CLK_HZ), .BAUD(BAUD)) u_tx (
      .clk(clk), .rst(rst), .s_valid(l_valid), .s_ready(l_ready), .s_data(l_data),
      .tx(uart_txd));

  // ---- probes (tests)
  wire [7:0] p_seq /* verilator public_flat_rd */ = l_seq;
  wire p_dtmf_pkt_fire /* verilator public_flat_rd */ = pv[0] && pr[0];
  wire p_hall_pkt_fire /* verilator public_flat_rd */ = pv[1] && pr[1];
endmodule
`default_nettype wire
