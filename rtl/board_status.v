`default_nettype none
// board_status: the status LEDs of a board wrapper (board_icebreaker,
// board_ulx3s), derived from the top's pins because dtmf_top has no status
// outputs. Time is cut into windows of ACT_MS ms; each activity output shows
// whether its signal was active during the previous window, so a 3 Mbaud
// burst or a 35 kSPS ADC is visible to the eye.
//   heartbeat: toggles every 10 windows (1 Hz blink at ACT_MS = 50).
//   tx_act / rx_act: the UART line was low (a start or 0 bit).
//   adc_act: ~CS was low (a conversion ran).
// All outputs active high (the wrappers invert them for active-low LEDs).
// Small on purpose (one window counter, a few flags): the UP5K is full.
// No reset input: the registers start from their initial values at
// configuration (iCE40 and ECP5 both load them), so the LEDs also work
// while the top is held in reset.
module board_status #(
    parameter integer CLK_HZ = 12_000_000,
    parameter integer ACT_MS = 50
) (
    input  wire clk,
    input  wire uart_tx,   // line to the host (idle high)
    input  wire uart_rx,   // line from the host (idle high, asynchronous)
    input  wire adc_cs_n,  // the ADC's chip select (low while converting)
    output wire heartbeat,
    output reg  tx_act = 1'b0,
    output reg  rx_act = 1'b0,
    output reg  adc_act = 1'b0
);
  localparam integer WIN = CLK_HZ / 1000 * ACT_MS;  // clocks per window
  localparam integer WW = $clog2(WIN);
  localparam [WW-1:0] WIN_LAST = WIN[WW-1:0] - 1'b1;
  generate
    if (CLK_HZ < 2000 || ACT_MS < 1 || ACT_MS > 1000) begin : g_bad_params
      $error("board_status: CLK_HZ (%0d) must be >= 2000 and ACT_MS (%0d) in 1..1000",
             CLK_HZ, ACT_MS);
    end
  endgenerate

  reg [WW-1:0] win_cnt = {WW{1'b0}};
  reg [3:0] beat = 4'd0;  // windows since the last heartbeat toggle
  reg hb = 1'b0;
  reg rx_s = 1'b1;        // one register: uart_rx is only displayed here
  reg tx_seen = 1'b0, rx_seen = 1'b0, cs_seen = 1'b0;
  wire win_end = win_cnt == WIN_LAST;
  always @(posedge clk) begin
    rx_s <= uart_rx;
    win_cnt <= win_end ? {WW{1'b0}} : win_cnt + 1'b1;
    if (win_end) begin
      beat <= (beat == 4'd9) ? 4'd0 : beat + 4'd1;
      if (beat == 4'd9) hb <= ~hb;
      tx_act <= tx_seen; rx_act <= rx_seen; adc_act <= cs_seen;
      tx_seen <= 1'b0; rx_seen <= 1'b0; cs_seen <= 1'b0;
    end else begin
      tx_seen <= tx_seen | ~uart_tx;
      rx_seen <= rx_seen | ~rx_s;
      cs_seen <= cs_seen | ~adc_cs_n;
    end
  end
  assign heartbeat = hb;
endmodule
`default_nettype wire
