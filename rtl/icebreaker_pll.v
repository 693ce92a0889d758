`default_nettype none
// icebreaker_pll: the iCEBreaker's 12 MHz oscillator through the UP5K's
// SB_PLL40_PAD (SIMPLE feedback) to a board wrapper's core clock,
//   clk = 12 MHz x (DIVF + 1) / (2^DIVQ x (DIVR + 1)),
// with the dividers `icepll` gives (host/fpga/board.cpp picks them). One
// module for every iCEBreaker wrapper (board_icebreaker, board_icebreaker_hall)
// so the PLL's limits are checked in one place: dividers outside the
// sysCLOCK PLL guide's ranges (PFD 10..133 MHz, VCO 533..1066 MHz, output
// >= 16 MHz) or a clock that is not a whole number of Hz stop elaboration.
module icebreaker_pll #(
    parameter integer DIVR = 0,
    parameter integer DIVF = 47,
    parameter integer DIVQ = 5,
    parameter integer FILTER_RANGE = 1
) (
    input  wire clk_12mhz,  // the oscillator's pad (pin 35)
    output wire clk,
    output wire locked
);
  localparam integer OSC_HZ = 12_000_000;
  localparam integer PFD_HZ = OSC_HZ / (DIVR + 1);
  localparam integer VCO_MHZ = PFD_HZ / 1000 * (DIVF + 1) / 1000;
  localparam integer CLK_HZ = PFD_HZ * (DIVF + 1) / (1 << DIVQ);
  generate
    if (DIVR < 0 || DIVR > 15 || DIVF < 0 || DIVF > 127 || DIVQ < 1 || DIVQ > 6 ||
        FILTER_RANGE < 0 || FILTER_RANGE > 7 || OSC_HZ % (DIVR + 1) != 0 ||
        PFD_HZ < 10_000_000 || PFD_HZ > 133_000_000 || VCO_MHZ < 533 || VCO_MHZ > 1066 ||
        CLK_HZ < 16_000_000 || (PFD_HZ * (DIVF + 1)) % (1 << DIVQ) != 0) begin : g_bad_pll
      $error("icebreaker_pll: DIVR %0d, DIVF %0d, DIVQ %0d out of range (PFD %0d Hz, VCO %0d MHz)",
             DIVR, DIVF, DIVQ, PFD_HZ, VCO_MHZ);
    end
  endgenerate

`ifdef VERILATOR
  // Lint and simulation only: Verilator has no iCE40 primitives, so the
  // oscillator stands in for the PLL output.
  assign clk = clk_12mhz;
  assign locked = 1'b1;
`else
  SB_PLL40_PAD #(
      .FEEDBACK_PATH("SIMPLE"), .DIVR(DIVR[3:0]), .DIVF(DIVF[6:0]), .DIVQ(DIVQ[2:0]),
      .FILTER_RANGE(FILTER_RANGE[2:0])
  ) u_pll (
      .PACKAGEPIN(clk_12mhz), .PLLOUTCORE(), .PLLOUTGLOBAL(clk), .EXTFEEDBACK(1'b0),
      .DYNAMICDELAY(8'd0), .LOCK(locked), .BYPASS(1'b0), .RESETB(1'b1),
      .LATCHINPUTVALUE(1'b0), .SDI(1'b0), .SDO(), .SCLK(1'b0));
`endif
endmodule
`default_nettype wire
