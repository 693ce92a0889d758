`default_nettype none
// force_curve: seed-003 multi-range force curves, one per cell.
// Bit-exact implementation of hls/force_curve.h (formats, rounding and the
// breakpoint search are stated there).
//
// Input: hall_baseline tokens of sensors ID_BASE .. ID_BASE+NC-1 (one per
// cell; others are ignored). GAIN_X/Y/Z (UQ4.12 uT/LSB) and the range ends
// LOCK_MN (NR x 32-bit signed mN, entry r at [32r +: 32]) are parameters of
// the scene's setting; the curves (NB breakpoints per cell: db in 1/64 uT,
// f in mN, slope in Q15.16 mN per 1/64 uT) are loaded at run time through
// t_valid/t_cell/t_index/t_which (0 db, 1 f, 2 slope)/t_value.
// Schedule, the input handshake being cycle 0 (one multiplier, one
// restoring square-root step per cycle):
//   1..3   p_a = (d_a * g_a + 32) >>> 6, one axis per cycle
//   4..6   s += p_a^2
//   7..30  24 square-root steps
//   31..   breakpoint reads db[1] .. db[NB-2] (cycles 31 .. NB + 28), each
//          compared one cycle later (up to NB + 29); then one cycle reading
//          db[k], f[k], slope[k], one interpolation cycle (the force) and
//          one cycle for its range (a cycle of its own so that the path
//          RAM -> multiplier -> saturation -> range compares does not limit
//          the clock: 11.2 MHz on the UP5K in one cycle, under its 12)
// out_valid rises at cycle NB + 33 (46 for NB = 13) and holds until
// out_ready; in_ready is high only while idle.
module force_curve #(
    parameter integer NC = 9,
    parameter integer NB = 13,
    parameter integer NR = 3,
    parameter integer ID_BASE = 0,
    parameter [15:0] GAIN_X = 16'd1540,   // 0.376 uT/LSB (XY at GAIN_SEL 3, RES 0)
    parameter [15:0] GAIN_Y = 16'd1540,
    parameter [15:0] GAIN_Z = 16'd2478,   // 0.605 uT/LSB (Z)
    parameter [NR*32-1:0] LOCK_MN = {32'sd16200, 32'sd4800, 32'sd900},
    parameter integer CW = (NC > 1) ? $clog2(NC) : 1
) (
    input  wire        clk,
    input  wire        rst,
    input  wire        in_valid,
    output wire        in_ready,
    input  wire [7:0]  in_id,
    input  wire [31:0] in_t,
    input  wire [15:0] in_dx,
    input  wire [15:0] in_dy,
    input  wire [15:0] in_dz,
    input  wire [7:0]  in_flags,
    output reg         out_valid,
    input  wire        out_ready,
    output reg  [7:0]  out_cell,
    output reg  [31:0] out_t,
    output reg  [31:0] out_force_mn,  // signed
    output reg  [7:0]  out_range,
    output reg  [7:0]  out_flags,
    input  wire        t_valid,
    input  wire [CW-1:0] t_cell,
    input  wire [4:0]  t_index,
    input  wire [1:0]  t_which,
    input  wire [31:0] t_value
);
  generate
    if (NC < 1 || NC > 64) begin : g_bad_nc
      illegal_parameter_NC_must_be_1_to_64 u_bad();
    end
    if (NB < 3 || NB > 32) begin : g_bad_nb
      illegal_parameter_NB_must_be_3_to_32 u_bad();
    end
    if (NR < 1 || NR > 8) begin : g_bad_nr
      illegal_parameter_NR_must_be_1_to_8 u_bad();
    end
    if (ID_BASE < 0 || ID_BASE + NC > 256) begin : g_bad_id
      illegal_parameter_ID_BASE_plus_NC_must_fit_8_bits u_bad();
    end
  endgenerate

  localparam [2:0] S_IDLE = 3'd0, S_SCALE = 3'd1, S_SQ = 3'd2, S_ROOT = 3'd3, S_SEARCH = 3'd4,
                   S_FETCH = 3'd5, S_INTERP = 3'd6, S_OUT = 3'd7;
  reg [2:0] state;
  reg [4:0] cnt;

  // Curve RAMs, address {cur_cell, index}.
  (* no_rw_check *) reg [31:0] db_mem [0:(1 << (CW + 5)) - 1];
  (* no_rw_check *) reg [31:0] f_mem [0:(1 << (CW + 5)) - 1];
  (* no_rw_check *) reg [31:0] sl_mem [0:(1 << (CW + 5)) - 1];
  reg [4:0] raddr;
  reg signed [31:0] db_q, f_q, sl_q;
  always @(posedge clk) begin
    if (t_valid && t_which == 2'd0) db_mem[{t_cell, t_index}] <= t_value;
    if (t_valid && t_which == 2'd1) f_mem[{t_cell, t_index}] <= t_value;
    if (t_valid && t_which == 2'd2) sl_mem[{t_cell, t_index}] <= t_value;
    db_q <= db_mem[{cur_cell, raddr}];
    f_q <= f_mem[{cur_cell, raddr}];
    sl_q <= sl_mem[{cur_cell, raddr}];
  end

  assign in_ready = (state == S_IDLE);
  wire [8:0] rel = {1'b0, in_id} - 9'(ID_BASE);
  wire mine = !rel[8] && rel[7:0] < 8'(NC);

  reg [CW-1:0] cur_cell;
  reg signed [15:0] d [0:2];
  reg signed [31:0] p [0:2];
  reg [47:0] ssum;     // radicand, consumed from the top
  reg [25:0] rem;      // partial remainder
  reg [23:0] root;
  reg [4:0] k;         // breakpoint found so far
  reg cmp_v;           // db_q holds breakpoint cmp_i
  reg rng_pend;        // S_OUT: out_force_mn is set, its range not yet
  reg [4:0] cmp_i;

  // SCALE: one 16 x 16 product per cycle.
  wire [1:0] ax = cnt[1:0];
  wire [15:0] g = (ax == 2'd0) ? GAIN_X : (ax == 2'd1) ? GAIN_Y : GAIN_Z;
  wire signed [32:0] dg = d[ax] * $signed({1'b0, g});
  // |d g| < 2^31, so |p| < 2^25 and p^2 < 2^50; the top bits are sign copies.
  /* verilator lint_off UNUSEDSIGNAL */
  wire signed [32:0] pr = (dg + 33'sd32) >>> 6;
  // SQ: the sum of three squares of 25-bit values fits the 48-bit radicand
  // only for |p| < 2^23 (|dB| < 1.3 T): the sensors' range is far below.
  wire signed [63:0] psq = p[ax] * p[ax];
  // ROOT: one restoring step; the remainder stays below 2 root + 1 < 2^25.
  wire [27:0] rtry = {rem, ssum[47:46]};
  wire [27:0] trial = {2'b00, root, 2'b01};
  wire step_one = rtry >= trial;
  wire [27:0] rnext = step_one ? rtry - trial : rtry;
  /* verilator lint_on UNUSEDSIGNAL */
  // INTERP.
  wire signed [32:0] dm = $signed({9'd0, root}) - 33'(db_q);
  wire signed [64:0] x = dm * sl_q;
  wire signed [64:0] fi = 65'(f_q) + ((x + 65'sd32768) >>> 16);
  wire [31:0] fsat = (fi > 65'sd2147483647) ? 32'h7FFFFFFF :
                     (fi < -65'sd2147483648) ? 32'h80000000 : fi[31:0];
  // Range of the output force: the count of lock forces below it, at most NR - 1.
  function [7:0] range_of(input [31:0] f);
    integer r;
    begin
      range_of = 8'd0;
      for (r = 0; r < NR; r = r + 1)
        if ($signed(f) > $signed(LOCK_MN[32*r +: 32])) range_of = 8'(r + 1);
      if (range_of > 8'(NR - 1)) range_of = 8'(NR - 1);
    end
  endfunction

  always @(posedge clk) begin
    if (rst) begin
      state <= S_IDLE;
      out_valid <= 1'b0;
      cnt <= 5'd0;
      raddr <= 5'd0;
      cur_cell <= {CW{1'b0}};
      out_cell <= 8'd0;
      out_t <= 32'd0;
      out_force_mn <= 32'd0;
      out_range <= 8'd0;
      out_flags <= 8'd0;
      ssum <= 48'd0;
      rem <= 26'd0;
      root <= 24'd0;
      k <= 5'd0;
      cmp_v <= 1'b0;
      cmp_i <= 5'd0;
      rng_pend <= 1'b0;
      d[0] <= 16'sd0; d[1] <= 16'sd0; d[2] <= 16'sd0;
      p[0] <= 32'sd0; p[1] <= 32'sd0; p[2] <= 32'sd0;
    end else begin
      case (state)
        S_IDLE: if (in_valid && mine) begin
          cur_cell <= rel[CW-1:0];
          out_cell <= 8'(rel[7:0]);
          out_t <= in_t;
          out_flags <= in_flags;
          d[0] <= in_dx; d[1] <= in_dy; d[2] <= in_dz;
          cnt <= 5'd0;
          state <= S_SCALE;
        end
        S_SCALE: begin
          p[ax] <= pr[31:0];
          cnt <= (cnt == 5'd2) ? 5'd0 : cnt + 1'b1;
          if (cnt == 5'd2) begin
            state <= S_SQ;
            ssum <= 48'd0;
          end
        end
        S_SQ: begin
          ssum <= ssum + psq[47:0];
          cnt <= (cnt == 5'd2) ? 5'd0 : cnt + 1'b1;
          if (cnt == 5'd2) begin
            state <= S_ROOT;
            rem <= 26'd0;
            root <= 24'd0;
          end
        end
        S_ROOT: begin
          ssum <= {ssum[45:0], 2'b00};
          rem <= rnext[25:0];
          root <= {root[22:0], step_one};
          cnt <= cnt + 1'b1;
          if (cnt == 5'd23) begin
            state <= S_SEARCH;
            raddr <= 5'd1;
            k <= 5'd0;
            cmp_v <= 1'b0;
          end
        end
        S_SEARCH: begin
          // Issue reads of db[1] .. db[NB-2]; compare each one cycle later.
          cmp_v <= raddr <= 5'(NB - 2);
          cmp_i <= raddr;
          if (raddr <= 5'(NB - 2)) raddr <= raddr + 1'b1;
          if (cmp_v && $signed(db_q) <= $signed({8'd0, root})) k <= cmp_i;
          if (cmp_v && cmp_i == 5'(NB - 2)) begin
            state <= S_FETCH;
            raddr <= ($signed(db_q) <= $signed({8'd0, root})) ? cmp_i : k;
          end
        end
        S_FETCH: state <= S_INTERP;  // the RAMs read db[k], f[k], slope[k]
        S_INTERP: begin
          out_force_mn <= fsat;
          rng_pend <= 1'b1;
          state <= S_OUT;
        end
        default:  // S_OUT
          if (rng_pend) begin
            out_range <= range_of(out_force_mn);
            out_valid <= 1'b1;
            rng_pend <= 1'b0;
          end else if (out_ready) begin
            out_valid <= 1'b0;
            state <= S_IDLE;
          end
      endcase
    end
  end
endmodule
`default_nettype wire
