`default_nettype none
// Bench top: one i2c_master driven by one mlx90393_sequencer; tstamp is a
// free-running clock counter so tests can assert exact cycles.
module mlx90393_sequencer_tb #(
    parameter integer NS = 3,
    parameter [NS*7-1:0] ADDR = {7'h0C, 7'h0D, 7'h0C},
    parameter [NS*7-1:0] MUX_ADDR = {7'h70, 7'h00, 7'h70},
    parameter [NS*3-1:0] MUX_CH = {3'd1, 3'd0, 3'd0},
    parameter integer BURST = 1,
    parameter integer CONV_CYC = 29_564,  // 2053 us * 12 MHz * 1.2
    parameter integer STALE_CYC = 36_954  // 1.5 x 2053 us
) (
    input  wire        clk,
    input  wire        rst,
    input  wire        scl_i,
    input  wire        sda_i,
    output wire        scl_oe,
    output wire        sda_oe,
    input  wire [NS-1:0] drdy,
    output wire        s_valid,
    input  wire        s_ready,
    output wire [7:0]  s_id,
    output wire [31:0] s_t,
    output wire [15:0] s_x,
    output wire [15:0] s_y,
    output wire [15:0] s_z,
    output wire [7:0]  s_flags,
    output wire [15:0] nacks,
    output wire [15:0] status_errors,
    output wire [15:0] reply_errors,
    output wire [15:0] recoveries,
    output wire [15:0] bus_errors,
    output reg  [31:0] cycle,
    output wire        owned  // the master holds the bus (START..STOP)
);
  always @(posedge clk) cycle <= rst ? 32'd0 : cycle + 32'd1;
  wire cmd_valid, cmd_ready, cmd_ack, rsp_valid, rsp_ready, rsp_nack;
  wire [2:0] cmd_op;
  wire [7:0] cmd_data, rsp_data;
  wire [1:0] rsp_err;
  i2c_master u_master (
      .clk(clk), .rst(rst), .cmd_valid(cmd_valid), .cmd_ready(cmd_ready), .cmd_op(cmd_op),
      .cmd_data(cmd_data), .cmd_ack(cmd_ack), .rsp_valid(rsp_valid), .rsp_ready(rsp_ready),
      .rsp_data(rsp_data), .rsp_nack(rsp_nack), .rsp_err(rsp_err), .scl_i(scl_i), .sda_i(sda_i),
      .scl_oe(scl_oe), .sda_oe(sda_oe), .owned(owned));
  mlx90393_sequencer #(
      .NS(NS), .ADDR(ADDR), .MUX_ADDR(MUX_ADDR), .MUX_CH(MUX_CH), .BURST(BURST),
      .CONV_CYC(CONV_CYC), .STALE_CYC(STALE_CYC)
  ) u_seq (
      .clk(clk), .rst(rst), .drdy(drdy), .tstamp(cycle), .m_cmd_valid(cmd_valid),
      .m_cmd_ready(cmd_ready), .m_cmd_op(cmd_op), .m_cmd_data(cmd_data), .m_cmd_ack(cmd_ack),
      .m_rsp_valid(rsp_valid), .m_rsp_ready(rsp_ready), .m_rsp_data(rsp_data),
      .m_rsp_nack(rsp_nack), .m_rsp_err(rsp_err), .s_valid(s_valid), .s_ready(s_ready),
      .s_id(s_id), .s_t(s_t), .s_x(s_x), .s_y(s_y), .s_z(s_z), .s_flags(s_flags),
      .nacks(nacks), .status_errors(status_errors), .reply_errors(reply_errors),
      .recoveries(recoveries), .bus_errors(bus_errors));
endmodule
`default_nettype wire
