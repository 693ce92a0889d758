`default_nettype none
// board_ulx3s: the DTMF top on the ULX3S (ECP5 LFE5U-85F or -25F, CABGA381),
// pins in constraints/ulx3s.lpf.
//   25 MHz oscillator -> EHXPLLL -> the core's clock
//     CLK_HZ = 25 MHz * CLKFB_DIV / CLKI_DIV, VCO = CLK_HZ * CLKOP_DIV.
//     The default 30 MHz (6/5, VCO 600 MHz) is an exact multiple of the
//     3 Mbaud UART (10 clocks per bit) and keeps the AD7476A's SCLK at
//     15 MHz (<= 20 MHz). `eskin bitstream` picks other dividers for other
//     clocks (host/fpga/board.cpp) and passes them with the same CLK_HZ to
//     the core.
//   FIRE1 (active high) -> reset; the core is also held in reset until the
//     PLL locks.
//   Pmod AD1 on J1 gp[0..3] -> the core's ADC pins; FT231X -> the UART.
//   LEDs: 0 heartbeat, 1 TX activity, 2 RX activity, 3 ADC running,
//     4 PLL locked.
//
// The core: by default dtmf_top with its default parameters but CLK_HZ;
// `eskin bitstream` defines ESKIN_DTMF_CORE as the name of a wrapper module
// with a scene's dtmf_top parameters (hls/dtmf_top_config.h).
module board_ulx3s #(
    parameter integer CLKI_DIV = 5,
    parameter integer CLKFB_DIV = 6,
    parameter integer CLKOP_DIV = 20
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
  localparam integer CLK_KHZ = 25_000 / CLKI_DIV * CLKFB_DIV;
  localparam integer CLK_HZ = CLK_KHZ * 1000;
  localparam integer VCO_MHZ = CLK_KHZ * CLKOP_DIV / 1000;
  // EHXPLLL limits: PFD 3.125..400 MHz (CLKI_DIV <= 8 at 25 MHz), VCO
  // 400..800 MHz, dividers 1..128; and an exact CLK_HZ.
  generate
    if (CLKI_DIV < 1 || CLKI_DIV > 8 || CLKFB_DIV < 1 || CLKFB_DIV > 128 ||
        CLKOP_DIV < 1 || CLKOP_DIV > 128 || 25_000 % CLKI_DIV != 0 ||
        VCO_MHZ < 400 || VCO_MHZ > 800) begin : g_bad_pll
      $error("board_ulx3s: PLL CLKI_DIV %0d, CLKFB_DIV %0d, CLKOP_DIV %0d out of range (VCO %0d MHz)",
             CLKI_DIV, CLKFB_DIV, CLKOP_DIV, VCO_MHZ);
    end
  endgenerate

  wire clk, locked;
`ifdef VERILATOR
  // Lint and simulation only: Verilator has no ECP5 primitives, so the
  // oscillator stands in for the PLL output.
  assign clk = clk_25mhz;
  assign locked = 1'b1;
`else
  (* FREQUENCY_PIN_CLKI = "25" *)
  EHXPLLL #(
      .PLLRST_ENA("DISABLED"), .INTFB_WAKE("DISABLED"), .STDBY_ENABLE("DISABLED"),
      .DPHASE_SOURCE("DISABLED"), .OUTDIVIDER_MUXA("DIVA"), .OUTDIVIDER_MUXB("DIVB"),
      .OUTDIVIDER_MUXC("DIVC"), .OUTDIVIDER_MUXD("DIVD"), .CLKI_DIV(CLKI_DIV),
      .CLKOP_ENABLE("ENABLED"), .CLKOP_DIV(CLKOP_DIV), .CLKOP_CPHASE(CLKOP_DIV / 2 - 1),
      .CLKOP_FPHASE(0), .FEEDBK_PATH("CLKOP"), .CLKFB_DIV(CLKFB_DIV)
  ) u_pll (
      .RST(1'b0), .STDBY(1'b0), .CLKI(clk_25mhz), .CLKOP(clk), .CLKFB(clk), .CLKINTFB(),
      .PHASESEL0(1'b0), .PHASESEL1(1'b0), .PHASEDIR(1'b1), .PHASESTEP(1'b1),
      .PHASELOADREG(1'b1), .PLLWAKESYNC(1'b0), .ENCLKOP(1'b0), .LOCK(locked));
`endif

  wire rst_n = locked & ~btn_fire1;
  /* verilator lint_off PINCONNECTEMPTY */
`ifdef ESKIN_DTMF_CORE
  `ESKIN_DTMF_CORE u_core (
`else
  dtmf_top #(.CLK_HZ(CLK_HZ)) u_core (
`endif
      .clk(clk), .rst_n(rst_n), .adc_cs_n(adc_cs_n), .adc_sclk(adc_sclk),
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
