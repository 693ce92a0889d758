`default_nettype none
// board_icebreaker: the DTMF top on the iCEBreaker (iCE40 UP5K SG48), pins
// in constraints/icebreaker.pcf.
//   12 MHz oscillator -> the core's clock (the core is built for 12 MHz;
//     a core that wants a faster clock has its PLL inside).
//   BTN_N -> the core's rst_n (the core adds its power-on reset).
//   Pmod AD1 on PMOD1A -> the core's ADC pins; FTDI channel B -> the UART.
//   LEDs (active low): green = heartbeat, red = UART activity either way.
//
// The core: by default dtmf_top with its default parameters (the default
// scene). `eskin bitstream` builds a scene's core instead: it writes a
// wrapper module with the scene's dtmf_top parameters
// (hls/dtmf_top_config.h) and defines ESKIN_DTMF_CORE as its name.
module board_icebreaker (
    input  wire clk_12mhz,
    input  wire btn_n,
    input  wire uart_rx,     // from the host (FTDI)
    output wire uart_tx,     // to the host
    output wire adc_cs_n,
    output wire adc_sclk,
    input  wire adc_sdata,
    output wire ledr_n,
    output wire ledg_n
);
  localparam integer CLK_HZ = 12_000_000;
  wire clk = clk_12mhz;

`ifdef ESKIN_DTMF_CORE
  `ESKIN_DTMF_CORE u_core (
`else
  dtmf_top #(.CLK_HZ(CLK_HZ)) u_core (
`endif
      .clk(clk), .rst_n(btn_n), .adc_cs_n(adc_cs_n), .adc_sclk(adc_sclk),
      .adc_sdata(adc_sdata), .uart_txd(uart_tx), .uart_rxd(uart_rx));

  wire heartbeat, tx_act, rx_act, adc_act;
  board_status #(.CLK_HZ(CLK_HZ)) u_status (
      .clk(clk), .uart_tx(uart_tx), .uart_rx(uart_rx), .adc_cs_n(adc_cs_n),
      .heartbeat(heartbeat), .tx_act(tx_act), .rx_act(rx_act), .adc_act(adc_act));
  assign ledg_n = ~heartbeat;
  assign ledr_n = ~(tx_act | rx_act);
  wire unused = adc_act;
endmodule
`default_nettype wire
