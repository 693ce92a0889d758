`default_nettype none
// board_icebreaker: the DTMF top on the iCEBreaker (iCE40 UP5K SG48), pins
// in constraints/icebreaker.pcf.
//   12 MHz oscillator -> SB_PLL40_PAD -> the core's clock
//     CLK_HZ = 12 MHz x (PLL_DIVF + 1) / (2^PLL_DIVQ x (PLL_DIVR + 1)).
//     The default 18 MHz (DIVR 0, DIVF 47, DIVQ 5: VCO 576 MHz, as
//     `icepll -i 12 -o 18` gives) is the fastest PLL clock below the top's
//     Fmax (about 20 MHz) that is a multiple of the 3 Mbaud UART (6 clocks
//     per bit); common/eskin/dtmf_top_plan.h's kDtmfTopClkHz. `eskin bitstream`
//     picks other dividers for other clocks (host/fpga/board.cpp) and
//     passes the same clock to the core as its CLK_HZ.
//   BTN_N -> the core's rst_n, which is also held low until the PLL locks
//     (the core adds its power-on reset).
//   Pmod AD1 on PMOD1A -> the core's ADC pins; FTDI channel B -> the UART.
//   LEDs (active low): green = heartbeat, red = UART activity either way.
//
// The core: by default dtmf_top with its default parameters but CLK_HZ
// (no microcode: for lint only). `eskin bitstream` builds a scene's core:
// it writes a wrapper module with the scene's dtmf_top parameters and
// microcode files (ucode/dtmf_ucode.h) and defines ESKIN_DTMF_CORE as its
// name.
module board_icebreaker #(
    parameter integer PLL_DIVR = 0,
    parameter integer PLL_DIVF = 47,
    parameter integer PLL_DIVQ = 5,
    parameter integer PLL_FILTER_RANGE = 1
) (
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
  // The core's clock; icebreaker_pll stops elaboration on illegal dividers.
  localparam integer CLK_HZ = 12_000_000 / (PLL_DIVR + 1) * (PLL_DIVF + 1) / (1 << PLL_DIVQ);
  wire clk, locked;
  icebreaker_pll #(
      .DIVR(PLL_DIVR), .DIVF(PLL_DIVF), .DIVQ(PLL_DIVQ), .FILTER_RANGE(PLL_FILTER_RANGE)
  ) u_pll (.clk_12mhz(clk_12mhz), .clk(clk), .locked(locked));

  wire rst_n = btn_n & locked;
  /* verilator lint_off PINCONNECTEMPTY */
`ifdef ESKIN_DTMF_CORE
  `ESKIN_DTMF_CORE u_core (
`else
  dtmf_top #(.CLK_HZ(CLK_HZ)) u_core (
`endif
      .clk(clk), .adc_clk(clk), .rst_n(rst_n), .adc_cs_n(adc_cs_n), .adc_sclk(adc_sclk),
      .adc_sdata(adc_sdata), .uart_txd(uart_tx), .uart_rxd(uart_rx),
      .pkt_valid(), .pkt_ready(1'b0), .pkt_data());  // own link: no packet stream out
  /* verilator lint_on PINCONNECTEMPTY */

  wire heartbeat, tx_act, rx_act, adc_act;
  board_status #(.CLK_HZ(CLK_HZ)) u_status (
      .clk(clk), .uart_tx(uart_tx), .uart_rx(uart_rx), .adc_cs_n(adc_cs_n),
      .heartbeat(heartbeat), .tx_act(tx_act), .rx_act(rx_act), .adc_act(adc_act));
  assign ledg_n = ~heartbeat;
  assign ledr_n = ~(tx_act | rx_act);
  wire unused = adc_act;
endmodule
`default_nettype wire
