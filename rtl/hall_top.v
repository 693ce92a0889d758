`default_nettype none
// hall_top: the FPGA top of a magnetic (Hall) skin: NB I2C buses in
// parallel, each an i2c_master driven by an mlx90393_sequencer with NSB
// MLX90393 sensors (directly on the bus or behind TCA9548A channels), a frame
// assembler, and the host link (link_framer + uart_tx, docs/protocol.md; or,
// with EXT_LINK, its packet stream to rtl/mixed_top.v's shared link).
// The parameters are generated from the scene (sensor addresses, mux
// channels, register settings, conversion wait).
//
// Sensor s = b * NSB + k is sensor k of bus b; its DRDY (INT) pin is drdy[s].
// Frames: one token per sensor per round (data, or flags saying why not)
// goes into slot s of a frame buffer (one RAM); when every slot is filled a
// HALL_SAMPLES packet (type 0x10) carries all of them, 10 bytes per sensor
// in sensor order: id u8, flags u8, t16 u16 (low 16 bits of the µs time the
// reading's status byte arrived), x u16, y u16, z u16 (the device's codes).
// The packet's t is the µs counter when the frame completed. While a frame
// is being sent, and while a sensor's slot is already full, its bus waits
// (the sequencer holds its token), so rounds of all buses stay aligned.
// Every STATUS_EVERY frames a HALL_BUS_STATUS packet (type 0x20) follows:
// per bus nacks, status_errors, reply_errors, recoveries, bus_errors (u16
// each, LE).
// DELTAS = 1 adds the decoding's first block: every token also goes through
// hall_baseline (each sensor's first 16 readings with data are its baseline)
// and each HALL_SAMPLES frame is followed by a HALL_DELTAS packet (type
// 0x12, docs/protocol.md section 9) in the same 10-byte layout with the
// baseline-removed field (s16 LSB) instead of the codes; a slot without a
// delta (baseline still capturing, or a reading without data) has x, y, z 0
// and flag bit 5 (REPLY: not trusted) set. With DELTAS = 1 the top also
// takes commands on uart_rxd (uart_rx -> cmd_decoder -> hall_cmd:
// HALL_SET_BASELINE, HALL_RECAPTURE; HALL_LOAD_C with FT = 1,
// HALL_SET_DECOUPLE with DECOUPLE = 1, HALL_LOAD_CURVE with CURVE = 1) and sends
// a HALL_DECODE_STATUS packet (type 0x16: the decoding's and the commands'
// counters) with every HALL_BUS_STATUS and, after a rejected command, at
// the end of the frame packets being sent (or of the next frame's). Without DELTAS there is nothing to command: uart_rxd
// is not used.
// FT = 1 (needs DELTAS) adds ft_calibrate on sensors FT_ID .. FT_ID+2 (seed
// 002): W = C dB with C loaded by HALL_LOAD_C; each frame that completes a
// wrench is followed (after its HALL_DELTAS) by a WRENCH6 packet (type
// 0x14) whose t is the µs time of the token that completed it.
// DECOUPLE = 1 (needs DELTAS) adds hall_decouple on sensor DEC_ID (seed
// 001, gains DEC_GAIN_X/Y/Z UQ16.16 uT/LSB): Rx, Ry, Sz of each of its
// deltas, with k1, c1, k2, c2 set by HALL_SET_DECOUPLE; each frame with a
// result is followed by a DECOUPLE3 packet (type 0x13) whose t is the
// token's µs time.
// CURVE = 1 (needs DELTAS) adds force_curve on sensors CURVE_ID ..
// CURVE_ID+NC-1 (seed 003: one cell each, CURVE_NB breakpoints loaded by
// HALL_LOAD_CURVE, gains CURVE_GAIN_X/Y/Z UQ4.12, range ends LOCK_MN); each
// frame is followed by a FORCE_CURVE packet (type 0x15) of NC records, a
// cell without a result in this frame with force 0, t 0 and flag bit 5.
// force_curve and hall_decouple take one token at a time: the intake waits
// while either is busy (46 and at most 257 clocks (docs/hall_fpga.md); tokens come one per
// I2C reading, about 3000 clocks).
// Packet order after a frame: HALL_SAMPLES, HALL_DELTAS, DECOUPLE3, WRENCH6,
// FORCE_CURVE, HALL_BUS_STATUS, HALL_DECODE_STATUS (each only when due).
// ft_calibrate is idle whenever a token reaches it: it computes for 56
// clocks after sensor FT_ID+2's token, and the next token of sensors
// FT_ID..FT_ID+2 comes in the next round, after this frame's packets.
module hall_top #(
    parameter integer CLK_HZ = 12_000_000,
    parameter integer BAUD = 3_000_000,
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
    parameter integer CONV_CYC = 29_564,
    parameter integer STALE_CYC = 36_954,
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
    parameter [CURVE_NR*32-1:0] LOCK_MN = {32'sd16200, 32'sd4800, 32'sd900},
    // 0: this top owns the host link (link_framer -> uart_tx on uart_txd).
    // 1: it shares the link with a DTMF top (rtl/mixed_top.v): its packets
    // leave on pkt_* (whole packets, as link_framer takes them; uart_txd
    // idles high) and its command decoder keeps only the Hall commands
    // 0x90-0x9F (the DTMF top judges every other type).
    parameter integer EXT_LINK = 0
) (
    input  wire              clk,
    input  wire              rst,
    input  wire [NB-1:0]     scl_i,
    input  wire [NB-1:0]     sda_i,
    output wire [NB-1:0]     scl_oe,
    output wire [NB-1:0]     sda_oe,
    input  wire [NB*NSB-1:0] drdy,
    output wire              uart_txd,
    input  wire              uart_rxd,
    output wire              pkt_valid,   // EXT_LINK = 1: the packet stream (else 0)
    input  wire              pkt_ready,
    output wire [7:0]        pkt_data
);
  localparam integer NSENS = NB * NSB;
  localparam integer FB = NSENS * 10;  // frame payload bytes
  localparam integer PMAX0 = (FB > 25) ? FB : 25;  // longest payload (WRENCH6 25 bytes)
  localparam integer PMAX = (PMAX0 > NC * 11) ? PMAX0 : NC * 11;  // or FORCE_CURVE's
  localparam integer CW = (NC > 1) ? $clog2(NC) : 1;  // cell index bits
  localparam integer AW = $clog2(PMAX + 1);
  localparam integer BW = (NB > 1) ? $clog2(NB) : 1;
  localparam integer SW = (NSENS > 1) ? $clog2(NSENS) : 1;  // slot index bits
  localparam integer US_DIV = CLK_HZ / 1_000_000;
  localparam [7:0] T_SAMPLES = 8'h10, T_BUS_STATUS = 8'h20, T_DELTAS = 8'h12, T_WRENCH = 8'h14,
                   T_DECODE_STATUS = 8'h16, T_DECOUPLE = 8'h13, T_CURVE = 8'h15;
  localparam integer DEC_BYTES = 17;  // HALL_DECODE_STATUS payload
  // Code format per axis (mlx90393_config.h): offset binary 0x8000 with
  // TCMP_EN (REG1[10]) or at RES 2, 0x4000 at RES 3, else two's complement.
  function [15:0] code_offset(input [1:0] res);
    code_offset = REG1[10] ? 16'h8000 : (res == 2'd2) ? 16'h8000 : (res == 2'd3) ? 16'h4000 : 16'h0000;
  endfunction

  generate
    if (NSENS > 255 || CLK_HZ % 1_000_000 != 0) begin : g_bad
      hall_top_needs_at_most_255_sensors_and_a_whole_MHz_clock bad ();
    end
    if (EXT_LINK != 0 && EXT_LINK != 1) begin : g_bad_link
      hall_top_EXT_LINK_is_0_or_1 bad ();
    end
    if (FT != 0 && (DELTAS == 0 || FT_ID < 0 || FT_ID + 3 > NSENS)) begin : g_bad_ft
      hall_top_FT_needs_DELTAS_and_sensors_FT_ID_to_FT_ID_plus_2 bad ();
    end
    if (DECOUPLE != 0 && (DELTAS == 0 || DEC_ID < 0 || DEC_ID >= NSENS)) begin : g_bad_dc
      hall_top_DECOUPLE_needs_DELTAS_and_DEC_ID_below_NB_times_NSB bad ();
    end
    if (CURVE != 0 && (DELTAS == 0 || CURVE_ID < 0 || NC < 1 || CURVE_ID + NC > NSENS)) begin : g_bad_fc
      hall_top_CURVE_needs_DELTAS_and_sensors_CURVE_ID_to_CURVE_ID_plus_NC_minus_1 bad ();
    end
    if (CURVE == 0 && NC != 1) begin : g_bad_nc
      hall_top_NC_is_for_CURVE_builds_only bad ();
    end
  endgenerate

  // ---- µs time base
  reg [31:0] t_us;  // µs since reset (timestamps)
  reg [$clog2(US_DIV + 1)-1:0] us_cnt;
  always @(posedge clk) begin
    if (rst) begin
      us_cnt <= 0;
      t_us <= 32'd0;
    end else if (us_cnt == US_DIV[$clog2(US_DIV + 1)-1:0] - 1'b1) begin
      us_cnt <= 0;
      t_us <= t_us + 32'd1;
    end else begin
      us_cnt <= us_cnt + 1'b1;
    end
  end

  // ---- buses
  wire [NB-1:0] tv;
  reg  [NB-1:0] tr;
  wire [NB*8-1:0] tid, tflags;
  wire [NB*32-1:0] tt;
  wire [NB*48-1:0] txyz;
  wire [NB*80-1:0] counters;
  genvar b;
  generate
    for (b = 0; b < NB; b = b + 1) begin : g_bus
      wire cv, cr, ca, rv, rr, rn, own;
      wire [2:0] co;
      wire [7:0] cd, rd;
      wire [1:0] re;
      i2c_master #(.CLK_HZ(CLK_HZ), .SCL_HZ(SCL_HZ)) u_master (
          .clk(clk), .rst(rst), .cmd_valid(cv), .cmd_ready(cr), .cmd_op(co), .cmd_data(cd),
          .cmd_ack(ca), .rsp_valid(rv), .rsp_ready(rr), .rsp_data(rd), .rsp_nack(rn),
          .rsp_err(re), .scl_i(scl_i[b]), .sda_i(sda_i[b]), .scl_oe(scl_oe[b]),
          .sda_oe(sda_oe[b]), .owned(own));
      mlx90393_sequencer #(
          .NS(NSB), .ADDR(ADDR[b*NSB*7 +: NSB*7]), .MUX_ADDR(MUX_ADDR[b*NSB*7 +: NSB*7]),
          .MUX_CH(MUX_CH[b*NSB*3 +: NSB*3]), .ID_BASE(8'(b * NSB)), .REG0(REG0), .REG1(REG1),
          .REG2(REG2), .BURST(BURST), .CONV_CYC(CONV_CYC), .STALE_CYC(STALE_CYC)
      ) u_seq (
          .clk(clk), .rst(rst), .drdy(drdy[b*NSB +: NSB]), .tstamp(t_us), .m_cmd_valid(cv),
          .m_cmd_ready(cr), .m_cmd_op(co), .m_cmd_data(cd), .m_cmd_ack(ca), .m_rsp_valid(rv),
          .m_rsp_ready(rr), .m_rsp_data(rd), .m_rsp_nack(rn), .m_rsp_err(re),
          .s_valid(tv[b]), .s_ready(tr[b]), .s_id(tid[b*8 +: 8]), .s_t(tt[b*32 +: 32]),
          .s_x(txyz[b*48+32 +: 16]), .s_y(txyz[b*48+16 +: 16]), .s_z(txyz[b*48 +: 16]),
          .s_flags(tflags[b*8 +: 8]), .nacks(counters[b*80 +: 16]),
          .status_errors(counters[b*80+16 +: 16]), .reply_errors(counters[b*80+32 +: 16]),
          .recoveries(counters[b*80+48 +: 16]), .bus_errors(counters[b*80+64 +: 16]));
      wire unused_bus = &{1'b0, own, tt[b*32+16 +: 16]};
    end
  endgenerate

  // ---- frame buffer (one RAM, byte wide)
  reg [7:0] fb[0:(1 << AW) - 1];  // FB bytes used; the full address range keeps the index width exact
  reg        fb_we;
  reg [AW-1:0] fb_waddr, fb_raddr;
  reg [7:0]  fb_wdata, fb_rdata;
  always @(posedge clk) begin
    if (fb_we) fb[fb_waddr] <= fb_wdata;
    fb_rdata <= fb[fb_raddr];
  end

  // ---- token intake: round robin over the buses, 10 bytes into slot id
  reg [NSENS-1:0] got;
  reg             emitting;   // a packet is being sent: intake waits
  reg             taking;     // writing a token's 10 bytes
  reg [3:0]       wbyte;
  reg [79:0]      tok;        // {id, flags, t16, x, y, z}, bytes LSB first per field
  reg [AW-1:0]    slot_base;
  reg [BW-1:0]    rr_next;

  // The bus whose token is taken next: the first at or after rr_next with a
  // token whose slot is free.
  reg             cand_ok;
  reg [BW-1:0]    cand;
  integer j;
  always @(*) begin
    cand_ok = 1'b0;
    cand = {BW{1'b0}};
    for (j = 2 * NB - 1; j >= 0; j = j - 1)
      if (j >= {{(32 - BW) {1'b0}}, rr_next} && j < {{(32 - BW) {1'b0}}, rr_next} + NB &&
          tv[j % NB] && !got[tid[(j % NB)*8 +: SW]]) begin
        cand_ok = 1'b1;
        cand = BW'(j % NB);
      end
  end
  always @(*) begin
    tr = {NB{1'b0}};
    if (!emitting && !taking && cand_ok && dc_idle && fc_idle) tr[cand] = 1'b1;
  end

  wire [7:0] c_id = tid[cand*8 +: 8];
  wire take_tok = !taking && |tr;

  // ---- decoding: baseline-removed deltas of every token (DELTAS = 1), the
  // command path, and the wrench (FT = 1)
  reg  [7:0]  fb2[0:(1 << AW) - 1];
  reg  [7:0]  fb2_rdata;
  reg         d_have;             // the token being written has a delta
  reg  [47:0] d_xyz;              // its dx, dy, dz
  wire        b_valid;
  wire [47:0] b_xyz;
  wire [DEC_BYTES*8-1:0] dec_status;  // HALL_DECODE_STATUS payload, byte 0 low
  wire        cmd_reject;             // a command was rejected (one clock)
  wire        ft_idle, ft_valid;      // ft_calibrate: in_ready, out_valid
  wire [31:0] ft_t;
  wire [199:0] ft_w;                  // WRENCH6 payload: w0..w5 s32, flags
  wire        dc_idle, dc_valid;      // hall_decouple: in_ready, out_valid
  wire [31:0] dc_t;
  wire [111:0] dc_w;                  // DECOUPLE3 payload: rx, ry, sz s32, valid, flags
  wire        fc_idle, fc_valid;      // force_curve: in_ready, out_valid
  wire        fc_last;                // fc_ram gets the last byte of force_curve's record
  wire [87:0] fc_rec;                 // one FORCE_CURVE record
  wire [CW-1:0] fc_cell;
  generate
    if (DELTAS != 0) begin : g_deltas
      wire [7:0] b_id, b_flags;
      wire [31:0] b_t;
      wire [15:0] b_dropped, ft_skipped, acc, rej, crc_err, frm_err, ovf;
      wire [7:0] l_type, l_reason, l_seq;
      wire b_ready;  // high at every take_tok: busy 1 cycle after a token, tokens 11+ apart
      wire set_v, recap;
      wire [SW-1:0] set_s;
      wire [1:0] set_a;
      wire [15:0] set_d;
      wire c_v;
      wire [2:0] c_r;
      wire [3:0] c_c;
      wire [31:0] c_d;
      wire t_v;
      wire [CW-1:0] t_c;
      wire [4:0] t_i;
      wire [1:0] t_w;
      wire [31:0] t_d, k_c1, k_c2;
      wire [15:0] k_k1, k_k2;
      hall_baseline #(
          .NS(NSENS), .CAPTURE_LOG2(4), .ID_BASE(0), .OFFSET_X(code_offset(REG2[6:5])),
          .OFFSET_Y(code_offset(REG2[8:7])), .OFFSET_Z(code_offset(REG2[10:9]))
      ) u_baseline (
          .clk(clk), .rst(rst), .in_valid(take_tok), .in_ready(b_ready),
          .in_id(c_id), .in_t(tt[cand*32 +: 32]), .in_x(txyz[cand*48+32 +: 16]),
          .in_y(txyz[cand*48+16 +: 16]), .in_z(txyz[cand*48 +: 16]), .in_flags(tflags[cand*8 +: 8]),
          .out_valid(b_valid), .out_ready(1'b1), .out_id(b_id), .out_t(b_t),
          .out_dx(b_xyz[47:32]), .out_dy(b_xyz[31:16]), .out_dz(b_xyz[15:0]), .out_flags(b_flags),
          .set_valid(set_v), .set_sensor(set_s), .set_axis(set_a), .set_value(set_d),
          .recapture(recap), .dropped(b_dropped));

      // Commands: uart_rx -> cmd_decoder (framing, CRC) -> hall_cmd (contents).
      wire r_valid, r_ready, r_ferr, r_ovr, q_avail, q_pop;
      wire [7:0] r_data, q_head;
      uart_rx #(.CLK_HZ(CLK_HZ), .BAUD(BAUD)) u_rx (
          .clk(clk), .rst(rst), .rx(uart_rxd), .m_valid(r_valid), .m_ready(r_ready),
          .m_data(r_data), .frame_err(r_ferr), .overrun(r_ovr));
      cmd_decoder #(.DEPTH(64), .TYPE_LO(EXT_LINK != 0 ? 8'h90 : 8'h00),
                    .TYPE_HI(EXT_LINK != 0 ? 8'h9F : 8'hFF)) u_cmd_dec (
          .clk(clk), .rst(rst), .s_valid(r_valid), .s_ready(r_ready), .s_data(r_data),
          .rx_error(r_ferr | r_ovr), .avail(q_avail), .head(q_head), .pop(q_pop),
          .clear(1'b0), .crc_errors(crc_err), .frame_errors(frm_err), .overflows(ovf));
      hall_cmd #(.NS(NSENS), .HAS_BASELINE(1), .HAS_FT(FT), .HAS_CURVE(CURVE),
                 .HAS_DECOUPLE(DECOUPLE), .NC(NC), .NBP(CURVE_NB), .SW(SW), .CW(CW)) u_cmd (
          .clk(clk), .rst(rst), .avail(q_avail), .head(q_head), .pop(q_pop),
          .c_valid(c_v), .c_row(c_r), .c_col(c_c), .c_value(c_d),
          .set_valid(set_v), .set_sensor(set_s), .set_axis(set_a), .set_value(set_d),
          .recapture(recap), .accepted(acc), .rejected(rej), .last_type(l_type),
          .last_reason(l_reason), .last_seq(l_seq), .reject(cmd_reject),
          .t_valid(t_v), .t_cell(t_c), .t_index(t_i), .t_which(t_w), .t_value(t_d),
          .dc_k1(k_k1), .dc_c1(k_c1), .dc_k2(k_k2), .dc_c2(k_c2));

      if (DECOUPLE != 0) begin : g_dc
        wire [31:0] rx, ry, sz;
        wire ok;
        wire [7:0] fl;
        hall_decouple #(.ID(DEC_ID), .GAIN_X(DEC_GAIN_X), .GAIN_Y(DEC_GAIN_Y),
                        .GAIN_Z(DEC_GAIN_Z)) u_dc (
            .clk(clk), .rst(rst), .in_valid(b_valid), .in_ready(dc_idle), .in_id(b_id),
            .in_t(b_t), .in_dx(b_xyz[47:32]), .in_dy(b_xyz[31:16]), .in_dz(b_xyz[15:0]),
            .in_flags(b_flags), .cfg_k1(k_k1), .cfg_c1(k_c1), .cfg_k2(k_k2), .cfg_c2(k_c2),
            .out_valid(dc_valid), .out_ready(1'b1), .out_t(dc_t), .out_rx(rx), .out_ry(ry),
            .out_sz(sz), .out_ok(ok), .out_flags(fl));
        assign dc_w = {fl, 7'd0, ok, sz, ry, rx};
      end else begin : g_no_dc
        assign dc_idle = 1'b1;
        assign dc_valid = 1'b0;
        assign dc_t = 32'd0;
        assign dc_w = 112'd0;
        wire unused_dc = &{1'b0, k_k1, k_c1, k_k2, k_c2};
      end

      if (CURVE != 0) begin : g_fc
        wire [7:0] o_cell, o_range, fl;
        wire [31:0] t, f;
        force_curve #(.NC(NC), .NB(CURVE_NB), .NR(CURVE_NR), .ID_BASE(CURVE_ID),
                      .GAIN_X(CURVE_GAIN_X), .GAIN_Y(CURVE_GAIN_Y), .GAIN_Z(CURVE_GAIN_Z),
                      .LOCK_MN(LOCK_MN), .CW(CW)) u_fc (
            .clk(clk), .rst(rst), .in_valid(b_valid), .in_ready(fc_idle), .in_id(b_id),
            .in_t(b_t), .in_dx(b_xyz[47:32]), .in_dy(b_xyz[31:16]), .in_dz(b_xyz[15:0]),
            .in_flags(b_flags), .out_valid(fc_valid), .out_ready(fc_last), .out_cell(o_cell),
            .out_t(t), .out_force_mn(f), .out_range(o_range), .out_flags(fl),
            .t_valid(t_v), .t_cell(t_c), .t_index(t_i), .t_which(t_w), .t_value(t_d));
        assign fc_rec = {f, t, fl, o_range, o_cell};
        assign fc_cell = o_cell[CW-1:0];
      end else begin : g_no_fc
        assign fc_idle = 1'b1;
        assign fc_valid = 1'b0;
        assign fc_rec = 88'd0;
        assign fc_cell = {CW{1'b0}};
        wire unused_fc = &{1'b0, t_v, t_c, t_i, t_w, t_d};
      end

      if (FT != 0) begin : g_ft
        wire [31:0] w0, w1, w2, w3, w4, w5;
        wire [7:0] w_flags;
        ft_calibrate #(.C_FRAC(16), .ID_BASE(FT_ID)) u_ft (
            .clk(clk), .rst(rst), .in_valid(b_valid), .in_ready(ft_idle), .in_id(b_id),
            .in_t(b_t), .in_dx(b_xyz[47:32]), .in_dy(b_xyz[31:16]), .in_dz(b_xyz[15:0]),
            .in_flags(b_flags), .out_valid(ft_valid), .out_ready(1'b1), .out_t(ft_t),
            .out_w0(w0), .out_w1(w1), .out_w2(w2), .out_w3(w3), .out_w4(w4), .out_w5(w5),
            .out_flags(w_flags), .c_valid(c_v), .c_row(c_r), .c_col(c_c), .c_value(c_d),
            .skipped(ft_skipped));
        assign ft_w = {w_flags, w5, w4, w3, w2, w1, w0};
      end else begin : g_no_ft
        assign ft_idle = 1'b1;
        assign ft_valid = 1'b0;
        assign ft_t = 32'd0;
        assign ft_w = 200'd0;
        assign ft_skipped = 16'd0;
        wire unused_ft = &{1'b0, c_v, c_r, c_c, c_d};
        if (DECOUPLE == 0 && CURVE == 0) begin : g_no_use
          wire unused_b_tok = &{1'b0, b_id, b_t, b_flags};
        end
      end
      assign dec_status = {l_seq, l_reason, l_type, ovf, frm_err, crc_err, rej, acc, ft_skipped,
                           b_dropped};
      wire unused_b = &{1'b0, b_ready};
    end else begin : g_no_deltas
      assign b_valid = 1'b0;
      assign b_xyz = 48'd0;
      assign dec_status = {DEC_BYTES * 8{1'b0}};
      assign cmd_reject = 1'b0;
      assign ft_idle = 1'b1;
      assign ft_valid = 1'b0;
      assign ft_t = 32'd0;
      assign ft_w = 200'd0;
      assign dc_idle = 1'b1;
      assign dc_valid = 1'b0;
      assign dc_t = 32'd0;
      assign dc_w = 112'd0;
      assign fc_idle = 1'b1;
      assign fc_valid = 1'b0;
      assign fc_rec = 88'd0;
      assign fc_cell = {CW{1'b0}};
      wire unused_rx = &{1'b0, uart_rxd};
    end
  endgenerate
  // fb2 is written one byte per cycle, one cycle behind fb (bytes 0..8 in
  // write cycles 1..9, byte 9 in the cycle after), through a registered port.
  reg         fb2_we, d_last;
  reg [AW-1:0] fb2_waddr;
  reg [7:0]   fb2_wdata;
  always @(posedge clk) begin
    if (fb2_we) fb2[fb2_waddr] <= fb2_wdata;
    fb2_rdata <= fb2[fb_raddr];
  end
  always @(posedge clk) begin
    if (rst) begin
      d_have <= 1'b0;
      d_xyz <= 48'd0;
      d_last <= 1'b0;
      fb2_we <= 1'b0;
      fb2_waddr <= {AW{1'b0}};
      fb2_wdata <= 8'd0;
    end else begin
      fb2_we <= 1'b0;
      d_last <= 1'b0;
      // hall_baseline's latency is 2: the delta (if any) is out in the
      // token's second write cycle, before byte 2 (the flags) needs d_have.
      // Its in_ready (II 2) is not looked at: tokens are taken 11+ cycles apart.
      if (taking && wbyte == 4'd1) begin
        d_have <= b_valid;
        d_xyz <= b_valid ? b_xyz : 48'd0;
      end
      if (DELTAS != 0 && ((taking && wbyte != 4'd0) || d_last)) begin
        fb2_we <= 1'b1;
        fb2_waddr <= slot_base + (d_last ? AW'(9) : AW'(wbyte) - AW'(1));
        if (d_last) begin
          fb2_wdata <= d_xyz[15:8];
        end else begin
          case (wbyte)  // id, flags (+ REPLY without a delta), t16, dx, dy, dz little endian
            4'd1: fb2_wdata <= tok[79:72];
            4'd2: fb2_wdata <= tok[71:64] | (d_have ? 8'h00 : 8'h20);
            4'd3: fb2_wdata <= tok[55:48];
            4'd4: fb2_wdata <= tok[63:56];
            4'd5: fb2_wdata <= d_xyz[39:32];
            4'd6: fb2_wdata <= d_xyz[47:40];
            4'd7: fb2_wdata <= d_xyz[23:16];
            4'd8: fb2_wdata <= d_xyz[31:24];
            default: fb2_wdata <= d_xyz[7:0];
          endcase
        end
        if (taking && wbyte == 4'd9) d_last <= 1'b1;
      end
    end
  end

  always @(posedge clk) begin
    if (rst) begin
      taking <= 1'b0;
      wbyte <= 4'd0;
      tok <= 80'd0;
      slot_base <= {AW{1'b0}};
      rr_next <= {BW{1'b0}};
      fb_we <= 1'b0;
      fb_waddr <= {AW{1'b0}};
      fb_wdata <= 8'd0;
    end else begin
      fb_we <= 1'b0;
      if (take_tok) begin
        taking <= 1'b1;
        wbyte <= 4'd0;
        slot_base <= AW'(c_id * 10);
        tok <= {c_id, tflags[cand*8 +: 8], tt[cand*32 +: 16], txyz[cand*48 +: 48]};
        rr_next <= (cand == BW'(NB - 1)) ? {BW{1'b0}} : cand + 1'b1;
      end else if (taking) begin
        fb_we <= 1'b1;
        fb_waddr <= slot_base + AW'(wbyte);
        case (wbyte)  // id, flags, then t16, x, y, z little endian
          4'd0: fb_wdata <= tok[79:72];
          4'd1: fb_wdata <= tok[71:64];
          4'd2: fb_wdata <= tok[55:48];
          4'd3: fb_wdata <= tok[63:56];
          4'd4: fb_wdata <= tok[39:32];
          4'd5: fb_wdata <= tok[47:40];
          4'd6: fb_wdata <= tok[23:16];
          4'd7: fb_wdata <= tok[31:24];
          4'd8: fb_wdata <= tok[7:0];
          default: fb_wdata <= tok[15:8];
        endcase
        wbyte <= wbyte + 4'd1;
        if (wbyte == 4'd9) taking <= 1'b0;
      end
    end
  end

  // ---- packets out
  // link_framer takes a packet as one byte stream: type, t (4 bytes LE),
  // len (2 bytes LE), then the payload; hdr_* hold the header being sent.
  reg  [7:0]  hdr_type;
  reg  [31:0] hdr_t;
  reg  [15:0] hdr_len;
  reg         p_valid;
  wire        p_ready;
  reg  [7:0]  p_data;

  // Packet kinds, in the order they follow a frame.
  localparam [2:0] K_SAMPLES = 3'd0, K_DELTAS = 3'd1, K_DECOUPLE = 3'd2, K_WRENCH = 3'd3,
                   K_CURVE = 3'd4, K_BUS = 3'd5, K_DEC = 3'd6;
  localparam [2:0] E_IDLE = 3'd0, E_HDR = 3'd1, E_READ = 3'd2, E_WAIT = 3'd3, E_OFFER = 3'd4,
                   E_VEC = 3'd5, E_HOFFER = 3'd6, E_NEXT = 3'd7;
  reg [2:0]  estate;
  reg [2:0]  e_kind;   // the packet being sent (or, in E_NEXT, the last one sent)
  reg [2:0]  h_idx;    // header byte being offered
  reg [AW-1:0] e_idx;
  reg [15:0] since_status;
  reg        per_now;  // this frame's packets include the periodic status ones
  reg        rej_pend; // a command was rejected: HALL_DECODE_STATUS is due
  reg        w_have;   // a wrench not sent yet
  reg [31:0] w_t;
  reg [199:0] w_vec;
  reg        dc_have;  // a DECOUPLE3 not sent yet
  reg [31:0] dc_tq;
  reg [111:0] dc_vec;
  reg [NC-1:0] fc_have;     // cells with a result in this frame
  // FORCE_CURVE records, byte j of cell c at {c, j}: a block RAM read like
  // the frame buffers (registers and their 11 * NC byte mux did not fit the
  // UP5K at 9 cells). force_curve holds its 88-bit record until out_ready:
  // it is written one byte per clock straight from force_curve's output
  // (11 clocks, out_ready with the last byte; the next result is 45+ clocks
  // away anyway, and the record is in fc_ram before FORCE_CURVE is sent: the
  // packets wait for force_curve's in_ready, low while it holds a result).
  reg  [7:0]  fc_ram [0:(1 << (CW + 4)) - 1];
  reg  [7:0]  fc_rdata;
  reg  [CW-1:0] rc;            // cell being sent
  reg  [3:0]  fc_wj, rj;       // byte being written; byte being sent
  assign fc_last = fc_wj == 4'd10;
  wire [NSENS-1:0] all = {NSENS{1'b1}};
  wire frame_done = (got == all) && !taking;

  // Register-sourced payloads, padded to one width: byte i at [8i +: 8].
  localparam integer VB0 = (NB * 10 > 25) ? NB * 10 : 25;
  localparam integer VB = (VB0 > DEC_BYTES) ? VB0 : DEC_BYTES;
  localparam integer VW = $clog2(VB);
  wire [VB*8-1:0] v_wrench = (VB*8)'(w_vec);
  wire [VB*8-1:0] v_bus = (VB*8)'(counters);
  wire [VB*8-1:0] v_dec = (VB*8)'(dec_status);
  wire [VB*8-1:0] v_decouple = (VB*8)'(dc_vec);
  wire [VB*8-1:0] v_sel = (e_kind == K_WRENCH) ? v_wrench : (e_kind == K_BUS) ? v_bus :
                          (e_kind == K_DECOUPLE) ? v_decouple : v_dec;
  // FORCE_CURVE byte rj of cell rc; a cell without a result in this frame
  // has force 0, t 0, flags REPLY, range 0.
  wire [7:0] curve_byte = fc_have[rc] ? fc_rdata : (rj == 4'd0) ? 8'(rc) : (rj == 4'd2) ? 8'h20 : 8'h00;
  wire [VW-1:0] v_idx = e_idx[VW-1:0];

  // What follows packet e_kind (in E_NEXT): the first kind after it that is
  // due; n_wait while the wrench of this frame is still being computed.
  wire n_wait = (e_kind == K_DELTAS) && !(ft_idle && dc_idle && fc_idle);
  reg        n_none;
  reg [2:0]  n_kind;
  always @(*) begin
    n_none = 1'b0;
    n_kind = K_DEC;
    if (e_kind < K_DELTAS && DELTAS != 0) n_kind = K_DELTAS;
    else if (e_kind < K_DECOUPLE && dc_have) n_kind = K_DECOUPLE;
    else if (e_kind < K_WRENCH && w_have) n_kind = K_WRENCH;
    else if (e_kind < K_CURVE && CURVE != 0) n_kind = K_CURVE;
    else if (e_kind < K_BUS && per_now) n_kind = K_BUS;
    else if (e_kind < K_DEC && DELTAS != 0 && (per_now || rej_pend)) n_kind = K_DEC;
    else n_none = 1'b1;
  end
  wire per_due = STATUS_EVERY != 0 && since_status + 16'd1 >= 16'(STATUS_EVERY);
  wire start_frame = (estate == E_IDLE) && frame_done;
  wire start_next = (estate == E_NEXT) && !n_wait && !n_none;
  wire [2:0] s_kind = start_frame ? K_SAMPLES : n_kind;
  wire [15:0] s_len = (s_kind == K_SAMPLES || s_kind == K_DELTAS) ? 16'(FB) :
                      (s_kind == K_WRENCH) ? 16'd25 : (s_kind == K_BUS) ? 16'(NB * 10) :
                      (s_kind == K_DECOUPLE) ? 16'd14 : (s_kind == K_CURVE) ? 16'(NC * 11) :
                      16'(DEC_BYTES);
  wire [7:0] s_type = (s_kind == K_SAMPLES) ? T_SAMPLES : (s_kind == K_DELTAS) ? T_DELTAS :
                      (s_kind == K_WRENCH) ? T_WRENCH : (s_kind == K_BUS) ? T_BUS_STATUS :
                      (s_kind == K_DECOUPLE) ? T_DECOUPLE : (s_kind == K_CURVE) ? T_CURVE :
                      T_DECODE_STATUS;
  wire e_from_ram = (e_kind == K_SAMPLES) || (e_kind == K_DELTAS) || (e_kind == K_CURVE);

  always @(posedge clk) begin
    if (rst) begin
      got <= {NSENS{1'b0}};
      emitting <= 1'b0;
      estate <= E_IDLE;
      e_kind <= K_SAMPLES;
      e_idx <= {AW{1'b0}};
      fb_raddr <= {AW{1'b0}};
      h_idx <= 3'd0;
      hdr_type <= T_SAMPLES;
      hdr_t <= 32'd0;
      hdr_len <= 16'd0;
      p_valid <= 1'b0;
      p_data <= 8'd0;
      since_status <= 16'd0;
      per_now <= 1'b0;
      rej_pend <= 1'b0;
      w_have <= 1'b0;
      w_t <= 32'd0;
      w_vec <= 200'd0;
      dc_have <= 1'b0;
      dc_tq <= 32'd0;
      dc_vec <= 112'd0;
      fc_have <= {NC{1'b0}};
      rc <= {CW{1'b0}};
      rj <= 4'd0;
    end else begin
      if (dc_valid) begin
        dc_vec <= dc_w;
        dc_tq <= dc_t;
      end
      if (fc_valid && fc_last) fc_have[fc_cell] <= 1'b1;
      if (taking && wbyte == 4'd9) got[tok[72 +: SW]] <= 1'b1;
      if (ft_valid) begin
        w_vec <= ft_w;
        w_t <= ft_t;
      end
      if (start_frame) begin
        emitting <= 1'b1;
        per_now <= per_due;
        since_status <= per_due ? 16'd0 : since_status + 16'd1;
      end
      if (start_frame || start_next) begin
        e_kind <= s_kind;
        hdr_type <= s_type;
        hdr_t <= (s_kind == K_WRENCH) ? w_t : (s_kind == K_DECOUPLE) ? dc_tq : t_us;
        hdr_len <= s_len;
        h_idx <= 3'd0;
        estate <= E_HDR;
      end
      // A flag set and cleared in one clock stays set: its packet goes later.
      w_have <= ft_valid || (w_have && !(start_next && s_kind == K_WRENCH));
      rej_pend <= cmd_reject || (rej_pend && !(start_next && s_kind == K_DEC));
      dc_have <= dc_valid || (dc_have && !(start_next && s_kind == K_DECOUPLE));
      case (estate)
        E_IDLE: ;
        E_NEXT:
          if (!n_wait && n_none) begin
            emitting <= 1'b0;
            fc_have <= {NC{1'b0}};  // every result of this frame has been sent
            estate <= E_IDLE;
          end
        E_HDR: begin
          p_valid <= 1'b1;
          case (h_idx)
            3'd0: p_data <= hdr_type;
            3'd1: p_data <= hdr_t[7:0];
            3'd2: p_data <= hdr_t[15:8];
            3'd3: p_data <= hdr_t[23:16];
            3'd4: p_data <= hdr_t[31:24];
            3'd5: p_data <= hdr_len[7:0];
            default: p_data <= hdr_len[15:8];
          endcase
          estate <= E_HOFFER;
        end
        E_HOFFER:
          if (p_ready) begin
            p_valid <= 1'b0;
            if (h_idx == 3'd6) begin
              e_idx <= {AW{1'b0}};
              fb_raddr <= {AW{1'b0}};
              rc <= {CW{1'b0}};
              rj <= 4'd0;
              estate <= e_from_ram ? E_READ : E_VEC;
            end else begin
              h_idx <= h_idx + 3'd1;
              estate <= E_HDR;
            end
          end
        E_READ: estate <= E_WAIT;  // the RAM's read takes a clock
        E_WAIT: begin
          p_valid <= 1'b1;
          p_data <= (e_kind == K_DELTAS) ? fb2_rdata : (e_kind == K_CURVE) ? curve_byte : fb_rdata;
          estate <= E_OFFER;
        end
        E_VEC: begin
          p_valid <= 1'b1;
          p_data <= v_sel[v_idx*8 +: 8];
          estate <= E_OFFER;
        end
        default:  // E_OFFER
          if (p_ready) begin
            p_valid <= 1'b0;
            e_idx <= e_idx + 1'b1;
            fb_raddr <= e_idx + 1'b1;
            rj <= (rj == 4'd10) ? 4'd0 : rj + 4'd1;
            if (rj == 4'd10) rc <= rc + 1'b1;
            if ({{(16 - AW) {1'b0}}, e_idx} == hdr_len - 16'd1) begin
              if (e_kind == K_SAMPLES) got <= {NSENS{1'b0}};
              estate <= E_NEXT;
            end else begin
              estate <= e_from_ram ? E_READ : E_VEC;
            end
          end
      endcase
    end
  end

  always @(posedge clk) begin
    if (fc_valid) fc_ram[{fc_cell, fc_wj}] <= fc_rec[fc_wj*8 +: 8];
    fc_rdata <= fc_ram[{rc, rj}];
  end
  always @(posedge clk) begin
    if (rst) fc_wj <= 4'd0;
    else if (fc_valid) fc_wj <= fc_last ? 4'd0 : fc_wj + 4'd1;
  end

  generate
    if (EXT_LINK == 0) begin : g_link
      wire l_valid, l_ready;
      wire [7:0] l_data, l_seq;
      link_framer u_framer (
          .clk(clk), .rst(rst), .s_valid(p_valid), .s_ready(p_ready), .s_data(p_data),
          .m_valid(l_valid), .m_ready(l_ready), .m_data(l_data), .seq(l_seq));
      uart_tx #(.CLK_HZ(CLK_HZ), .BAUD(BAUD)) u_tx (
          .clk(clk), .rst(rst), .s_valid(l_valid), .s_ready(l_ready), .s_data(l_data),
          .tx(uart_txd));
      assign pkt_valid = 1'b0;
      assign pkt_data = 8'd0;
      wire unused_link = &{1'b0, l_seq, pkt_ready};
    end else begin : g_ext_link
      assign pkt_valid = p_valid;
      assign pkt_data = p_data;
      assign p_ready = pkt_ready;
      assign uart_txd = 1'b1;
    end
  endgenerate
endmodule
`default_nettype wire
