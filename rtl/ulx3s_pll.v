`default_nettype none
// ulx3s_pll: the ULX3S's 25 MHz oscillator through an ECP5 EHXPLLL to a
// board wrapper's core clock,
//   clk = 25 MHz x CLKFB_DIV / CLKI_DIV, VCO = clk x CLKOP_DIV,
// with the dividers prjtrellis' `ecppll` would give (host/fpga/board.cpp
// picks them); CLKOS_DIV > 0 adds a second clock from the same VCO,
//   clk_adc = VCO / CLKOS_DIV (rtl/dtmf_top.v's ADC_CLK_HZ),
// else clk_adc is clk. One module for every ULX3S wrapper (board_ulx3s,
// board_ulx3s_hall) so the PLL's limits are checked in one place: PFD >=
// 3.125 MHz (CLKI_DIV <= 8), VCO 400..800 MHz, dividers 1..128, a whole
// number of kHz; anything else stops elaboration.
module ulx3s_pll #(
    parameter integer CLKI_DIV = 5,
    parameter integer CLKFB_DIV = 6,
    parameter integer CLKOP_DIV = 20,
    parameter integer CLKOS_DIV = 0
) (
    input  wire clk_25mhz,
    output wire clk,
    output wire clk_adc,
    output wire locked
);
  localparam integer CLK_KHZ = 25_000 / CLKI_DIV * CLKFB_DIV;
  localparam integer VCO_MHZ = CLK_KHZ * CLKOP_DIV / 1000;
  generate
    if (CLKI_DIV < 1 || CLKI_DIV > 8 || CLKFB_DIV < 1 || CLKFB_DIV > 128 ||
        CLKOP_DIV < 1 || CLKOP_DIV > 128 || CLKOS_DIV < 0 || CLKOS_DIV > 128 ||
        25_000 % CLKI_DIV != 0 ||
        VCO_MHZ < 400 || VCO_MHZ > 800) begin : g_bad_pll
      $error("ulx3s_pll: CLKI_DIV %0d, CLKFB_DIV %0d, CLKOP_DIV %0d out of range (VCO %0d MHz)",
             CLKI_DIV, CLKFB_DIV, CLKOP_DIV, VCO_MHZ);
    end
  endgenerate

`ifdef VERILATOR
  // Lint and simulation only: Verilator has no ECP5 primitives, so the
  // oscillator stands in for the PLL output.
  assign clk = clk_25mhz;
  assign clk_adc = clk_25mhz;
  assign locked = 1'b1;
`else
  wire clk_os;
  assign clk_adc = CLKOS_DIV != 0 ? clk_os : clk;
  (* FREQUENCY_PIN_CLKI = "25" *)
  EHXPLLL #(
      .PLLRST_ENA("DISABLED"), .INTFB_WAKE("DISABLED"), .STDBY_ENABLE("DISABLED"),
      .DPHASE_SOURCE("DISABLED"), .OUTDIVIDER_MUXA("DIVA"), .OUTDIVIDER_MUXB("DIVB"),
      .OUTDIVIDER_MUXC("DIVC"), .OUTDIVIDER_MUXD("DIVD"), .CLKI_DIV(CLKI_DIV),
      .CLKOP_ENABLE("ENABLED"), .CLKOP_DIV(CLKOP_DIV), .CLKOP_CPHASE(CLKOP_DIV / 2 - 1),
      .CLKOP_FPHASE(0), .CLKOS_ENABLE(CLKOS_DIV != 0 ? "ENABLED" : "DISABLED"),
      .CLKOS_DIV(CLKOS_DIV != 0 ? CLKOS_DIV : 1), .CLKOS_CPHASE(CLKOS_DIV != 0 ? CLKOS_DIV / 2 - 1 : 0),
      .CLKOS_FPHASE(0), .FEEDBK_PATH("CLKOP"), .CLKFB_DIV(CLKFB_DIV)
  ) u_pll (
      .RST(1'b0), .STDBY(1'b0), .CLKI(clk_25mhz), .CLKOP(clk), .CLKOS(clk_os), .CLKFB(clk),
      .CLKINTFB(),
      .PHASESEL0(1'b0), .PHASESEL1(1'b0), .PHASEDIR(1'b1), .PHASESTEP(1'b1),
      .PHASELOADREG(1'b1), .PLLWAKESYNC(1'b0), .ENCLKOP(1'b0), .LOCK(locked));
`endif
endmodule
`default_nettype wire
