// dtmf_top: the FPGA top of the DTMF (spatial-frequency) skin path.
//
//   AD7476A --SPI--> adc_ad7476 -> x = code - 2048 -> sdft_bank (K = R + C
//   carriers, window N) -> step gate (every STEP-th sample) ->
//   carrier_magnitude -> taxel_reconstruct (R x C, conductance g, UQ1.15) ->
//   izhikevich_layer (one RA neuron per taxel) -> frame_packetizer ->
//   link_framer -> uart_tx --> host;   host --> uart_rx -> cmd_decoder
//   (output mask, decimations, status requests; carriers if CARRIER_CMD).
// TOKEN_FIFO > 0 inserts a frame buffer (token_fifo) after the step gate,
// for skins whose K * 26 magnitude cycles exceed a sample period (16x16).
// Default parameters: the default scene (scenes/neuroskin2.yaml, 3x3) on an
// iCE40 UP5K at 12 MHz (docs/fpga.md: build, figures, latency table).
//
// The bit-exact spec of the whole path, down to the packet payloads, is
// hls/dtmf_chain.h; tests/rtl/dtmf_top_test.cpp compares them byte for byte.
//
// Sample format: the AD7476A gives 12-bit codes; a 10-bit scene code c10 is
// seen as c10 << 2 (left aligned). x = code - 2048 (XW-bit signed). The
// magnitude shift MAG_SHIFT = 2 undoes the left alignment: mag is the
// window-sum magnitude in 10-bit code units (max N * 512: 16384 for N = 32;
// for N = 128 only a full-scale square wave would saturate at 65535).
//
// Timestamps: every frame carries t, the ADC sample counter of the sample
// it was computed from. The stream tokens have no room for it, so tag_fifo
// instances carry t past sdft_bank, carrier_magnitude and taxel_reconstruct;
// izhikevich_layer carries t itself.
//
// Processing step: the DFT runs on every sample; magnitudes, taxels and
// neurons run on every STEP-th sample (the neuron constants assume
// dt = STEP / SAMPLE_HZ). STEP = 1 for 3x3 at 12 MHz: per 343-cycle sample
// the slowest stage (carrier_magnitude, 6 x 26 cycles) needs 156 cycles.
//
// Start-up: after reset the carrier table (parameter CARRIER_INC, carrier k
// in bits 32k+31:32k, rows first) is written to sdft_bank, then the ADC is
// enabled; its first conversion is sample t = 0.
module dtmf_top #(
    parameter integer CLK_HZ = 12_000_000,
    parameter integer SAMPLE_HZ = 35_000,
    parameter integer BAUD = 3_000_000,
    parameter integer R = 3,
    parameter integer C = 3,
    parameter integer N = 32,
    parameter integer XW = 12,          // code - 2048 fits 12 bits
    parameter integer CW = 16,
    parameter integer TW = 10,
    parameter integer ACC_W = 18,       // XW + 1 + log2 N: window sums never wrap
    parameter integer MAG_W = 16,
    parameter integer MAG_SHIFT = 2,
    parameter integer TAX_W = 16,
    // phase increments round(f / fs * 2^32): 1.9, 3.3, 5 kHz rows, 7.14,
    // 8.3, 10 kHz columns at 35 kHz (scenes/neuroskin2.yaml)
    parameter [32*(R+C)-1:0] CARRIER_INC = {32'd1227133513, 32'd1018520816, 32'd876173328,
                                            32'd613566757, 32'd404954059, 32'd233155367},
    // taxel_reconstruct: mode 1 (conductance): g = isqrt(m_i m_j) * RECIP >>
    // RECIP_SHIFT, RECIP = round(2^(15+12) / full carrier magnitude 2482.42)
    parameter integer TAX_MODE = 1,
    parameter integer TAX_SHIFT = 0,
    parameter integer TAX_RECIP = 54067,
    parameter integer TAX_RECIP_SHIFT = 12,
    parameter integer STEP = 1,
    parameter integer TOKEN_FIFO = 0,   // DFT -> magnitude frame buffer depth (0: none)
    parameter integer CARRIER_CMD = 0,  // 1: SET_CARRIER_INC reloads the DFT carriers (+~500 LCs)
    // Reset values of the command registers (docs/protocol.md): output mask
    // (amplitudes, taxels, spikes, periodic status) and decimations in steps.
    parameter [3:0] MASK = 4'b1111,
    parameter [15:0] DECIM_AMP = 16'd35,
    parameter [15:0] DECIM_TAX = 16'd35,    // taxel frames and spike windows
    parameter [15:0] DECIM_STATUS = 16'd1000,
    parameter integer SPK_DEPTH = 512,
    // izhikevich_layer constants (hls::make_izhikevich_config: RA, dt =
    // STEP / 35 ms, input g UQ1.15 * input_scale 10, x_shift 1)
    parameter integer V_INIT = -272629760,
    parameter integer U_INIT = -60445913,
    parameter integer V_RESET = -230686720,
    parameter integer U_JUMP = 185987,
    parameter integer U_FRAC = 27,
    parameter integer C_CONST = -1888935,
    parameter integer M2 = 18599,
    parameter integer S2 = 16,
    parameter integer M3 = 16494,
    parameter integer S3 = 13,
    parameter integer M4 = 18599,
    parameter integer S4 = 25,
    parameter integer GAIN = 20433,
    parameter integer GAIN_SHIFT = 5,
    parameter integer X_SHIFT = 1
) (
    input  wire clk,
    input  wire rst_n,       // active low (button); a power-on reset is built in
    output wire adc_cs_n,
    output wire adc_sclk,
    input  wire adc_sdata,
    output wire uart_txd,    // to the host
    input  wire uart_rxd     // from the host
);
  localparam integer K = R + C;
  localparam integer T = R * C;
  localparam integer K_M1 = K - 1;
  localparam integer STEP_M1 = STEP - 1;
  localparam [7:0] K_LAST = K_M1[7:0];
  localparam [7:0] R8 = R[7:0];
  localparam [7:0] C8 = C[7:0];
  localparam [1:0] TAX_MODE2 = TAX_MODE[1:0];
  localparam [4:0] TAX_SHIFT5 = TAX_SHIFT[4:0];
  localparam [15:0] TAX_RECIP16 = TAX_RECIP[15:0];
  localparam [4:0] TAX_RECIP_SHIFT5 = TAX_RECIP_SHIFT[4:0];

  // ---------------- reset: power-on counter and synchronised button -------
  reg [3:0] por_cnt = 4'd0;
  reg [1:0] rst_sync = 2'b00;
  reg rst = 1'b1;
  always @(posedge clk) begin
    rst_sync <= {rst_sync[0], rst_n};
    if (por_cnt != 4'hF) por_cnt <= por_cnt + 4'd1;
    rst <= (por_cnt != 4'hF) || !rst_sync[1];
  end

  // ---------------- carrier table load, then ADC enable -------------------
  // After reset and after each SET_CARRIER_INC the K increments are written
  // to sdft_bank (the last write clears its window, phases and sums).
  reg [7:0] cfg_k;
  reg cfg_busy, adc_en;
  wire cfg_ready, carrier_reload;
  wire [32*K-1:0] carrier_inc;
  always @(posedge clk) begin
    if (rst) begin
      cfg_k <= 8'd0; cfg_busy <= 1'b1; adc_en <= 1'b0;
    end else if (carrier_reload) begin
      cfg_k <= 8'd0; cfg_busy <= 1'b1;
    end else if (cfg_busy && cfg_ready) begin
      cfg_k <= cfg_k + 8'd1;
      if (cfg_k == K_LAST) cfg_busy <= 1'b0;
    end else if (!cfg_busy) begin
      adc_en <= 1'b1;
    end
  end
  // CARRIER_CMD = 0: the table is the parameter (SET_CARRIER_INC is accepted
  // and counted but not applied); saves the decoder's K x 32 registers.
  wire [31:0] cfg_inc = (CARRIER_CMD != 0) ? carrier_inc[32 * cfg_k +: 32]
                                           : CARRIER_INC[32 * cfg_k +: 32];

  // ---------------- ADC ------------------------------------------------
  wire adc_valid, sdft_in_ready;
  wire [11:0] adc_code;
  wire [31:0] adc_t;
  wire [15:0] adc_overruns;
  adc_ad7476 #(.CLK_HZ(CLK_HZ), .SAMPLE_HZ(SAMPLE_HZ), .SCLK_DIV(1), .NCH(1)) u_adc (
      .clk(clk), .rst(rst), .en(adc_en), .cs_n(adc_cs_n), .sclk(adc_sclk),
      .sdata(adc_sdata), .m_valid(adc_valid), .m_ready(sdft_in_ready),
      .m_data(adc_code), .m_t(adc_t), .overruns(adc_overruns));
  // Samples taken so far (status block): t of the newest sample + 1 (the
  // ADC holds m_t until its next token; 1 before the first one).
  wire [31:0] samples = adc_t + 32'd1;

  // ---------------- sliding DFT -----------------------------------------
  wire [XW-1:0] x = {{(XW - 11){~adc_code[11]}}, adc_code[10:0]};  // code - 2048
  wire sdft_fire = adc_valid && sdft_in_ready;
  wire sd_valid, sd_last;
  wire sd_ready;
  wire [7:0] sd_k;
  wire [ACC_W-1:0] sd_re, sd_im;
  sdft_bank #(.K_MAX(K), .N(N), .XW(XW), .CW(CW), .TW(TW), .ACC_W(ACC_W), .K_W(8)) u_sdft (
      .clk(clk), .rst(rst), .in_valid(adc_valid), .in_ready(sdft_in_ready), .in_x(x),
      .cfg_valid(cfg_busy && !rst), .cfg_ready(cfg_ready), .cfg_k(cfg_k), .cfg_inc(cfg_inc),
      .cfg_last(cfg_k == K_LAST), .out_valid(sd_valid), .out_ready(sd_ready), .out_k(sd_k),
      .out_re(sd_re), .out_im(sd_im), .out_last(sd_last));
  wire [31:0] sd_t;
  wire tq0_err;
  tag_fifo #(.W(32), .DEPTH(2)) u_tq0 (
      .clk(clk), .rst(rst), .push(sdft_fire), .push_tag(adc_t),
      .pop(sd_valid && sd_ready && sd_last), .head(sd_t), .error(tq0_err));

  // ---------------- step gate: every STEP-th sample goes on ---------------
  localparam integer STW = (STEP > 1) ? $clog2(STEP) : 1;
  reg [STW-1:0] step_ph;
  wire step_sel = (step_ph == {STW{1'b0}});
  wire gq_ready;  // gated queue (token FIFO or carrier_magnitude) ready
  assign sd_ready = step_sel ? gq_ready : 1'b1;
  always @(posedge clk) begin
    if (rst) step_ph <= {STW{1'b0}};
    else if (sd_valid && sd_ready && sd_last)
      step_ph <= (step_ph == STEP_M1[STW-1:0]) ? {STW{1'b0}} : step_ph + 1'b1;
  end
  wire gq_fire = sd_valid && step_sel && gq_ready;

  // Optional frame buffer (TOKEN_FIFO > 0) between the DFT and the
  // magnitudes: needed when K * 26 cycles exceed a sample period.
  localparam integer TOKW = 8 + 2 * ACC_W + 1;
  wire mg_in_valid, mg_in_ready, mg_in_last;
  wire [7:0] mg_in_k;
  wire [ACC_W-1:0] mg_in_re, mg_in_im;
  generate
    if (TOKEN_FIFO > 0) begin : g_fifo
      wire [TOKW-1:0] q_out;
      token_fifo #(.W(TOKW), .DEPTH(TOKEN_FIFO)) u_q (
          .clk(clk), .rst(rst), .in_valid(sd_valid && step_sel), .in_ready(gq_ready),
          .in_data({sd_last, sd_k, sd_re, sd_im}), .out_valid(mg_in_valid),
          .out_ready(mg_in_ready), .out_data(q_out));
      assign {mg_in_last, mg_in_k, mg_in_re, mg_in_im} = q_out;
    end else begin : g_direct
      assign mg_in_valid = sd_valid && step_sel;
      assign gq_ready = mg_in_ready;
      assign {mg_in_last, mg_in_k, mg_in_re, mg_in_im} = {sd_last, sd_k, sd_re, sd_im};
    end
  endgenerate

  // ---------------- magnitudes -------------------------------------------
  wire mg_valid, mg_last, mg_ready;
  wire [7:0] mg_k;
  wire [MAG_W-1:0] mg_mag;
  carrier_magnitude #(.ACC_W(ACC_W), .MAG_W(MAG_W), .SHIFT(MAG_SHIFT), .K_W(8)) u_mag (
      .clk(clk), .rst(rst), .in_valid(mg_in_valid), .in_ready(mg_in_ready), .in_k(mg_in_k),
      .in_re(mg_in_re), .in_im(mg_in_im), .in_last(mg_in_last), .out_valid(mg_valid),
      .out_ready(mg_ready), .out_k(mg_k), .out_mag(mg_mag), .out_last(mg_last));
  // t of a frame from the gate (FIFO input) to the last magnitude: at most
  // one frame in the FIFO and one in carrier_magnitude (one without FIFO).
  wire [31:0] mg_t;
  wire tq1_err;
  tag_fifo #(.W(32), .DEPTH(TOKEN_FIFO > 0 ? 2 : 1)) u_tq1 (
      .clk(clk), .rst(rst), .push(gq_fire && sd_k == 8'd0), .push_tag(sd_t),
      .pop(mg_valid && mg_ready && mg_last), .head(mg_t), .error(tq1_err));
  wire mg_fire = mg_valid && mg_ready;

  // ---------------- taxels -----------------------------------------------
  wire tx_in_ready, tx_valid, tx_last, tx_ready;
  wire [7:0] tx_row, tx_col;
  wire [TAX_W-1:0] tx_value;
  assign mg_ready = tx_in_ready;  // the packetizer side is always ready
  taxel_reconstruct #(.R_MAX(R), .C_MAX(C), .MAG_W(MAG_W), .TAX_W(TAX_W), .K_W(8)) u_tax (
      .clk(clk), .rst(rst), .cfg_rows(R8), .cfg_cols(C8), .cfg_mode(TAX_MODE2),
      .cfg_shift(TAX_SHIFT5), .cfg_threshold({MAG_W{1'b0}}), .cfg_recip(TAX_RECIP16),
      .cfg_recip_shift(TAX_RECIP_SHIFT5), .cfg_slope_shift(5'd0), .tab_we(1'b0),
      .tab_addr(4'd0), .tab_g(16'd0), .tab_p({TAX_W{1'b0}}), .tab_slope(16'd0),
      .in_valid(mg_valid), .in_ready(tx_in_ready), .in_k(mg_k), .in_mag(mg_mag),
      .out_valid(tx_valid), .out_ready(tx_ready), .out_row(tx_row), .out_col(tx_col),
      .out_value(tx_value), .out_last(tx_last));
  wire [31:0] tx_t;
  wire tq2_err;
  tag_fifo #(.W(32), .DEPTH(1)) u_tq2 (
      .clk(clk), .rst(rst), .push(mg_fire && mg_k == K_LAST), .push_tag(mg_t),
      .pop(tx_valid && tx_ready && tx_last), .head(tx_t), .error(tq2_err));
  wire tx_fire = tx_valid && tx_ready;

  // ---------------- neurons ----------------------------------------------
  wire nr_valid, nr_spike, nr_last;
  wire [15:0] nr_neuron;
  wire [31:0] nr_t, nr_v, nr_u;
  izhikevich_layer #(.N(T), .V_INIT(V_INIT), .U_INIT(U_INIT), .V_RESET(V_RESET),
      .U_JUMP(U_JUMP), .U_FRAC(U_FRAC), .C_CONST(C_CONST), .M2(M2), .S2(S2), .M3(M3),
      .S3(S3), .M4(M4), .S4(S4), .GAIN(GAIN), .GAIN_SHIFT(GAIN_SHIFT), .X_SHIFT(X_SHIFT)) u_nrn (
      .clk(clk), .rst(rst), .in_valid(tx_valid), .in_ready(tx_ready),
      .in_x({{(32 - TAX_W){1'b0}}, tx_value}), .in_t(tx_t), .out_valid(nr_valid), .out_ready(1'b1),
      .out_neuron(nr_neuron), .out_t(nr_t), .out_spike(nr_spike), .out_last(nr_last),
      .out_v(nr_v), .out_u(nr_u));

  // ---------------- commands: uart_rx -> cmd_decoder ---------------------
  // Registers (docs/protocol.md section 6) used here: carrier_inc (reloaded
  // into sdft_bank after a SET_CARRIER_INC), out_mask, decim (amplitudes,
  // taxels + spike windows, status; counted in steps; DECIM_MAX = 1023, so
  // 10-bit counters), status_req and the counters. thresholds and neuron are not wired: the dense taxel packet
  // and one neuron per taxel need every taxel (threshold 0), and
  // izhikevich_layer takes its constants as parameters.
  wire rx_valid, rx_frame_err, rx_overrun;
  wire [7:0] rx_data;
  uart_rx #(.CLK_HZ(CLK_HZ), .BAUD(BAUD)) u_rx (
      .clk(clk), .rst(rst), .rx(uart_rxd), .m_valid(rx_valid), .m_ready(1'b1),
      .m_data(rx_data), .frame_err(rx_frame_err), .overrun(rx_overrun));
  reg [15:0] uart_rx_errors;
  always @(posedge clk) begin
    if (rst) uart_rx_errors <= 16'd0;
    else if ((rx_frame_err || rx_overrun) && uart_rx_errors != 16'hFFFF)
      uart_rx_errors <= uart_rx_errors + 16'd1;
  end
  wire [4*16-1:0] thresholds;
  wire [4*32-1:0] neuron_regs;
  wire [3:0] out_mask;
  wire [47:0] decim;
  wire cfg_changed, status_req;
  wire cmd_ready;  // always 1: cmd_decoder takes a byte per clock
  wire [15:0] cmd_crc_errors, cmd_frame_errors, cmd_accepted, cmd_rejected;
  wire [7:0] rej_type, rej_reason, rej_seq;
  cmd_decoder #(.K(K), .PHASE_W(32), .NTHR(4), .NNP(4), .INC_INIT(CARRIER_INC),
      .MASK_INIT({4'd0, MASK}), .DECIM_INIT({DECIM_STATUS, DECIM_TAX, DECIM_AMP}),
      .DECIM_MAX(16'd1023)) u_cmd (
      .clk(clk), .rst(rst), .s_valid(rx_valid), .s_ready(cmd_ready), .s_data(rx_data),
      .rx_error(rx_frame_err || rx_overrun), .carrier_inc(carrier_inc),
      .thresholds(thresholds), .neuron(neuron_regs), .out_mask(out_mask), .decim(decim),
      .cfg_changed(cfg_changed), .status_req(status_req), .crc_errors(cmd_crc_errors),
      .frame_errors(cmd_frame_errors), .accepted(cmd_accepted), .rejected(cmd_rejected),
      .last_reject_type(rej_type), .last_reject_reason(rej_reason),
      .last_reject_seq(rej_seq));
  // Type of the last command frame, to reload the carriers only after a
  // SET_CARRIER_INC (a reload clears the DFT window): the type is raw byte
  // 0, i.e. wire byte 1 after a 0x00 (byte 0 is the COBS code; no type is 0).
  reg [1:0] rx_pos;
  reg [7:0] rx_type;
  always @(posedge clk) begin
    if (rst) begin
      rx_pos <= 2'd0; rx_type <= 8'd0;
    end else if (rx_valid) begin
      if (rx_data == 8'd0) rx_pos <= 2'd0;
      else if (rx_pos != 2'd2) rx_pos <= rx_pos + 2'd1;
      if (rx_data != 8'd0 && rx_pos == 2'd1) rx_type <= rx_data;
    end
  end
  assign carrier_reload = (CARRIER_CMD != 0) && cfg_changed && rx_type == 8'h81;

  // ---------------- packets ----------------------------------------------
  wire [15:0] dropped;
  // Status bytes 0..19 (StatusBlock, little endian): command counters,
  // last rejection, mask, dropped, ADC overruns, UART errors, reserved.
  wire [159:0] status_fixed = {16'd0, uart_rx_errors, adc_overruns, dropped,
      {4'd0, out_mask}, rej_seq, rej_reason, rej_type, cmd_rejected, cmd_accepted,
      cmd_frame_errors, cmd_crc_errors};
  wire hdr_valid, hdr_ready, pk_valid, pk_ready;
  wire [7:0] hdr_type, pk_data;
  wire [31:0] hdr_t;
  wire [15:0] hdr_len;
  frame_packetizer #(.K_MAX(K), .T_MAX(T), .SPK_DEPTH(SPK_DEPTH), .MAG_W(MAG_W),
      .TAX_W(TAX_W), .K_W(8)) u_pack (
      .clk(clk), .rst(rst), .mask(out_mask), .decim_amp(decim[9:0]), .decim_tax(decim[25:16]),
      .decim_status(decim[41:32]), .rows(R8), .cols(C8),
      .amp_valid(mg_fire), .amp_k(mg_k), .amp_mag(mg_mag), .amp_last(mg_last), .amp_t(mg_t),
      .tax_valid(tx_fire), .tax_value(tx_value), .tax_last(tx_last), .tax_t(tx_t),
      .nrn_valid(nr_valid), .nrn_neuron(nr_neuron), .nrn_t(nr_t), .nrn_spike(nr_spike),
      .nrn_last(nr_last), .status_req(status_req), .status_fixed(status_fixed), .samples(samples),
      .dropped(dropped), .hdr_valid(hdr_valid), .hdr_ready(hdr_ready), .hdr_type(hdr_type),
      .hdr_t(hdr_t), .hdr_len(hdr_len), .s_valid(pk_valid), .s_ready(pk_ready),
      .s_data(pk_data));
  wire fr_valid, fr_ready;
  wire [7:0] fr_data, fr_seq;
  link_framer u_framer (
      .clk(clk), .rst(rst), .hdr_valid(hdr_valid), .hdr_ready(hdr_ready),
      .hdr_type(hdr_type), .hdr_t(hdr_t), .hdr_len(hdr_len), .s_valid(pk_valid),
      .s_ready(pk_ready), .s_data(pk_data), .m_valid(fr_valid), .m_ready(fr_ready),
      .m_data(fr_data), .seq(fr_seq));
  uart_tx #(.CLK_HZ(CLK_HZ), .BAUD(BAUD)) u_tx (
      .clk(clk), .rst(rst), .s_valid(fr_valid), .s_ready(fr_ready), .s_data(fr_data),
      .tx(uart_txd));

  // Probes for the testbench (latency table, error flags); no logic.
  wire tag_error /* verilator public_flat_rd */ = tq0_err | tq1_err | tq2_err;
  wire p_adc_fire /* verilator public_flat_rd */ = sdft_fire;
  wire [31:0] p_adc_t /* verilator public_flat_rd */ = adc_t;
  wire p_sd_fire /* verilator public_flat_rd */ = sd_valid && sd_ready && step_sel;
  wire p_sd_last /* verilator public_flat_rd */ = sd_last;
  wire [31:0] p_sd_t /* verilator public_flat_rd */ = sd_t;
  wire p_mg_fire /* verilator public_flat_rd */ = mg_fire;
  wire p_mg_last /* verilator public_flat_rd */ = mg_last;
  wire [31:0] p_mg_t /* verilator public_flat_rd */ = mg_t;
  wire p_tx_fire /* verilator public_flat_rd */ = tx_fire;
  wire p_tx_last /* verilator public_flat_rd */ = tx_last;
  wire [31:0] p_tx_t /* verilator public_flat_rd */ = tx_t;
  wire p_nr_fire /* verilator public_flat_rd */ = nr_valid;
  wire p_nr_last /* verilator public_flat_rd */ = nr_last;
  wire [31:0] p_nr_t /* verilator public_flat_rd */ = nr_t;
  wire p_hdr_fire /* verilator public_flat_rd */ = hdr_valid && hdr_ready;
  wire [7:0] p_hdr_type /* verilator public_flat_rd */ = hdr_type;
  wire [31:0] p_hdr_t /* verilator public_flat_rd */ = hdr_t;
  wire [15:0] p_dropped /* verilator public_flat_rd */ = dropped;
  wire [15:0] p_overruns /* verilator public_flat_rd */ = adc_overruns;
  wire p_cfg_done /* verilator public_flat_rd */ = cfg_busy && cfg_ready && cfg_k == K_LAST;
  wire [3:0] p_mask /* verilator public_flat_rd */ = out_mask;
  wire unused = ^{tx_row, tx_col, nr_v, nr_u, fr_seq, thresholds, neuron_regs, cmd_ready, decim[47:42], decim[31:26],
                  decim[15:10], tag_error, p_adc_fire,
                  p_adc_t, p_sd_fire, p_sd_last, p_sd_t, p_mg_fire, p_mg_last, p_mg_t, p_tx_fire,
                  p_tx_last, p_tx_t, p_nr_fire, p_nr_last, p_nr_t, p_hdr_fire, p_hdr_type,
                  p_hdr_t, p_dropped, p_overruns, p_cfg_done, p_mask};
endmodule
