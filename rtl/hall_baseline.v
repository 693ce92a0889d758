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
// Timing: II = 1, latency 1 (out_valid the cycle after the input handshake);
// in_ready = !out_valid || out_ready.
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

  reg signed [31:0] sum_x [0:NS-1], sum_y [0:NS-1], sum_z [0:NS-1];
  reg signed [15:0] base_x [0:NS-1], base_y [0:NS-1], base_z [0:NS-1];
  reg [CW-1:0] count [0:NS-1];
  reg [2:0] set_mask [0:NS-1];

  assign in_ready = !out_valid || out_ready;
  wire take = in_valid && in_ready;

  wire [8:0] rel = {1'b0, in_id} - ID_BASE[8:0];
  wire in_range = !rel[8] && ({1'b0, rel[7:0]} < NS[8:0]);
  wire [SW-1:0] s = rel[SW-1:0];
  wire no_data = (in_flags & 8'h78) != 8'd0;
  wire use_tok = in_range && !no_data;
  wire captured = (count[s] == FULL) || (set_mask[s] == 3'b111);

  // Signed values of the three codes.
  function signed [16:0] value(input [15:0] code, input [15:0] offset);
    value = (offset == 16'd0) ? {code[15], code} : $signed({1'b0, code}) - $signed({1'b0, offset});
  endfunction
  wire signed [16:0] v0 = value(in_x, OFFSET_X);
  wire signed [16:0] v1 = value(in_y, OFFSET_Y);
  wire signed [16:0] v2 = value(in_z, OFFSET_Z);

  function [15:0] sat16(input signed [17:0] x);
    if (x > 18'sd32767) sat16 = 16'h7FFF;
    else if (x < -18'sd32768) sat16 = 16'h8000;
    else sat16 = x[15:0];
  endfunction
  // The mean of 2^n values of 17 bits fits 16 bits (|v| <= 32768): the
  // rounded shift's top bits are sign copies.
  function signed [15:0] mean(input signed [31:0] sm);
    /* verilator lint_off UNUSEDSIGNAL */
    reg signed [31:0] r;
    /* verilator lint_on UNUSEDSIGNAL */
    begin
      if (CAPTURE_LOG2 == 0) r = sm;
      else r = (sm + (32'sd1 <<< (CAPTURE_LOG2 > 0 ? CAPTURE_LOG2 - 1 : 0))) >>> CAPTURE_LOG2;
      mean = r[15:0];
    end
  endfunction

  wire signed [31:0] nsx = sum_x[s] + {{15{v0[16]}}, v0};
  wire signed [31:0] nsy = sum_y[s] + {{15{v1[16]}}, v1};
  wire signed [31:0] nsz = sum_z[s] + {{15{v2[16]}}, v2};

  // A set_sensor that names no sensor is ignored.
  wire set_ok;
  generate
    if (NS == (1 << SW)) begin : g_set_all
      assign set_ok = 1'b1;
    end else begin : g_set_some
      assign set_ok = {1'b0, set_sensor} < NS[SW:0];
    end
  endgenerate

  integer k;
  always @(posedge clk) begin
    if (rst || recapture) begin
      for (k = 0; k < NS; k = k + 1) begin
        sum_x[k] <= 32'sd0;
        sum_y[k] <= 32'sd0;
        sum_z[k] <= 32'sd0;
        base_x[k] <= 16'sd0;
        base_y[k] <= 16'sd0;
        base_z[k] <= 16'sd0;
        count[k] <= {CW{1'b0}};
        set_mask[k] <= 3'b000;
      end
    end else begin
      if (take && use_tok && !captured) begin
        sum_x[s] <= nsx;
        sum_y[s] <= nsy;
        sum_z[s] <= nsz;
        count[s] <= count[s] + 1'b1;
        if (count[s] + 1'b1 == FULL) begin
          if (!set_mask[s][0]) base_x[s] <= mean(nsx);
          if (!set_mask[s][1]) base_y[s] <= mean(nsy);
          if (!set_mask[s][2]) base_z[s] <= mean(nsz);
        end
      end
      if (set_valid && set_axis != 2'd3 && set_ok) begin
        case (set_axis)
          2'd0: base_x[set_sensor] <= set_value;
          2'd1: base_y[set_sensor] <= set_value;
          default: base_z[set_sensor] <= set_value;
        endcase
        set_mask[set_sensor] <= set_mask[set_sensor] | (3'b001 << set_axis);
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
      if (take) begin
        if (!use_tok) begin
          if (dropped != 16'hFFFF) dropped <= dropped + 1'b1;
        end else if (captured) begin
          out_valid <= 1'b1;
          out_id <= in_id;
          out_t <= in_t;
          out_flags <= in_flags;
          out_dx <= sat16({v0[16], v0} - {{2{base_x[s][15]}}, base_x[s]});
          out_dy <= sat16({v1[16], v1} - {{2{base_y[s][15]}}, base_y[s]});
          out_dz <= sat16({v2[16], v2} - {{2{base_z[s][15]}}, base_z[s]});
        end
      end
    end
  end
endmodule
`default_nettype wire
