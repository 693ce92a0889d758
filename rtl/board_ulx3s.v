`default_nettype none
// board_ulx3s: the DTMF top on the ULX3S (ECP5 LFE5U-85F or -25F, CABGA381),
// pins in constraints/ulx3s.lpf.
//   25 MHz oscillator -> EHXPLLL -> the core's clock
//     CLK_HZ = 25 MHz * CLKFB_DIV / CLKI_DIV, VCO = CLK_HZ * CLKOP_DIV.
//     The default 30 MHz (6/5, VCO 600 MHz) is an exact multiple of the
//     3 Mbaud UART (10 clocks per bit) and keeps the AD7476A's SCLK at
//     15 MHz (<= 20 MHz). `eskin bitstream` picks other dividers for other
//     clocks (host/fpga/board.cpp) and passes them with the same CLK_HZ to
//     the core; with CLKOS_DIV > 0 the ADC gets its own clock from the same
//     VCO, VCO / CLKOS_DIV (the core's ADC_CLK_HZ: 40 MHz for 1 MS/s while
//     the core runs faster).
//   FIRE1 (active high) -> reset; the core is also held in reset until the
//     PLL locks.
//   Pmod AD1 on J1 gp[0..3] -> the core's ADC pins; FT231X -> the UART.
//   LEDs: 0 heartbeat, 1 TX activity, 2 RX activity, 3 ADC running,
//     4 PLL locked.
//
// The core: by default dtmf_top with its default parameters but CLK_HZ;
// `eskin bitstream` defines ESKIN_DTMF_CORE as the name of a wrapper module
// with a scene's dtmf_top parameters (common/eskin/dtmf_top_plan.h).
module board_ulx3s #(
    parameter integer CLKI_DIV = 5,
    parameter integer CLKFB_DIV = 6,
    parameter integer CLKOP_DIV = 20,
    parameter integer CLKOS_DIV = 0
) (
    input  wire clk_25mhz,
    input  wire btn_fire1,
    input  wire ftdi_txd,    // from the host (FT231X TXD)
    output wire ftdi_rxd,    // to the host (FT231X RXD)
    output wire adc_cs_n,
    output wire adc_sclk,
    input  wire adc_sdata,
    output wire [7:0] led
);
  // The core's clock; ulx3s_pll stops elaboration on illegal dividers.
  localparam integer CLK_HZ = 25_000 / CLKI_DIV * CLKFB_DIV * 1000;
  wire clk, adc_clk, locked;
  ulx3s_pll #(.CLKI_DIV(CLKI_DIV), .CLKFB_DIV(CLKFB_DIV), .CLKOP_DIV(CLKOP_DIV),
              .CLKOS_DIV(CLKOS_DIV)) u_pll (
      .clk_25mhz(clk_25mhz), .clk(clk), .clk_adc(adc_clk), .locked(locked));

  wire rst_n = locked & ~btn_fire1;
  /* verilator lint_off PINCONNECTEMPTY */
`ifdef ESKIN_DTMF_CORE
  `ESKIN_DTMF_CORE u_core (
`else
  dtmf_top #(.CLK_HZ(CLK_HZ)) u_core (
`endif
      .clk(clk), .adc_clk(adc_clk), .rst_n(rst_n), .adc_cs_n(adc_cs_n), .adc_sclk(adc_sclk),
      .adc_sdata(adc_sdata), .uart_txd(ftdi_rxd), .uart_rxd(ftdi_txd),
      .pkt_valid(), .pkt_ready(1'b0), .pkt_data());  // own link: no packet stream out
  /* verilator lint_on PINCONNECTEMPTY */

  wire heartbeat, tx_act, rx_act, adc_act;
  board_status #(.CLK_HZ(CLK_HZ)) u_status (
      .clk(clk), .uart_tx(ftdi_rxd), .uart_rx(ftdi_txd), .adc_cs_n(adc_cs_n),
      .heartbeat(heartbeat), .tx_act(tx_act), .rx_act(rx_act), .adc_act(adc_act));
  assign led = {3'b000, locked, adc_act, rx_act, tx_act, heartbeat};
endmodule
`default_nettype wire
