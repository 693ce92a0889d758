`default_nettype none
// Test wrapper: uart_rx (12 MHz, 3 Mbaud) -> cmd_decoder -> hall_cmd, as in
// rtl/hall_top.v; NS and HAS_FT are hall_cmd's (the test builds 16 sensors
// without F/T and 3 sensors with it).
module hall_cmd_tb #(
    parameter integer NS = 16,
    parameter integer HAS_FT = 0,
    parameter integer SW = (NS > 1) ? $clog2(NS) : 1
) (
    input  wire          clk,
    input  wire          rst,
    input  wire          rx,
    output wire          c_valid,
    output wire [2:0]    c_row,
    output wire [3:0]    c_col,
    output wire [31:0]   c_value,
    output wire          set_valid,
    output wire [SW-1:0] set_sensor,
    output wire [1:0]    set_axis,
    output wire [15:0]   set_value,
    output wire          recapture,
    output wire [15:0]   accepted,
    output wire [15:0]   rejected,
    output wire [7:0]    last_type,
    output wire [7:0]    last_reason,
    output wire [7:0]    last_seq,
    output wire          reject,
    output wire [15:0]   crc_errors
);
  wire       r_valid, r_ready, r_ferr, r_ovr, q_avail, q_pop;
  wire [7:0] r_data, q_head;
  wire [15:0] frame_errors, overflows;
  uart_rx #(.CLK_HZ(12_000_000), .BAUD(3_000_000)) u_rx (
      .clk(clk), .rst(rst), .rx(rx), .m_valid(r_valid), .m_ready(r_ready),
      .m_data(r_data), .frame_err(r_ferr), .overrun(r_ovr));
  cmd_decoder #(.DEPTH(64)) u_dec (
      .clk(clk), .rst(rst), .s_valid(r_valid), .s_ready(r_ready), .s_data(r_data),
      .rx_error(r_ferr | r_ovr), .avail(q_avail), .head(q_head), .pop(q_pop),
      .clear(1'b0), .crc_errors(crc_errors), .frame_errors(frame_errors),
      .overflows(overflows));
  hall_cmd #(.NS(NS), .HAS_BASELINE(1), .HAS_FT(HAS_FT), .SW(SW)) u_cmd (
      .clk(clk), .rst(rst), .avail(q_avail), .head(q_head), .pop(q_pop),
      .c_valid(c_valid), .c_row(c_row), .c_col(c_col), .c_value(c_value),
      .set_valid(set_valid), .set_sensor(set_sensor), .set_axis(set_axis),
      .set_value(set_value), .recapture(recapture), .accepted(accepted),
      .rejected(rejected), .last_type(last_type), .last_reason(last_reason),
      .last_seq(last_seq), .reject(reject), .t_valid(t_v), .t_cell(t_c), .t_index(t_i),
      .t_which(t_w), .t_value(t_d), .dc_k1(k1), .dc_c1(c1), .dc_k2(k2), .dc_c2(c2));
  // The curve and decoupling ports (not in this build: HAS_CURVE, HAS_DECOUPLE 0).
  wire t_v;
  wire [0:0] t_c;
  wire [4:0] t_i;
  wire [1:0] t_w;
  wire [31:0] t_d, c1, c2;
  wire [15:0] k1, k2;
  wire unused = &{1'b0, frame_errors, overflows, t_v, t_c, t_i, t_w, t_d, c1, c2, k1, k2};
endmodule
`default_nettype wire
