`default_nettype none
// Test wrapper: uart_rx (12 MHz, 3 Mbaud) feeding cmd_decoder, as on the
// board; DEPTH is the command FIFO size (the test builds 512 and 32);
// TYPE_* route command types as in rtl/mixed_top.v (defaults: every type).
module cmd_decoder_tb #(
    parameter integer DEPTH = 512,
    parameter [7:0] TYPE_LO = 8'h00,
    parameter [7:0] TYPE_HI = 8'hFF,
    parameter integer TYPE_IN = 1
) (
    input  wire        clk,
    input  wire        rst,
    input  wire        rx,
    output wire        avail,
    output wire [7:0]  head,
    input  wire        pop,
    input  wire        clear,
    output wire [15:0] crc_errors,
    output wire [15:0] frame_errors,
    output wire [15:0] overflows,
    output wire        rx_frame_err
);
  wire       b_valid, b_ready, overrun;
  wire [7:0] b_data;
  uart_rx #(.CLK_HZ(12_000_000), .BAUD(3_000_000)) u_rx (
      .clk(clk), .rst(rst), .rx(rx), .m_valid(b_valid), .m_ready(b_ready),
      .m_data(b_data), .frame_err(rx_frame_err), .overrun(overrun));
  cmd_decoder #(.DEPTH(DEPTH), .TYPE_LO(TYPE_LO), .TYPE_HI(TYPE_HI), .TYPE_IN(TYPE_IN)) u_dec (
      .clk(clk), .rst(rst), .s_valid(b_valid), .s_ready(b_ready), .s_data(b_data),
      .rx_error(rx_frame_err | overrun), .avail(avail), .head(head), .pop(pop),
      .clear(clear), .crc_errors(crc_errors), .frame_errors(frame_errors),
      .overflows(overflows));
endmodule
`default_nettype wire
