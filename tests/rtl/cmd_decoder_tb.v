// Test wrapper: uart_rx (12 MHz, 3 Mbaud) feeding cmd_decoder with its
// default parameters (K 6, PHASE_W 32, NTHR 4, NNP 4), as on the board.
module cmd_decoder_tb (
    input  wire         clk,
    input  wire         rst,
    input  wire         rx,
    output wire [191:0] carrier_inc,
    output wire [63:0]  thresholds,
    output wire [127:0] neuron,
    output wire [3:0]   out_mask,
    output wire [47:0]  decim,
    output wire         cfg_changed,
    output wire         status_req,
    output wire [15:0]  crc_errors,
    output wire [15:0]  frame_errors,
    output wire [15:0]  accepted,
    output wire [15:0]  rejected,
    output wire [7:0]   last_reject_type,
    output wire [7:0]   last_reject_reason,
    output wire [7:0]   last_reject_seq,
    output wire         rx_frame_err
);
  wire       b_valid, b_ready, overrun;
  wire [7:0] b_data;
  uart_rx #(.CLK_HZ(12_000_000), .BAUD(3_000_000)) u_rx (
      .clk(clk), .rst(rst), .rx(rx), .m_valid(b_valid), .m_ready(b_ready),
      .m_data(b_data), .frame_err(rx_frame_err), .overrun(overrun));
  cmd_decoder u_dec (
      .clk(clk), .rst(rst), .s_valid(b_valid), .s_ready(b_ready), .s_data(b_data),
      .rx_error(rx_frame_err | overrun), .carrier_inc(carrier_inc),
      .thresholds(thresholds), .neuron(neuron), .out_mask(out_mask), .decim(decim),
      .cfg_changed(cfg_changed), .status_req(status_req), .crc_errors(crc_errors),
      .frame_errors(frame_errors), .accepted(accepted), .rejected(rejected),
      .last_reject_type(last_reject_type), .last_reject_reason(last_reject_reason),
      .last_reject_seq(last_reject_seq));
endmodule
