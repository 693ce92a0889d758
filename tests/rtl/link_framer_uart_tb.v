// Test wrapper: link_framer feeding uart_tx (12 MHz, 3 Mbaud by default),
// as on the board; the testbench decodes the serial line.
module link_framer_uart_tb #(
    parameter integer CLK_HZ = 12_000_000,
    parameter integer BAUD   = 3_000_000
) (
    input  wire        clk,
    input  wire        rst,
    input  wire        hdr_valid,
    output wire        hdr_ready,
    input  wire [7:0]  hdr_type,
    input  wire [31:0] hdr_t,
    input  wire [15:0] hdr_len,
    input  wire        s_valid,
    output wire        s_ready,
    input  wire [7:0]  s_data,
    output wire        tx
);
  wire       f_valid, f_ready;
  wire [7:0] f_data, seq;
  link_framer u_framer (
      .clk(clk), .rst(rst), .hdr_valid(hdr_valid), .hdr_ready(hdr_ready),
      .hdr_type(hdr_type), .hdr_t(hdr_t), .hdr_len(hdr_len), .s_valid(s_valid),
      .s_ready(s_ready), .s_data(s_data), .m_valid(f_valid), .m_ready(f_ready),
      .m_data(f_data), .seq(seq));
  uart_tx #(.CLK_HZ(CLK_HZ), .BAUD(BAUD)) u_tx (
      .clk(clk), .rst(rst), .s_valid(f_valid), .s_ready(f_ready), .s_data(f_data), .tx(tx));
  wire unused = ^seq;
endmodule
