`default_nettype none
// Test wrapper: link_framer feeding uart_tx (12 MHz, 3 Mbaud by default),
// as on the board; the testbench decodes the serial line.
module link_framer_uart_tb #(
    parameter integer CLK_HZ = 12_000_000,
    parameter integer BAUD   = 3_000_000
) (
    input  wire        clk,
    input  wire        rst,
    input  wire        s_valid,
    output wire        s_ready,
    input  wire [7:0]  s_data,
    output wire        tx
);
  wire       f_valid, f_ready;
  wire [7:0] f_data, seq;
  link_framer u_framer (
      .clk(clk), .rst(rst), .s_valid(s_valid),
      .s_ready(s_ready), .s_data(s_data), .m_valid(f_valid), .m_ready(f_ready),
      .m_data(f_data), .seq(seq));
  uart_tx #(.CLK_HZ(CLK_HZ), .BAUD(BAUD)) u_tx (
      .clk(clk), .rst(rst), .s_valid(f_valid), .s_ready(f_ready), .s_data(f_data), .tx(tx));
  /* verilator lint_off UNUSEDSIGNAL */
  wire [7:0] seq_unused = seq;
  /* verilator lint_on UNUSEDSIGNAL */
endmodule
`default_nettype wire
