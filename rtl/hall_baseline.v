`default_nettype none
// hall_baseline: Hall sample tokens -> baseline-removed field tokens.
// Bit-exact implementation of hls/hall_baseline.h (formats, rounding,
// capture and drop rules are stated there):
//   v = code - OFFSET (OFFSET 0: two's complement code), per axis;
//   capture: the first 2^CAPTURE_LOG2 data tokens of each sensor are summed,
//   base = (sum + 2^(n-1)) >>> n; afterwards d = sat16(v - base).
// Tokens without data (flags & 8'h78) or of ids outside ID_BASE..+NS-1 are
// dropped and counted (`dropped`, saturating). set_* loads one axis'
// baseline (a sensor with all three axes loaded stops capturing);
// `recapture` restarts every sensor's capture.
//
// Storage: the per-sensor state lives in block RAM (plain synchronous-read
// memories, SB_RAM40_4K on the iCE40) so that 16 or more sensors fit the
// UP5K: `acc` holds each sensor's capture count and three sums (the sums
// freeze once captured and the captured baseline is their rounded mean,
// computed when a delta is formed, so a finished capture needs no write of
// its own), `sb_*` the baselines loaded by set_*. Registers keep only what
// must change for all sensors at once or be read combinationally: a
// `live` bit per sensor (0: its acc word is stale and reads as zero, which
// is how `recapture` clears every sensor in one cycle) and the 3-bit mask of
// loaded axes (an axis with its bit set takes its baseline from sb_*).
//
// Timing: a data token takes two cycles: the handshake cycle reads the
// sensor's RAM words, the next computes, writes the acc word back and loads
// the output register. So II = 2 for data tokens (in_ready is low in the
// second cycle), II = 1 for dropped ones, latency 2 (out_valid two cycles
// after the input handshake); in_ready = !busy && (!out_valid || out_ready).
// Commands apply in the cycle they are given and come after a token taken
// in the same cycle (as before the RAMs): the token sees the mask and sb_*
// as they were at its handshake, and its write-back touches neither; a
// recapture in either of its two cycles cancels its write-back (live stays
// 0), as the token's update came before the recapture.
module hall_baseline #(
    parameter integer NS = 16,
    parameter integer CAPTURE_LOG2 = 4,
    parameter integer ID_BASE = 0,
    parameter [15:0] OFFSET_X = 16'd0,
    parameter [15:0] OFFSET_Y = 16'd0,
    parameter [15:0] OFFSET_Z = 16'd0,
    parameter integer SW = (NS > 1) ? $clog2(NS) : 1
) (
    input  wire        clk,
    input  wire        rst,
    input  wire        in_valid,
    output wire        in_ready,
    input  wire [7:0]  in_id,
    input  wire [31:0] in_t,
    input  wire [15:0] in_x,
    input  wire [15:0] in_y,
    input  wire [15:0] in_z,
    input  wire [7:0]  in_flags,
    output reg         out_valid,
    input  wire        out_ready,
    output reg  [7:0]  out_id,
    output reg  [31:0] out_t,
    output reg  [15:0] out_dx,  // signed
    output reg  [15:0] out_dy,
    output reg  [15:0] out_dz,
    output reg  [7:0]  out_flags,
    input  wire        set_valid,
    input  wire [SW-1:0] set_sensor,
    input  wire [1:0]  set_axis,
    input  wire [15:0] set_value,
    input  wire        recapture,
    output reg  [15:0] dropped
);
  generate
    if (NS < 1 || NS > 64) begin : g_bad_ns
      illegal_parameter_NS_must_be_1_to_64 u_bad();
    end
    if (CAPTURE_LOG2 < 0 || CAPTURE_LOG2 > 15) begin : g_bad_cap
      illegal_parameter_CAPTURE_LOG2_must_be_0_to_15 u_bad();
    end
    if (ID_BASE < 0 || ID_BASE + NS > 256) begin : g_bad_id
      illegal_parameter_ID_BASE_plus_NS_must_fit_8_bits u_bad();
    end
  endgenerate

  localparam integer CW = CAPTURE_LOG2 + 1;
  localparam [CW-1:0] FULL = {1'b1, {CAPTURE_LOG2{1'b0}}};
  // A sum of 2^n values of 17 bits needs 17 + n bits.
  localparam integer UW = 17 + CAPTURE_LOG2;
  localparam integer AW = CW + 3 * UW;  // acc word: count, sum z, sum y, sum x

  (* ram_style = "block" *) reg [AW-1:0] acc [0:NS-1];
  (* ram_style = "block" *) reg [15:0] sb_x [0:NS-1];
  (* ram_style = "block" *) reg [15:0] sb_y [0:NS-1];
  (* ram_style = "block" *) reg [15:0] sb_z [0:NS-1];
  reg [NS-1:0] live;
  reg [2:0] set_mask [0:NS-1];

  // The token between its handshake and its write-back (p_*).
  reg          busy;
  reg [SW-1:0] p_s;
  reg [7:0]    p_id, p_flags;
  reg [31:0]   p_t;
  reg signed [16:0] p_v0, p_v1, p_v2;
  reg [2:0]    p_mask;
  reg          p_live, p_kill;
  reg [AW-1:0] acc_rd;
  reg [15:0]   sbx_rd, sby_rd, sbz_rd;

  assign in_ready = !busy && (!out_valid || out_ready);
  wire take = in_valid && in_ready;

  wire [8:0] rel = {1'b0, in_id} - ID_BASE[8:0];
  wire in_range = !rel[8] && ({1'b0, rel[7:0]} < NS[8:0]);
  wire [SW-1:0] s = rel[SW-1:0];
  wire no_data = (in_flags & 8'h78) != 8'd0;
  wire use_tok = in_range && !no_data;

  // Signed values of the three codes.
  function signed [16:0] value(input [15:0] code, input [15:0] offset);
    value = (offset == 16'd0) ? {code[15], code} : $signed({1'b0, code}) - $signed({1'b0, offset});
  endfunction

  // x fits int16 exactly when its top three bits agree (a sign test, not
  // two 18-bit comparisons: fewer LUTs and carries).
  function [15:0] sat16(input signed [17:0] x);
    if (x[17:15] == 3'b000 || x[17:15] == 3'b111) sat16 = x[15:0];
    else sat16 = x[17] ? 16'h8000 : 16'h7FFF;
  endfunction
  // The mean of 2^n values of 17 bits fits 16 bits (|v| <= 32768): the
  // rounded shift's top bits are sign copies.
  function signed [15:0] mean(input signed [UW-1:0] sm);
    /* verilator lint_off UNUSEDSIGNAL */
    reg signed [UW-1:0] r;
    /* verilator lint_on UNUSEDSIGNAL */
    begin
      if (CAPTURE_LOG2 == 0) r = sm;
      else r = (sm + ({{(UW - 1){1'b0}}, 1'b1} <<< (CAPTURE_LOG2 > 0 ? CAPTURE_LOG2 - 1 : 0))) >>> CAPTURE_LOG2;
      mean = r[15:0];
    end
  endfunction
  // The baseline of one axis: loaded, or the capture's mean.
  function [17:0] base18(input loaded, input [15:0] sb, input signed [UW-1:0] sm);
    reg [15:0] b;
    begin
      b = loaded ? sb : mean(sm);
      base18 = {{2{b[15]}}, b};
    end
  endfunction

  // Second cycle: the sensor's state as read (zero when not live).
  wire [AW-1:0] st = p_live ? acc_rd : {AW{1'b0}};
  wire [CW-1:0] cnt = st[AW-1 -: CW];
  wire signed [UW-1:0] sum_x = st[0 +: UW];
  wire signed [UW-1:0] sum_y = st[UW +: UW];
  wire signed [UW-1:0] sum_z = st[2 * UW +: UW];
  wire captured = (cnt == FULL) || (p_mask == 3'b111);
  wire [UW-1:0] nsx = sum_x + {{(UW - 17){p_v0[16]}}, p_v0};
  wire [UW-1:0] nsy = sum_y + {{(UW - 17){p_v1[16]}}, p_v1};
  wire [UW-1:0] nsz = sum_z + {{(UW - 17){p_v2[16]}}, p_v2};
  wire acc_we = busy && !captured;

  // A set_sensor that names no sensor is ignored.
  wire set_ok;
  generate
    if (NS == (1 << SW)) begin : g_set_all
      assign set_ok = 1'b1;
    end else begin : g_set_some
      assign set_ok = {1'b0, set_sensor} < NS[SW:0];
    end
  endgenerate
  wire set_we = set_valid && set_axis != 2'd3 && set_ok;

  // The RAMs: one synchronous read port (read at the handshake) and one
  // write port each. Only sb_* can be written in a read cycle (a command in
  // a token's handshake cycle); the read returns the value from before it
  // (Yosys emulates that read-first behaviour around the SB_RAM40_4K).
  always @(posedge clk) begin
    if (acc_we) acc[p_s] <= {cnt + 1'b1, nsz, nsy, nsx};
    if (take) acc_rd <= acc[s];
  end
  always @(posedge clk) begin
    if (set_we && set_axis == 2'd0) sb_x[set_sensor] <= set_value;
    if (set_we && set_axis == 2'd1) sb_y[set_sensor] <= set_value;
    if (set_we && set_axis == 2'd2) sb_z[set_sensor] <= set_value;
    if (take) begin
      sbx_rd <= sb_x[s];
      sby_rd <= sb_y[s];
      sbz_rd <= sb_z[s];
    end
  end

  integer k;
  always @(posedge clk) begin
    if (acc_we && !p_kill) live[p_s] <= 1'b1;
    if (set_we) set_mask[set_sensor] <= set_mask[set_sensor] | (3'b001 << set_axis);
    if (rst || recapture) begin
      live <= {NS{1'b0}};
      for (k = 0; k < NS; k = k + 1) set_mask[k] <= 3'b000;
    end
  end

  always @(posedge clk) begin
    if (rst) begin
      busy <= 1'b0;
      p_s <= {SW{1'b0}};
      p_id <= 8'd0;
      p_t <= 32'd0;
      p_flags <= 8'd0;
      {p_v0, p_v1, p_v2} <= 51'd0;
      p_mask <= 3'b000;
      p_live <= 1'b0;
      p_kill <= 1'b0;
    end else begin
      busy <= take && use_tok;
      if (take) begin
        p_s <= s;
        p_id <= in_id;
        p_t <= in_t;
        p_flags <= in_flags;
        p_v0 <= value(in_x, OFFSET_X);
        p_v1 <= value(in_y, OFFSET_Y);
        p_v2 <= value(in_z, OFFSET_Z);
        p_mask <= set_mask[s];
        p_live <= live[s];
        p_kill <= recapture;
      end
    end
  end

  always @(posedge clk) begin
    if (rst) begin
      out_valid <= 1'b0;
      dropped <= 16'd0;
      out_id <= 8'd0;
      out_t <= 32'd0;
      {out_dx, out_dy, out_dz} <= 48'd0;
      out_flags <= 8'd0;
    end else begin
      if (out_valid && out_ready) out_valid <= 1'b0;
      if (take && !use_tok && dropped != 16'hFFFF) dropped <= dropped + 1'b1;
      // The output register is free here: the handshake needed it free or
      // leaving.
      if (busy && captured) begin
        out_valid <= 1'b1;
        out_id <= p_id;
        out_t <= p_t;
        out_flags <= p_flags;
        out_dx <= sat16({p_v0[16], p_v0} - base18(p_mask[0], sbx_rd, sum_x));
        out_dy <= sat16({p_v1[16], p_v1} - base18(p_mask[1], sby_rd, sum_y));
        out_dz <= sat16({p_v2[16], p_v2} - base18(p_mask[2], sbz_rd, sum_z));
      end
    end
  end
endmodule
`default_nettype wire
