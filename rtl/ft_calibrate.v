`default_nettype none
// ft_calibrate: six-axis force/torque W = C * dB of seed 002 (MagTac).
// Bit-exact implementation of hls/ft_calibrate.h (formats, rounding,
// saturation and frame rules are stated there).
//
// Input: hall_baseline tokens of sensors ID_BASE .. ID_BASE+2 (others are
// ignored); sensor ID_BASE+2 closes a frame, computed when all three gave a
// token since the last frame (else skipped, `skipped` counts, saturating).
// C: 6 x 9 signed entries Q(31-C_FRAC).C_FRAC in a RAM (address {row, col}),
// written through c_valid/c_row/c_col/c_value (the LOAD_C command) at any
// time; a frame uses the entries as they are while it is computed.
// Datapath: one 32 x 16 signed product per cycle into a 52-bit accumulator,
// row by row; each row's sum is rounded half up by C_FRAC bits and
// saturated to 32 bits.
// Timing: the closing token's handshake is cycle 0; the RAM reads run in
// cycles 1..54 and the products in 2..55; out_valid is high from cycle 56
// until out_ready. in_ready is high only while idle (not computing or
// holding an output).
module ft_calibrate #(
    parameter integer C_FRAC = 16,
    parameter integer ID_BASE = 0
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
    output reg  [31:0] out_t,
    output reg  [31:0] out_w0,
    output reg  [31:0] out_w1,
    output reg  [31:0] out_w2,
    output reg  [31:0] out_w3,
    output reg  [31:0] out_w4,
    output reg  [31:0] out_w5,
    output reg  [7:0]  out_flags,
    input  wire        c_valid,
    input  wire [2:0]  c_row,
    input  wire [3:0]  c_col,
    input  wire [31:0] c_value,
    output reg  [15:0] skipped
);
  generate
    if (C_FRAC < 1 || C_FRAC > 30) begin : g_bad_frac
      illegal_parameter_C_FRAC_must_be_1_to_30 u_bad();
    end
    if (ID_BASE < 0 || ID_BASE + 3 > 256) begin : g_bad_id
      illegal_parameter_ID_BASE_plus_3_must_fit_8_bits u_bad();
    end
  endgenerate

  localparam [1:0] S_IDLE = 2'd0, S_MAC = 2'd1, S_OUT = 2'd2;
  reg [1:0] state;

  (* no_rw_check *) reg [31:0] c_mem [0:127];
  reg signed [31:0] c_q;
  reg [2:0] row, row_q;   // address issued / address of c_q
  reg [3:0] col, col_q;
  reg issue, vq;          // a read is issued this cycle / c_q holds data
  reg signed [15:0] db [0:8];
  reg [2:0] seen;
  reg [7:0] flags_acc;
  reg signed [51:0] acc;

  assign in_ready = (state == S_IDLE);
  wire take = in_valid && in_ready;
  wire [8:0] rel = {1'b0, in_id} - ID_BASE[8:0];
  wire mine = !rel[8] && rel[7:0] < 8'd3;
  wire [1:0] s = rel[1:0];
  wire [3:0] b3 = {1'b0, s, 1'b0} + {2'b00, s};  // 3 s: the sensor's first input

  always @(posedge clk) begin
    if (c_valid) c_mem[{c_row, c_col}] <= c_value;
    c_q <= c_mem[{row, col}];
  end

  // The product of the entry read last cycle and its input.
  wire signed [47:0] prod = c_q * db[col_q];
  wire signed [51:0] acc_next = ((col_q == 4'd0) ? 52'sd0 : acc) + {{4{prod[47]}}, prod};
  wire signed [51:0] rounded = (acc_next + (52'sd1 <<< (C_FRAC - 1))) >>> C_FRAC;
  wire [31:0] w = (rounded > 52'sd2147483647) ? 32'h7FFFFFFF :
                  (rounded < -52'sd2147483648) ? 32'h80000000 : rounded[31:0];

  integer k;
  always @(posedge clk) begin
    if (rst) begin
      state <= S_IDLE;
      out_valid <= 1'b0;
      skipped <= 16'd0;
      seen <= 3'b000;
      flags_acc <= 8'd0;
      row <= 3'd0;
      col <= 4'd0;
      issue <= 1'b0;
      vq <= 1'b0;
      acc <= 52'sd0;
      out_t <= 32'd0;
      out_flags <= 8'd0;
      {out_w0, out_w1, out_w2, out_w3, out_w4, out_w5} <= 192'd0;
      for (k = 0; k < 9; k = k + 1) db[k] <= 16'sd0;
    end else begin
      case (state)
        S_IDLE: if (take && mine) begin
          db[b3] <= in_dx;
          db[b3 + 4'd1] <= in_dy;
          db[b3 + 4'd2] <= in_dz;
          if (s == 2'd2) begin
            seen <= 3'b000;
            flags_acc <= 8'd0;
            if ((seen | 3'b100) == 3'b111) begin
              state <= S_MAC;
              out_t <= in_t;
              out_flags <= flags_acc | in_flags;
              row <= 3'd0;
              col <= 4'd0;
              issue <= 1'b1;
            end else if (skipped != 16'hFFFF) begin
              skipped <= skipped + 1'b1;
            end
          end else begin
            seen <= seen | (3'b001 << s);
            flags_acc <= flags_acc | in_flags;
          end
        end
        S_MAC: begin
          // Issue the next read.
          vq <= issue;
          row_q <= row;
          col_q <= col;
          if (issue) begin
            if (col == 4'd8) begin
              col <= 4'd0;
              row <= row + 1'b1;
              if (row == 3'd5) issue <= 1'b0;
            end else begin
              col <= col + 1'b1;
            end
          end
          // Accumulate the entry that arrived.
          if (vq) begin
            acc <= acc_next;
            if (col_q == 4'd8) begin
              case (row_q)
                3'd0: out_w0 <= w;
                3'd1: out_w1 <= w;
                3'd2: out_w2 <= w;
                3'd3: out_w3 <= w;
                3'd4: out_w4 <= w;
                default: out_w5 <= w;
              endcase
              if (row_q == 3'd5) begin
                state <= S_OUT;
                out_valid <= 1'b1;
                vq <= 1'b0;
              end
            end
          end
        end
        default: if (out_ready) begin  // S_OUT
          out_valid <= 1'b0;
          state <= S_IDLE;
        end
      endcase
    end
  end
endmodule
`default_nettype wire
