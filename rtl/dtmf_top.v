`default_nettype none
// dtmf_top: the FPGA top of the DTMF (spatial-frequency) skin path, the whole
// decoding chain (docs/fpga.md):
//
//   AD7476A --SPI--> adc_ad7476 -> x = code - 2048 -> sdft_front (SDFT_FIFO
//   samples queue, then sdft_lanes: KS channels, the carriers + DC when
//   demixing; SDFT_LANES sdft_bank lanes, 1: sdft_bank itself; tokens only
//   for the samples frame_capture keeps) -> frame_capture
//   (every STEP-th sample once the window is full; double-buffered) ->
//   frame_engine, microcode
//   rtl/ucode/dtmf_chain.fe: carrier_demix, carrier_magnitude,
//   taxel_reconstruct, ghost_filter, izhikevich_layer x 2 (receptors, then the
//   3x3-weighted layer; with NEURON_UNIT on the hardware unit
//   rtl/izhikevich_layer.v), synapse_weights, spike_encoder, packets, commands ->
//   byte_fifo -> link_framer -> uart_tx --> host (with EXT_LINK: byte_fifo ->
//   pkt_*, into rtl/mixed_top.v's shared link)
//   host --> uart_rx -> cmd_decoder (COBS, CRC, length) -> frame_engine
//
// Everything after the DFT runs once per frame on the frame engine, whose
// state and constants live in block RAM (DMEM: SPRAM on the UP5K, by its
// ram_style attribute); every command is applied by its microcode at run
// time. The bit-exact spec of the packets is hls/dtmf_chain.h; every
// parameter below is generated from a scene by common/eskin/dtmf_top_plan.h
// (dtmf_top_params); the defaults are the default scene's
// (scenes/neuroskin2.yaml) on an iCE40 UP5K at 18 MHz (the board wrapper's
// PLL: 12 MHz x 3/2).
//
// Sample format: the AD7476A gives 12-bit codes, x = code - 2048 (12 bits
// signed). Timestamps: every frame carries t, the ADC sample counter of its
// newest sample (latched when that sample enters the DFT).
// Start-up: the engine writes the carrier table to the DFT; the first
// write with `last` enables the ADC, whose first conversion is sample t = 0.
module dtmf_top #(
    parameter integer CLK_HZ = 18_000_000,
    parameter integer SAMPLE_HZ = 35_000,
    parameter integer BAUD = 3_000_000,
    parameter integer KS = 7,           // DFT channels: carriers (+ DC when demixing)
    parameter integer N = 32,           // DFT window
    parameter integer ACC_W = 18,       // 12 + 1 + log2 N: window sums never wrap
    parameter integer STEP = 35,        // samples per frame
    parameter integer IW = 11,          // microcode address bits
    parameter integer IMEM_WORDS = 1280, // microcode words (10 EBRs)
    parameter integer DW = 10,          // engine data words 2^DW
    parameter integer KW = 9,           // engine constant words 2^KW
    // 1: the engine's barrel shifter (frame_engine FAST_SHIFT): the same
    // packets in fewer clocks, for the larger FPGAs.
    parameter integer ENGINE_FAST_SHIFT = 0,
    // Output FIFO bytes (common/eskin/dtmf_top_plan.h: the plan's longest packet
    // fits whole; the engine drops, and counts, a packet without room).
    parameter integer OUT_DEPTH = 512,
    // The scene's microcode and constants ($readmemh files written by
    // ucode/dtmf_ucode.h's write_dtmf_top_build, e.g. through `eskin bitstream`).
    parameter UCODE_HEX = "",
    parameter KROM_HEX = "",
    // 0: this top owns the host link (link_framer -> uart_tx on uart_txd).
    // 1: it shares the link with another top (rtl/mixed_top.v): its packets
    // leave on pkt_* (whole packets, as link_framer takes them; uart_txd
    // idles high).
    parameter integer EXT_LINK = 0,
    // 1: a Hall top beside this one takes the commands 0x90-0x9F from the
    // same line (rtl/mixed_top.v): this top's decoder drops them, and keeps
    // every other type, so an unknown type is still rejected here, once.
    parameter integer HALL_CMDS = 0,
    // Parallel DFT lanes (rtl/sdft_lanes.v), 1..min(64, KS). A frame's
    // sample takes 6 KS + 2 clocks with 1 lane, 9 + (KS - 1) + max(0, 6 - L)
    // (ceil(KS / L) - 1) with L >= 2, KS + 8 from 6 lanes on (frame_capture
    // takes a token every clock; hls/sdft_bank.h's sdft_lanes_interval);
    // every other sample gives no tokens and takes 6 ceil(KS / L) + 2
    // (sdft_skip_interval). common/eskin/dtmf_top_plan.h's budget says when the
    // ADC keeps up. 1 on the UP5K.
    parameter integer SDFT_LANES = 1,
    // Samples the DFT's front FIFO holds (rtl/sdft_front.v): 0, none (the
    // ADC's output register alone, the lanes as before), or a power of two
    // up to 64, with which a frame's sample may hold the lanes for several
    // sample periods (common/eskin/dtmf_top_plan.h's budget: F < (FIFO + 2)
    // P); the flow gives 4 where the lanes alone cannot keep up.
    parameter integer SDFT_FIFO = 0,
    // 1: the hardware neuron unit (rtl/izhikevich_layer.v): the microcode
    // hands it each neuron update (13 clocks; 14 engine clocks a neuron
    // with level input, the spike test included, overlapped) instead of
    // running the izhikevich_layer routine (about 120 clocks with the
    // barrel shifter, 210 without); the same packets.
    // The board flow decides (host/fpga/board.h).
    parameter integer NEURON_UNIT = 0,
    // With NEURON_UNIT: 0, the engine keeps the neurons' state and drives
    // the one unit; 2..8, that many units that keep the state themselves
    // (rtl/izhikevich_lanes.v: the engine sends each neuron's x, 3 clocks
    // a neuron, and reads spike flags and events back), for the ECP5s.
    // NEURON_BITS: neuron index bits (2 T <= 2^NEURON_BITS), COLS: the
    // skin's columns (synapse_weights reads a taxel's column of 3 flags).
    parameter integer NEURON_LANES = 0,
    parameter integer NEURON_BITS = 11,
    parameter integer COLS = 32,
    // 0: the ADC runs on clk. Else the frequency of adc_clk, on which it
    // runs instead (its samples cross to clk in rtl/stream_cdc.v): the
    // AD7476A's SCLK ties a 1 MS/s ADC to 37.3-40 MHz (or 74.7-80), and
    // this frees the rest of the core from that band.
    parameter integer ADC_CLK_HZ = 0,
    // 1: the streaming datapath (rtl/dtmf_chain.v) does every frame's work
    // after the DFT, one element a clock, and the frame engine is its
    // control plane (the microcode built with STREAM: commands, the ghost
    // filter's pairing, AMPLITUDES, headers, status); the large FPGAs'
    // architecture (a plan's DtmfTopSpec::datapath; the board flow does not
    // choose it yet). KS = ROWS + COLS carriers,
    // no demixing (the plan's bin-centred carriers), no neuron unit (the
    // chain has its own layers). MAG_SHIFT and MAX_SPIKES: the chain's
    // (hls::DtmfChainSizes). 0: the frame engine alone.
    parameter integer STREAM = 0,
    parameter integer ROWS = 3,
    parameter integer MAG_SHIFT = 0,
    parameter integer MAX_SPIKES = 256
) (
    input  wire clk,
    input  wire adc_clk,     // ADC_CLK_HZ != 0: the ADC's clock (else unused)
    input  wire rst_n,       // active low (button); a power-on reset is built in
    output wire adc_cs_n,
    output wire adc_sclk,
    input  wire adc_sdata,
    output wire uart_txd,    // to the host
    input  wire uart_rxd,    // from the host
    output wire pkt_valid,   // EXT_LINK = 1: the packet stream (else 0)
    input  wire pkt_ready,
    output wire [7:0] pkt_data
);
  generate
    if (KS < 1 || KS > 128 || N < 2 || ACC_W < 14 || ACC_W > 32 || STEP < 1 ||
        OUT_DEPTH < 512 || OUT_DEPTH > 32768 || (OUT_DEPTH & (OUT_DEPTH - 1)) != 0 ||
        (EXT_LINK != 0 && EXT_LINK != 1) || (HALL_CMDS != 0 && HALL_CMDS != 1) ||
        (ENGINE_FAST_SHIFT != 0 && ENGINE_FAST_SHIFT != 1) ||
        SDFT_LANES < 1 || SDFT_LANES > 64 || SDFT_LANES > KS ||
        SDFT_FIFO < 0 || SDFT_FIFO > 64 || (SDFT_FIFO & (SDFT_FIFO - 1)) != 0 ||
        (NEURON_UNIT != 0 && NEURON_UNIT != 1) || ADC_CLK_HZ < 0 ||
        NEURON_BITS < 1 || NEURON_BITS > 30 ||
        // the lanes' flag address io_raddr[NEURON_BITS:0] must stay below
        // its select bit (IO_IZ_FLAG: bit 12), the events' below bit 13
        (NEURON_LANES != 0 && NEURON_BITS > 11) ||
        (NEURON_LANES != 0 && (NEURON_UNIT != 1 || NEURON_LANES < 2 || NEURON_LANES > 8)) ||
        (STREAM != 0 && STREAM != 1) ||
        (STREAM == 1 && (KS != ROWS + COLS || ROWS < 1 || ROWS > 255 || COLS < 1 ||
                         COLS > 255 || ROWS * COLS > 16383 || NEURON_UNIT != 0 ||
                         ACC_W > 24))) begin : g_bad_params
      dtmf_top_illegal_parameters u_stop ();  // no such module: stops elaboration
    end
  endgenerate

  // ---------------- reset: power-on counter and synchronised button -------
  wire rst;
  power_on_reset u_por (.clk(clk), .rst_n(rst_n), .rst(rst));

  // ---------------- frame engine IO bus ---------------------------------
  // Its addresses and event bits: generated from ucode/dtmf_io_map.h.
`include "dtmf_io_map.vh"
  wire [15:0] io_raddr, io_waddr;
  wire        io_re, io_we;
  wire [31:0] io_wdata;
  reg  [31:0] io_reg;
  reg         io_frame_q;   // the read went to the frame buffer
  reg         io_flag_q, io_ev_q;  // to the lanes' spike flags, events (NEURON_LANES)
  wire [31:0] cap_data;
  wire [2:0]  lane_flags;
  wire [NEURON_BITS-1:0] lane_ev;
  wire [15:0] mag_q;  // STREAM: the chain's magnitude at IO_FRAME + k (registered there)
  wire [31:0] io_rdata = io_ev_q ? {{(32 - NEURON_BITS){1'b0}}, lane_ev} :
                         io_flag_q ? {29'd0, lane_flags} :
                         io_frame_q ? (STREAM != 0 ? {16'd0, mag_q} : cap_data) : io_reg;
  wire        wr_out = io_we && io_waddr == IO_OUT_BYTE;
  wire        wr_word = io_we && io_waddr == IO_OUT_WORD;  // two bytes (below)
  wire        wr_done = io_we && io_waddr == IO_FRAME_DONE;
  wire        wr_pop = io_we && io_waddr == IO_CMD_POP;
  wire        wr_sdk = io_we && io_waddr == IO_SDFT_K;
  wire        wr_sdinc = io_we && io_waddr == IO_SDFT_INC;
  wire        wr_clear = io_we && io_waddr == IO_CLEAR;
  wire        wr_iz_x = io_we && io_waddr == IO_IZ_X;
  wire        wr_iz_go = io_we && io_waddr == IO_IZ_GO;  // the x_prev operand
  wire        wr_iz_ugo = io_we && io_waddr == IO_IZ_UGO; // the U operand; starts (level input)
  wire        wr_iz_v = io_we && io_waddr == IO_IZ_V;
  wire        wr_iz_u = io_we && io_waddr == IO_IZ_U;
  wire        wr_iz_cfg = io_we && io_waddr[15:5] == IO_IZ_CFG[15:5];  // IO_IZ_CFG + word
  wire        wr_iz_n = io_we && io_waddr == IO_IZ_N;   // lanes: the next neuron
  wire        wr_iz_xgo = io_we && io_waddr == IO_IZ_XGO; // lanes: its x; starts it
  wire        wr_iz_sv = io_we && io_waddr == IO_IZ_SV;  // lanes: v of an initialisation
  wire        wr_iz_su = io_we && io_waddr == IO_IZ_SU;  // lanes: U; initialises

  // ---------------- carrier table writes to the DFT ---------------------
  reg [7:0]  cfg_k;
  reg        cfg_last, cfg_valid;
  reg [31:0] cfg_inc;
  reg        adc_en;
  wire       cfg_ready;
  wire       cfg_done = cfg_valid && cfg_ready && cfg_last;  // window cleared
  always @(posedge clk) begin
    if (rst) begin
      cfg_k <= 8'd0;
      cfg_last <= 1'b0;
      cfg_valid <= 1'b0;
      cfg_inc <= 32'd0;
      adc_en <= 1'b0;
    end else begin
      if (wr_sdk) {cfg_last, cfg_k} <= io_wdata[8:0];
      if (wr_sdinc) begin
        cfg_inc <= io_wdata;
        cfg_valid <= 1'b1;
      end else if (cfg_ready) begin
        cfg_valid <= 1'b0;
      end
      if (cfg_done) adc_en <= 1'b1;
    end
  end

  // ---------------- ADC ------------------------------------------------
  // On clk (ADC_CLK_HZ = 0), or on adc_clk, its samples carried into clk's
  // domain by stream_cdc with their index and the overrun count (the count
  // the engine reads is the one the latest sample brought: CLEAR_COUNTERS
  // reaches it with the next sample, a microsecond at 1 MS/s). rst and
  // adc_en reach the ADC through two adc_clk flip-flops (rst through a
  // power_on_reset of adc_clk, which also holds the ADC from configuration
  // on), wr_clear as a toggle. The ADC's own output register, s_hold and
  // m_data hold a sample each, so the DFT may take one later than with the
  // ADC on clk (common/eskin/dtmf_top_plan.h's budget assumes the one register of
  // that case).
  wire adc_valid, sdft_in_ready;
  wire [11:0] adc_code;
  wire [31:0] adc_t;
  wire [15:0] adc_overruns;
  // SCLK = ADC clock / (2 SCLK_DIV) at most 20 MHz (AD7476A): 9 MHz at 18 MHz.
  localparam integer ADC_HZ = ADC_CLK_HZ != 0 ? ADC_CLK_HZ : CLK_HZ;
  localparam integer SCLK_DIV = (ADC_HZ + 39_999_999) / 40_000_000;
  generate
    if (ADC_CLK_HZ == 0) begin : g_adc_on_clk
      adc_ad7476 #(.CLK_HZ(CLK_HZ), .SAMPLE_HZ(SAMPLE_HZ), .SCLK_DIV(SCLK_DIV), .NCH(1)) u_adc (
          .clk(clk), .rst(rst), .en(adc_en), .cs_n(adc_cs_n), .sclk(adc_sclk),
          .sdata(adc_sdata), .m_valid(adc_valid), .m_ready(sdft_in_ready),
          .m_data(adc_code), .m_t(adc_t), .overruns(adc_overruns), .clear(wr_clear));
      wire unused_adc_clk = adc_clk;
    end else begin : g_adc_clock
      reg clear_tgl;  // flips on every wr_clear
      always @(posedge clk) begin
        if (rst) clear_tgl <= 1'b0;
        else if (wr_clear) clear_tgl <= !clear_tgl;
      end
      // The ADC side's reset: from configuration on (its own power-on
      // count) and while rst is high, through two adc_clk flip-flops.
      wire a_rst;
      power_on_reset u_adc_por (.clk(adc_clk), .rst_n(!rst), .rst(a_rst));
      wire p_adc_rst /* verilator public_flat_rd */ = a_rst;  // probe (tests)
      (* ASYNC_REG = "TRUE" *) reg [1:0] a_en_q;
      (* ASYNC_REG = "TRUE" *) reg [2:0] a_clear_q;
      always @(posedge adc_clk) begin
        a_en_q <= {a_en_q[0], adc_en};
        a_clear_q <= {a_clear_q[1:0], clear_tgl};
      end
      wire a_valid, a_ready;
      wire [11:0] a_code;
      wire [31:0] a_t;
      wire [15:0] a_overruns;
      adc_ad7476 #(.CLK_HZ(ADC_CLK_HZ), .SAMPLE_HZ(SAMPLE_HZ), .SCLK_DIV(SCLK_DIV), .NCH(1)) u_adc (
          .clk(adc_clk), .rst(a_rst), .en(a_en_q[1]), .cs_n(adc_cs_n), .sclk(adc_sclk),
          .sdata(adc_sdata), .m_valid(a_valid), .m_ready(a_ready), .m_data(a_code), .m_t(a_t),
          .overruns(a_overruns), .clear(a_clear_q[2] != a_clear_q[1]));
      stream_cdc #(.W(60)) u_cdc (
          .s_clk(adc_clk), .s_rst(a_rst), .s_valid(a_valid), .s_ready(a_ready),
          .s_data({a_overruns, a_t, a_code}), .m_clk(clk), .m_rst(rst), .m_valid(adc_valid),
          .m_ready(sdft_in_ready), .m_data({adc_overruns, adc_t, adc_code}));
    end
  endgenerate

  // ---------------- sliding DFT and frame capture -----------------------
  // sdft_front: the sample FIFO (SDFT_FIFO samples; none: the ADC's sample
  // straight into the lanes, clock for clock as sdft_lanes alone) and the
  // lanes. A sample's tag is its ADC counter, so frame_capture dates a
  // frame by the sample that enters the DFT, however long it queued.
  wire [11:0] x = {~adc_code[11], adc_code[10:0]};  // code - 2048
  wire sdft_fire;  // a sample enters the lanes
  wire [31:0] sdft_t;
  wire sd_valid, sd_last, sd_ready;
  wire smp_frame;  // frame_capture: the sample entering now is a frame
  wire [7:0] sd_k;
  wire [ACC_W-1:0] sd_re, sd_im;
  /* verilator lint_off PINCONNECTEMPTY */
  sdft_front #(.K_MAX(KS), .N(N), .XW(12), .CW(16), .TW(10), .ACC_W(ACC_W), .K_W(8),
               .LANES(SDFT_LANES), .DEPTH(SDFT_FIFO), .TAG_W(32)) u_sdft (
      .clk(clk), .rst(rst), .s_valid(adc_valid), .s_ready(sdft_in_ready), .s_x(x), .s_t(adc_t),
      .dft_fire(sdft_fire), .dft_t(sdft_t), .dft_skip(!smp_frame), .backlog(),
      .cfg_valid(cfg_valid), .cfg_ready(cfg_ready), .cfg_k(cfg_k),
      .cfg_inc(cfg_inc), .cfg_last(cfg_last), .out_valid(sd_valid), .out_ready(sd_ready),
      .out_k(sd_k), .out_re(sd_re), .out_im(sd_im), .out_last(sd_last));
  /* verilator lint_on PINCONNECTEMPTY */
  wire frame_pending;  // the engine's frame event
  wire [31:0] frame_t;  // IO_FRAME_T
  wire cap_pending;
  wire [31:0] cap_t;
  wire [15:0] frame_overruns;
  // STREAM: the tokens go to the chain, and the capture only counts them
  // (those the chain takes) to date each frame: done held high, `pending`
  // is one clock after each frame's last token and frame_t its t (its
  // buffer, never read, goes in synthesis).
  wire ch_in_ready;
  wire cap_tok_ready;
  wire cap_done = STREAM != 0 ? 1'b1 : wr_done;
  assign sd_ready = STREAM != 0 ? ch_in_ready : cap_tok_ready;
  frame_capture #(.KS(KS), .W(ACC_W), .N(N), .STEP(STEP)) u_cap (
      .clk(clk), .rst(rst), .clr(cfg_done), .smp_fire(sdft_fire), .smp_t(sdft_t),
      .smp_frame(smp_frame), .tok_valid(sd_valid && sd_ready), .tok_ready(cap_tok_ready),
      .tok_last(sd_last),
      .tok_re(sd_re), .tok_im(sd_im), .rd_addr(io_raddr[7:0]), .rd_data(cap_data),
      .pending(cap_pending), .frame_t(cap_t), .done(cap_done), .clear(wr_clear),
      .overruns(frame_overruns));
  /* verilator lint_off UNUSEDSIGNAL */
  wire [7:0] sd_k_unused = sd_k;  // tokens arrive in k order; capture counts them
  /* verilator lint_on UNUSEDSIGNAL */

  // ---------------- host link: commands in ------------------------------
  wire rx_valid, rx_frame_err, rx_overrun;
  wire [7:0] rx_data;
  uart_rx #(.CLK_HZ(CLK_HZ), .BAUD(BAUD)) u_rx (
      .clk(clk), .rst(rst), .rx(uart_rxd), .m_valid(rx_valid), .m_ready(1'b1),
      .m_data(rx_data), .frame_err(rx_frame_err), .overrun(rx_overrun));
  reg [15:0] rx_errors;
  always @(posedge clk) begin
    if (rst || wr_clear) rx_errors <= 16'd0;
    else if ((rx_frame_err || rx_overrun) && rx_errors != 16'hFFFF) rx_errors <= rx_errors + 16'd1;
  end
  wire cmd_avail;
  wire [7:0] cmd_head;
  wire [15:0] cmd_crc_errors, cmd_frame_errors, cmd_overflows;
  /* verilator lint_off PINCONNECTEMPTY */
  // Every command type, or all but the Hall top's beside it.
  cmd_decoder #(.DEPTH(512), .TYPE_LO(HALL_CMDS != 0 ? 8'h90 : 8'h00),
                .TYPE_HI(HALL_CMDS != 0 ? 8'h9F : 8'hFF), .TYPE_IN(HALL_CMDS != 0 ? 0 : 1)) u_cmd (
      .clk(clk), .rst(rst), .s_valid(rx_valid), .s_ready(), .s_data(rx_data),
      .rx_error(rx_frame_err || rx_overrun), .avail(cmd_avail), .head(cmd_head),
      .pop(wr_pop), .clear(wr_clear), .crc_errors(cmd_crc_errors),
      .frame_errors(cmd_frame_errors), .overflows(cmd_overflows));
  /* verilator lint_on PINCONNECTEMPTY */

  // ---------------- packets out -----------------------------------------
  wire fifo_valid, fifo_ready;
  wire [7:0] fifo_data;
  wire [15:0] out_free, out_overflows;
  // IO_OUT_WORD writes bits 7:0 now and bits 15:8 from word_hi in the next
  // clock, which the microcode leaves free (hls::OutFifoPort checks that in
  // every microcode test): the FIFO keeps its one write port, and a 16-bit
  // field costs the engine one `out` instead of out, shr 8, out.
  reg        word_held;
  reg  [7:0] word_hi;
  always @(posedge clk) begin
    word_held <= !rst && wr_word;
    if (wr_word) word_hi <= io_wdata[15:8];
  end
`ifndef SYNTHESIS
  // The microcode's contracts with the top's ports, checked in simulation
  // (Verilator --assert, every build of a top) as the C++ port models
  // (ucode/engine_ports.h, ucode/dtmf_top_bus.h) check them in the
  // microcode tests: the word's second byte has the FIFO's write port to
  // itself; a DFT carrier exists.
  always @(posedge clk)
    if (!rst) begin
      if (word_held)
        assert (!wr_out && !wr_word)
        else $error("dtmf_top: the microcode wrote the output FIFO in the clock after an IO_OUT_WORD write, which writes that word's second byte");
      if (wr_sdinc)
        assert ({24'd0, cfg_k} < KS)
        else $error("dtmf_top: the microcode wrote DFT carrier %0d; the build has %0d", cfg_k, KS);
    end
`endif
  wire       fifo_in_valid = wr_out || wr_word || word_held;
  wire [7:0] fifo_in_data = word_held ? word_hi : io_wdata[7:0];
  // The engine's packets; STREAM: beside the chain's, both onto the link
  // whole packets at a time (below).
  wire eo_valid, eo_ready;
  wire [7:0] eo_data;
  byte_fifo #(.DEPTH(OUT_DEPTH)) u_out (
      .clk(clk), .rst(rst), .in_valid(fifo_in_valid), .in_data(fifo_in_data),
      .out_valid(eo_valid), .out_ready(eo_ready), .out_data(eo_data), .free(out_free),
      .overflows(out_overflows));

  // ---------------- the streaming datapath (STREAM) ----------------------
  // rtl/dtmf_chain.v takes the DFT's tokens (sign-extended to the kernel's
  // 24 bits) and sends TAXELS and SPIKES into a FIFO of its own; the
  // engine, its control plane, reads each frame's K magnitudes at
  // IO_FRAME + k once they are there (EV_FRAME_PENDING), runs the ghost
  // filter's pairing (IO_SITE for each site it adds: the chain clears the
  // released ones itself), sends AMPLITUDES and status into its FIFO and
  // writes IO_HEADER: sites done, and the frame's packets. The chain's
  // configuration comes from the engine's registers (IO_RECIP, IO_GHOST,
  // IO_SPARSE_MIN, IO_NEURONS, IO_WEIGHT, IO_IZ_CFG / IO_IZ_CFG1).
  // Frame tags: the capture's t of each frame the chain took, queued (a
  // few frames may be in the chain's magnitude pipeline at once) until
  // the engine's header takes the oldest.
  wire [31:0] spk_drop;       // the chain's spike events dropped (saturating)
  wire        frame_done;     // a frame's work handed back (the header, or IO_FRAME_DONE)
  reg  [15:0] ch_pkt_drops;   // its packets dropped for room (saturating)
  wire        stream_busy;    // IO_STREAM_BUSY: the layers initialising or holding a frame's work
  generate
    if (STREAM != 0) begin : g_stream
      localparam integer KA = (KS > 1) ? $clog2(KS) : 1;
      localparam integer T = ROWS * COLS;
      localparam integer MA = (T > 1) ? $clog2(T) : 1;
      wire wr_site = io_we && io_waddr == IO_SITE;
      wire wr_site_clr = io_we && io_waddr == IO_SITE_CLR;
      wire wr_hdr = io_we && io_waddr == IO_HEADER;
      wire wr_recip = io_we && io_waddr == IO_RECIP;
      wire wr_ghost = io_we && io_waddr == IO_GHOST;
      wire wr_smin = io_we && io_waddr == IO_SPARSE_MIN;
      wire wr_neurons = io_we && io_waddr == IO_NEURONS;
      wire wr_weight = io_we && io_waddr[15:4] == IO_WEIGHT[15:4] && io_waddr[3:0] < 4'd9;
      wire wr_cfg1 = io_we && io_waddr[15:5] == IO_IZ_CFG1[15:5];
      reg [14:0] c_recip;
      reg [4:0]  c_rshift;
      reg        c_ghost, c_neurons;
      reg [15:0] c_release, c_smin;
      reg [143:0] c_w;
      reg        nu_init_q;
      always @(posedge clk) begin
        if (rst) begin
          c_recip <= 15'd1;
          c_rshift <= 5'd0;
          c_ghost <= 1'b0;
          c_release <= 16'd0;
          c_smin <= 16'd0;
          c_neurons <= 1'b0;
          c_w <= 144'd0;
          nu_init_q <= 1'b0;
        end else begin
          if (wr_recip) {c_rshift, c_recip} <= {io_wdata[20:16], io_wdata[14:0]};
          if (wr_ghost) {c_ghost, c_release} <= io_wdata[16:0];
          if (wr_smin) c_smin <= io_wdata[15:0];
          if (wr_neurons) c_neurons <= io_wdata[0];
          nu_init_q <= wr_neurons && io_wdata[1];
          if (wr_weight) c_w[16 * io_waddr[3:0] +: 16] <= io_wdata[15:0];
        end
      end
      // Frame tags.
      reg [31:0] tq [0:7];
      reg [2:0]  tq_w, tq_r;
      reg [3:0]  tq_n;
      reg [31:0] hdr_t;
      reg        hdr_valid;
      reg [3:0]  hdr_bits;
      wire       hdr_ready;
      always @(posedge clk) begin
        if (cap_pending) tq[tq_w] <= cap_t;
        if (rst) begin
          tq_w <= 3'd0;
          tq_r <= 3'd0;
          tq_n <= 4'd0;
          hdr_valid <= 1'b0;
          hdr_bits <= 4'd0;
          hdr_t <= 32'd0;
        end else begin
          tq_w <= tq_w + {2'd0, cap_pending};
          tq_r <= tq_r + {2'd0, wr_hdr};
          tq_n <= tq_n + {3'd0, cap_pending} - {3'd0, wr_hdr};
          if (wr_hdr) begin
            hdr_valid <= 1'b1;
            hdr_bits <= io_wdata[3:0];
            hdr_t <= tq[tq_r];
          end else if (hdr_ready) begin
            hdr_valid <= 1'b0;
          end
        end
      end
      // A frame waits for the engine from its magnitudes (mag_ready) until
      // its header; mag_ready stays high until the frame's last taxel.
      wire mag_ready, layers_idle, nu_busy;
      reg  mag_ready_q, sites_given;
      always @(posedge clk) begin
        mag_ready_q <= !rst && mag_ready;
        if (rst || (mag_ready_q && !mag_ready)) sites_given <= 1'b0;
        else if (wr_hdr) sites_given <= 1'b1;
      end
      assign frame_pending = mag_ready && !sites_given && tq_n != 4'd0;
      assign frame_done = wr_hdr;
      assign frame_t = tq[tq_r];
      // The chain's FIFO and its packets onto the link with the engine's.
      wire co_in_valid, co_in_ready, co_valid, co_ready, ch_dropped;
      wire [7:0] co_in_data, co_data;
      wire [15:0] co_free;
      /* verilator lint_off PINCONNECTEMPTY */
      dtmf_chain #(.R(ROWS), .C(COLS), .ACC_W(24), .MAG_SHIFT(MAG_SHIFT),
                   .MAX_SPIKES(MAX_SPIKES), .KA(KA), .MA(MA)) u_chain (
          .clk(clk), .rst(rst), .cfg_recip(c_recip), .cfg_recip_shift(c_rshift),
          .cfg_ghost(c_ghost), .cfg_release(c_release), .cfg_neurons(c_neurons), .cfg_w(c_w),
          .nu_cfg_we({wr_cfg1, wr_iz_cfg}), .nu_cfg_addr(io_waddr[4:0]), .nu_cfg_data(io_wdata),
          .nu_init(nu_init_q), .nu_busy(nu_busy),
          .in_valid(sd_valid), .in_ready(ch_in_ready), .in_k(sd_k),
          .in_re(24'($signed(sd_re))), .in_im(24'($signed(sd_im))), .in_last(sd_last),
          .mag_ready(mag_ready), .mag_raddr(io_raddr[KA-1:0]), .mag_rdata(mag_q),
          .mask_we(wr_site || wr_site_clr), .mask_addr(io_wdata[MA-1:0]), .mask_din(wr_site),
          .sites_done(wr_hdr), .hdr_valid(hdr_valid), .hdr_ready(hdr_ready), .hdr_t(hdr_t),
          .hdr_dense(hdr_bits[0]), .hdr_sparse(hdr_bits[1]), .hdr_sparse_min(c_smin),
          .hdr_spikes(hdr_bits[2]), .hdr_close(hdr_bits[3]), .out_free(co_free),
          .out_valid(co_in_valid), .out_ready(co_in_ready), .out_data(co_in_data),
          .dropped(ch_dropped), .spikes_dropped(spk_drop), .drops_clear(wr_clear), .tax_valid(),
          .tax_site(), .idle(), .layers_idle(layers_idle));
      assign stream_busy = nu_busy || !layers_idle;
      byte_fifo #(.DEPTH(OUT_DEPTH)) u_chain_out (
          .clk(clk), .rst(rst), .in_valid(co_in_valid), .in_data(co_in_data),
          .out_valid(co_valid), .out_ready(co_ready), .out_data(co_data), .free(co_free),
          .overflows());
      /* verilator lint_on PINCONNECTEMPTY */
      assign co_in_ready = 1'b1;  // the chain sends a packet only with room for it
      packet_arbiter #(.NS(2)) u_arb (
          .clk(clk), .rst(rst), .s_valid({co_valid, eo_valid}), .s_ready({co_ready, eo_ready}),
          .s_data({co_data, eo_data}), .m_valid(fifo_valid), .m_ready(fifo_ready),
          .m_data(fifo_data));
      always @(posedge clk) begin
        if (rst || wr_clear) ch_pkt_drops <= 16'd0;
        else if (ch_dropped && ch_pkt_drops != 16'hFFFF) ch_pkt_drops <= ch_pkt_drops + 16'd1;
      end
`ifndef SYNTHESIS
      // The control plane's contracts with the chain: a header only for a
      // frame whose magnitudes wait and whose tag is queued, and never
      // over one the chain has not taken; no frame tag lost; magnitudes
      // read only while they are the frame's; a site only before the
      // frame's header (the chain checks that no mask write, a clear
      // included, falls in its taxel phase).
      always @(posedge clk)
        if (!rst) begin
          if (wr_hdr)
            assert (frame_pending && !hdr_valid)
            else $error("dtmf_top: the microcode wrote a frame header with no frame waiting for one (or over the last header)");
          if (cap_pending)
            assert (tq_n != 4'd8)
            else $error("dtmf_top: a ninth frame tag with eight waiting for their headers");
          if (io_re && !io_raddr[9])
            assert (frame_pending)
            else $error("dtmf_top: the microcode read magnitude %0d with no frame's magnitudes waiting", io_raddr[KA-1:0]);
          if (wr_iz_cfg || wr_cfg1 || wr_weight)
            assert (layers_idle)
            else $error("dtmf_top: the microcode wrote a neuron constant or a weight while the chain's layers held a frame's work");
          if (wr_site)  // (clears: at boot, before any frame)
            assert (frame_pending)
            else $error("dtmf_top: the microcode wrote a site outside a frame's control step");
          if (wr_site || wr_site_clr)
            assert (io_wdata < 32'(T))
            else $error("dtmf_top: the microcode wrote site %0d of %0d taxels", io_wdata, T);
        end
`endif
    end else begin : g_engine
      assign frame_pending = cap_pending;
      assign frame_t = cap_t;
      assign frame_done = wr_done;
      assign fifo_valid = eo_valid;
      assign fifo_data = eo_data;
      assign eo_ready = fifo_ready;
      assign mag_q = 16'd0;
      assign spk_drop = 32'd0;
      assign stream_busy = 1'b0;
      always @(posedge clk) ch_pkt_drops <= 16'd0;
      assign ch_in_ready = 1'b0;
      wire unused_stream = ^{IO_SITE, IO_SITE_CLR, IO_HEADER, IO_RECIP, IO_GHOST, IO_SPARSE_MIN,
                             IO_NEURONS, IO_WEIGHT, IO_IZ_CFG1};
    end
  endgenerate
  wire [7:0] link_seq;
  wire       link_fire;  // a framed byte goes to the UART (own link only)
  generate
    if (EXT_LINK == 0) begin : g_link
      wire fr_valid, fr_ready;
      wire [7:0] fr_data;
      link_framer u_framer (
          .clk(clk), .rst(rst), .s_valid(fifo_valid), .s_ready(fifo_ready), .s_data(fifo_data),
          .m_valid(fr_valid), .m_ready(fr_ready), .m_data(fr_data), .seq(link_seq));
      uart_tx #(.CLK_HZ(CLK_HZ), .BAUD(BAUD)) u_tx (
          .clk(clk), .rst(rst), .s_valid(fr_valid), .s_ready(fr_ready), .s_data(fr_data),
          .tx(uart_txd));
      assign link_fire = fr_valid && fr_ready;
      assign pkt_valid = 1'b0;
      assign pkt_data = 8'd0;
      wire unused_pkt = &{1'b0, pkt_ready};
    end else begin : g_ext_link
      assign pkt_valid = fifo_valid;
      assign pkt_data = fifo_data;
      assign fifo_ready = pkt_ready;
      assign uart_txd = 1'b1;
      assign link_seq = 8'd0;  // the shared link_framer counts
      assign link_fire = 1'b0;
    end
  endgenerate

  // ---------------- the neuron unit (NEURON_UNIT) ------------------------
  // Operands are written one by one (x, v, U); the x_prev write hands all
  // four over and starts the update; or, for a level input (no
  // input_change: the unit reads no x_prev), the U write (0x208) starts
  // it at the next edge, once U is in its register (no U and x_prev
  // multiplexers: they cost the UP5K's 8x8 build about 50 cells, which it
  // does not have; x_prev is then the bus's next word, unused). The
  // microcode waits for iz_done (or counts the unit's clocks) before it
  // starts the next, so in_ready is always 1 at the start, and reads a
  // neuron's results while the next one runs (the unit shows them until
  // the next one's replace them). The microcode keeps x_prev itself.
  wire        iz_done, iz_spike;
  wire [31:0] iz_v, iz_u;
  wire [NEURON_BITS:0] lane_ev_count;
  generate
    if (NEURON_LANES != 0) begin : g_neuron_lanes
      // The lanes keep the state; iz_done: every update written back.
      izhikevich_lanes #(.LANES(NEURON_LANES), .NB(NEURON_BITS), .COLS(COLS)) u_lanes (
          .clk(clk), .rst(rst), .cfg_we(wr_iz_cfg), .cfg_addr(io_waddr[4:0]), .idx_we(wr_iz_n),
          .x_we(wr_iz_xgo), .sv_we(wr_iz_sv), .su_we(wr_iz_su), .data(io_wdata),
          .flag_addr(io_raddr[NEURON_BITS:0]),
          .flag_q(lane_flags), .ev_addr(io_raddr[NEURON_BITS-1:0]), .ev_q(lane_ev),
          .ev_count(lane_ev_count), .idle(iz_done));
      assign iz_spike = 1'b0;
      assign iz_v = 32'd0;
      assign iz_u = 32'd0;
      wire unused_lanes = ^{wr_iz_x, wr_iz_go, wr_iz_ugo, wr_iz_v, wr_iz_u};
`ifndef SYNTHESIS
      // Reads of the lanes (hls::IzhikevichLanesPort's checks): the events
      // only once every update is written back, and only those there are;
      // no spike flag in the clock that writes it (the block RAM's read
      // during write is undefined). A flag read at f covers neurons f,
      // f - COLS and f - 2 COLS: the three copies' write addresses.
      wire rd_ev = io_re && io_raddr[15:12] == IO_IZ_EV[15:12];
      wire rd_evn = io_re && io_raddr == IO_IZ_EVN;
      wire rd_flag = io_re && io_raddr[15:12] == IO_IZ_FLAG[15:12];
      wire [NEURON_BITS:0] fa = io_raddr[NEURON_BITS:0];
      always @(posedge clk)
        if (!rst) begin
          if (rd_ev || rd_evn)
            assert (iz_done)
            else $error("dtmf_top: the microcode read the spike events (address %h) while the neuron lanes ran", io_raddr);
          if (rd_ev && iz_done)
            assert ({8'd0, io_raddr[11:0]} < {{(19 - NEURON_BITS){1'b0}}, lane_ev_count})
            else $error("dtmf_top: the microcode read spike event %0d of %0d", io_raddr[11:0], lane_ev_count);
          if (rd_flag && u_lanes.st_we)
            assert (fa != u_lanes.fl_a0 && fa != u_lanes.fl_a1 && fa != u_lanes.fl_a2)
            else $error("dtmf_top: the microcode read neuron %0d's spike flag in the clock that writes it", u_lanes.wb_n);
        end
`endif
    end else if (NEURON_UNIT != 0) begin : g_neuron_unit
      reg [31:0] op_x, op_v, op_u;
      reg        ugo_q;  // a U write of the clock before: start
      always @(posedge clk) begin
        if (wr_iz_x) op_x <= io_wdata;
        if (wr_iz_v) op_v <= io_wdata;
        if (wr_iz_u || wr_iz_ugo) op_u <= io_wdata;
        ugo_q <= wr_iz_ugo && !rst;
      end
      wire in_ready_unused;
      izhikevich_layer u_neuron (
          .clk(clk), .rst(rst), .cfg_we(wr_iz_cfg), .cfg_addr(io_waddr[4:0]),
          .cfg_data(io_wdata), .in_valid(wr_iz_go || ugo_q), .in_ready(in_ready_unused),
          .in_x(op_x), .in_x_prev(io_wdata), .in_v(op_v), .in_u(op_u),
          .out_valid(iz_done), .out_spike(iz_spike), .out_v(iz_v), .out_u(iz_u));
      wire unused_neuron = in_ready_unused;
`ifndef SYNTHESIS
      // The unit ignores a start while busy, and the U write's start has no
      // x_prev (hls::IzhikevichUnitPort's checks); its constant words are
      // checked by izhikevich_layer itself.
      always @(posedge clk)
        if (!rst) begin
          if (wr_iz_go || ugo_q)
            assert (in_ready_unused)
            else $error("dtmf_top: the microcode started the neuron unit while it ran (the unit ignores that start)");
          if (wr_iz_ugo)
            assert (!u_neuron.c_ic)
            else $error("dtmf_top: the microcode started the neuron unit by its U write with input_change set: that start has no x_prev");
        end
`endif
    end else begin : g_no_neuron_unit
      assign iz_done = 1'b0;
      assign iz_spike = 1'b0;
      assign iz_v = 32'd0;
      assign iz_u = 32'd0;
      wire unused_neuron = ^{wr_iz_x, wr_iz_go, wr_iz_ugo, wr_iz_v, wr_iz_u, wr_iz_cfg};
    end
    if (NEURON_LANES == 0) begin : g_no_lanes
      assign lane_flags = 3'd0;
      assign lane_ev = {NEURON_BITS{1'b0}};
      assign lane_ev_count = {(NEURON_BITS + 1){1'b0}};
      wire unused_lane_ports = ^{wr_iz_n, wr_iz_xgo, wr_iz_sv, wr_iz_su};
    end
  endgenerate

  // ---------------- the frame engine -------------------------------------
  // The `wait` mask bits, in the order of the generated map's EV_*_BIT
  // (ucode/dtmf_io_map.h): a map that moves them stops elaboration, so the
  // concatenation cannot drift from it. (A concatenation: the same wiring
  // written as shifts by EV_*_BIT maps to a few more LUTs under abc9.)
  wire [15:0] events = {13'd0, iz_done, cmd_avail, frame_pending};
  generate
    if (EV_FRAME_PENDING_BIT != 0 || EV_CMD_AVAIL_BIT != 1 || EV_IZ_DONE_BIT != 2) begin : g_bad_events
      dtmf_top_illegal_event_bits u_stop ();  // no such module: stops elaboration
    end
  endgenerate
  frame_engine #(.IW(IW), .IMEM_WORDS(IMEM_WORDS), .DW(DW), .KW(KW), .UCODE_HEX(UCODE_HEX),
                 .KROM_HEX(KROM_HEX), .FAST_SHIFT(ENGINE_FAST_SHIFT)) u_eng (
      .clk(clk), .rst(rst), .io_raddr(io_raddr), .io_re(io_re), .io_waddr(io_waddr), .io_rdata(io_rdata),
      .io_we(io_we), .io_wdata(io_wdata), .events(events));

  // Registered reads (the engine samples one clock after io_re). Reads have
  // no side effects, so the register loads every clock (no enable from the
  // engine's decode), and the address is decoded partially: bit 9 picks
  // the frame buffer (0x000-0x0FF) or the registers (0x200-0x20F, bits
  // 3:0); the microcode uses only these addresses (ucode/dtmf_engine_image.h).
  // Both keep the path IMEM -> ea adder -> this register short.
  // With lanes, bit 13 picks an event and bit 12 a spike flag (0x1000 +
  // flag address; 0x2000 + event).
  localparam LANES_ON = NEURON_LANES != 0;
  always @(posedge clk) begin
    io_ev_q <= LANES_ON && io_raddr[13];
    io_flag_q <= LANES_ON && !io_raddr[13] && io_raddr[12];
    io_frame_q <= !io_raddr[9];
    case (io_raddr[3:0])
      IO_FRAME_T[3:0]: io_reg <= frame_t;
      IO_STATUS[3:0]: io_reg <= {30'd0, cmd_avail, frame_pending};
      IO_CMD[3:0]: io_reg <= {24'd0, cmd_head};
      IO_OUT_FREE[3:0]: io_reg <= {16'd0, out_free};
      IO_ADC_T[3:0]: io_reg <= adc_t;
      IO_ADC_OVR[3:0]: io_reg <= {16'd0, adc_overruns};
      IO_RX_ERR[3:0]: io_reg <= {16'd0, rx_errors};
      IO_CRC_ERR[3:0]: io_reg <= {16'd0, cmd_crc_errors};
      IO_FRM_ERR[3:0]: io_reg <= {16'd0, cmd_frame_errors};
      IO_FRAME_OVR[3:0]: io_reg <= {16'd0, frame_overruns};
      IO_SDFT_BUSY[3:0]: io_reg <= {31'd0, cfg_valid};
      IO_CMD_OVF[3:0]: io_reg <= {16'd0, cmd_overflows};
      IO_IZ_SPIKE[3:0]: io_reg <= {31'd0, iz_spike};
      IO_IZ_V[3:0]: io_reg <= iz_v;
      IO_IZ_U[3:0]: io_reg <= iz_u;
      default: io_reg <= {{(31 - NEURON_BITS){1'b0}}, lane_ev_count};  // IO_IZ_EVN: lanes' events
    endcase
    // STREAM: the chain's registers at 0x210-0x212 (bit 4).
    if (STREAM != 0 && io_raddr[4])
      case (io_raddr[1:0])
        IO_SPK_DROP[1:0]: io_reg <= spk_drop;
        IO_PKT_DROP[1:0]: io_reg <= {16'd0, ch_pkt_drops};
        default: io_reg <= {31'd0, stream_busy};  // IO_STREAM_BUSY
      endcase
  end
  wire unused_io = ^{io_re, io_raddr[15:10], io_raddr[8]};  // partial decode

  // ---------------- probes (tests and latency benchmarks) ---------------
  wire p_cfg_done /* verilator public_flat_rd */ = cfg_done;
  wire p_adc_fire /* verilator public_flat_rd */ = sdft_fire;
  wire [31:0] p_adc_t /* verilator public_flat_rd */ = sdft_t;  // the tag of the sample p_adc_fire takes
  wire p_sd_fire /* verilator public_flat_rd */ = sd_valid && sd_ready;
  wire p_sd_last /* verilator public_flat_rd */ = sd_last;
  wire p_frame_fire /* verilator public_flat_rd */ = frame_pending;
  wire [31:0] p_frame_t /* verilator public_flat_rd */ = frame_t;
  wire p_frame_done /* verilator public_flat_rd */ = frame_done;
  wire p_out_fire /* verilator public_flat_rd */ = wr_out || wr_word;
  wire [15:0] p_out_overflows /* verilator public_flat_rd */ = out_overflows;
  wire p_fr_fire /* verilator public_flat_rd */ = link_fire;
  wire [7:0] p_seq /* verilator public_flat_rd */ = link_seq;
  wire p_rst /* verilator public_flat_rd */ = rst;
endmodule
`default_nettype wire
