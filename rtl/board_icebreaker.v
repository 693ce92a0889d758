`default_nettype none
// board_icebreaker: the DTMF top on the iCEBreaker (iCE40 UP5K SG48), pins
// in constraints/icebreaker.pcf.
//   12 MHz oscillator -> SB_PLL40_PAD -> the core's clock
//     CLK_HZ = 12 MHz x (PLL_DIVF + 1) / (2^PLL_DIVQ x (PLL_DIVR + 1)).
//     The default 18 MHz (DIVR 0, DIVF 47, DIVQ 5: VCO 576 MHz, as
//     `icepll -i 12 -o 18` gives) is the fastest PLL clock below the top's
//     Fmax (about 20 MHz) that is a multiple of the 3 Mbaud UART (6 clocks
//     per bit); hls/dtmf_top_config.h's kDtmfTopClkHz. `eskin bitstream`
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
// microcode files (hls/dtmf_ucode.h) and defines ESKIN_DTMF_CORE as its
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
  localparam integer OSC_HZ = 12_000_000;
  localparam integer PFD_HZ = OSC_HZ / (PLL_DIVR + 1);
  localparam integer VCO_MHZ = PFD_HZ / 1000 * (PLL_DIVF + 1) / 1000;
  localparam integer CLK_HZ = PFD_HZ * (PLL_DIVF + 1) / (1 << PLL_DIVQ);
  // SB_PLL40 limits (iCE40 sysCLOCK PLL guide): PFD 10..133 MHz, VCO
  // 533..1066 MHz, output 16..275 MHz; and an exact CLK_HZ.
  generate
    if (PLL_DIVR < 0 || PLL_DIVR > 15 || PLL_DIVF < 0 || PLL_DIVF > 127 || PLL_DIVQ < 1 ||
        PLL_DIVQ > 6 || PLL_FILTER_RANGE < 0 || PLL_FILTER_RANGE > 7 ||
        OSC_HZ % (PLL_DIVR + 1) != 0 || PFD_HZ < 10_000_000 || PFD_HZ > 133_000_000 ||
        VCO_MHZ < 533 || VCO_MHZ > 1066 || CLK_HZ < 16_000_000 ||
        (PFD_HZ * (PLL_DIVF + 1)) % (1 << PLL_DIVQ) != 0) begin : g_bad_pll
      $error("board_icebreaker: PLL DIVR %0d, DIVF %0d, DIVQ %0d out of range (PFD %0d Hz, VCO %0d MHz)",
             PLL_DIVR, PLL_DIVF, PLL_DIVQ, PFD_HZ, VCO_MHZ);
    end
  endgenerate

  wire clk, locked;
`ifdef VERILATOR
  // Lint and simulation only: Verilator has no iCE40 primitives, so the
  // oscillator stands in for the PLL output.
  assign clk = clk_12mhz;
  assign locked = 1'b1;
`else
  SB_PLL40_PAD #(
      .FEEDBACK_PATH("SIMPLE"), .DIVR(PLL_DIVR[3:0]), .DIVF(PLL_DIVF[6:0]),
      .DIVQ(PLL_DIVQ[2:0]), .FILTER_RANGE(PLL_FILTER_RANGE[2:0])
  ) u_pll (
      .PACKAGEPIN(clk_12mhz), .PLLOUTCORE(), .PLLOUTGLOBAL(clk), .EXTFEEDBACK(1'b0),
      .DYNAMICDELAY(8'd0), .LOCK(locked), .BYPASS(1'b0), .RESETB(1'b1),
      .LATCHINPUTVALUE(1'b0), .SDI(1'b0), .SDO(), .SCLK(1'b0));
`endif

  wire rst_n = btn_n & locked;
  /* verilator lint_off PINCONNECTEMPTY */
`ifdef ESKIN_DTMF_CORE
  `ESKIN_DTMF_CORE u_core (
`else
  dtmf_top #(.CLK_HZ(CLK_HZ)) u_core (
`endif
      .clk(clk), .rst_n(rst_n), .adc_cs_n(adc_cs_n), .adc_sclk(adc_sclk),
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
