`default_nettype none
// board_icebreaker_hall: a scene with Hall sensors on the iCEBreaker (iCE40
// UP5K SG48): hall_top alone, or, with ESKIN_MIXED defined, mixed_top
// (dtmf_top and hall_top on one host link, docs/fpga.md).
//   Clock: PLL = 0 runs the core on the 12 MHz oscillator itself (hall_top's
//     clock: 1 us time base, I2C timing and 3 Mbaud all exact,
//     docs/hall_fpga.md "Clock"); PLL = 1 makes CLK_HZ with icebreaker_pll's
//     dividers (a mixed build runs at the DTMF top's clock, 18 MHz by
//     default; host/fpga/board.cpp picks them).
//   I2C: bus b on i2c_scl[b] / i2c_sda[b], open drain (i2c_pads); DRDY of
//     sensor s = b * NSB + k on drdy[s]. Those pins go on PMOD1B and PMOD2
//     in the order host/fpga/hall_pins.cpp gives; `eskin bitstream` writes
//     them with constraints/icebreaker.pcf's into OUT/board_icebreaker_hall.pcf.
//   ESKIN_MIXED: the Pmod AD1 on PMOD1A as in board_icebreaker.
//   BTN_N -> reset, also held until the PLL locks (power_on_reset makes
//     hall_top's synchronous rst; mixed_top has its own).
//   LEDs (active low): green = heartbeat, red = UART activity either way.
// The core: ESKIN_HALL_CORE names a generated module with hall_top's ports
// (without the packet port) or, with ESKIN_MIXED, mixed_top's, carrying the
// scene's parameters (host/fpga/core_wrapper.h); without it, hall_top /
// mixed_top with their defaults but CLK_HZ, NB and NSB (for lint).
module board_icebreaker_hall #(
    parameter integer NB = 2,
    parameter integer NSB = 2,
    parameter integer PLL = 0,
    parameter integer PLL_DIVR = 0,
    parameter integer PLL_DIVF = 47,
    parameter integer PLL_DIVQ = 5,
    parameter integer PLL_FILTER_RANGE = 1
) (
    input  wire              clk_12mhz,
    input  wire              btn_n,
    input  wire              uart_rx,   // from the host (FTDI)
    output wire              uart_tx,   // to the host
`ifdef ESKIN_MIXED
    output wire              adc_cs_n,
    output wire              adc_sclk,
    input  wire              adc_sdata,
`endif
    inout  wire [NB-1:0]     i2c_scl,
    inout  wire [NB-1:0]     i2c_sda,
    input  wire [NB*NSB-1:0] drdy,
    output wire              ledr_n,
    output wire              ledg_n
);
  localparam integer CLK_HZ =
      PLL != 0 ? 12_000_000 / (PLL_DIVR + 1) * (PLL_DIVF + 1) / (1 << PLL_DIVQ) : 12_000_000;
  generate
    if (PLL != 0 && PLL != 1) begin : g_bad
      board_icebreaker_hall_PLL_must_be_0_or_1 bad ();
    end
  endgenerate

  wire clk, locked;
  generate
    if (PLL != 0) begin : g_pll
      icebreaker_pll #(
          .DIVR(PLL_DIVR), .DIVF(PLL_DIVF), .DIVQ(PLL_DIVQ), .FILTER_RANGE(PLL_FILTER_RANGE)
      ) u_pll (.clk_12mhz(clk_12mhz), .clk(clk), .locked(locked));
    end else begin : g_osc
      assign clk = clk_12mhz;
      assign locked = 1'b1;
    end
  endgenerate

  wire [NB-1:0] scl_i, sda_i, scl_oe, sda_oe;
  i2c_pads #(.NB(NB)) u_pads (
      .scl(i2c_scl), .sda(i2c_sda), .scl_oe(scl_oe), .sda_oe(sda_oe), .scl_i(scl_i),
      .sda_i(sda_i));

  wire rst_n = btn_n & locked;
`ifdef ESKIN_MIXED
  `ifdef ESKIN_HALL_CORE
  `ESKIN_HALL_CORE u_core (
  `else
  mixed_top #(.CLK_HZ(CLK_HZ), .NB(NB), .NSB(NSB)) u_core (
  `endif
      .clk(clk), .rst_n(rst_n), .adc_cs_n(adc_cs_n), .adc_sclk(adc_sclk),
      .adc_sdata(adc_sdata), .scl_i(scl_i), .sda_i(sda_i), .scl_oe(scl_oe), .sda_oe(sda_oe),
      .drdy(drdy), .uart_txd(uart_tx), .uart_rxd(uart_rx));
`else
  wire rst;
  power_on_reset u_por (.clk(clk), .rst_n(rst_n), .rst(rst));
  `ifdef ESKIN_HALL_CORE
  `ESKIN_HALL_CORE u_core (
      .clk(clk), .rst(rst), .scl_i(scl_i), .sda_i(sda_i), .scl_oe(scl_oe), .sda_oe(sda_oe),
      .drdy(drdy), .uart_txd(uart_tx), .uart_rxd(uart_rx));
  `else
  /* verilator lint_off PINCONNECTEMPTY */
  hall_top #(.CLK_HZ(CLK_HZ), .NB(NB), .NSB(NSB)) u_core (
      .clk(clk), .rst(rst), .scl_i(scl_i), .sda_i(sda_i), .scl_oe(scl_oe), .sda_oe(sda_oe),
      .drdy(drdy), .uart_txd(uart_tx), .uart_rxd(uart_rx), .pkt_valid(), .pkt_ready(1'b0),
      .pkt_data());
  /* verilator lint_on PINCONNECTEMPTY */
  `endif
`endif

  // The iCEBreaker has two LEDs: no ADC or I2C activity shown (adc_cs_n idle).
  wire heartbeat, tx_act, rx_act, adc_act;
  board_status #(.CLK_HZ(CLK_HZ)) u_status (
      .clk(clk), .uart_tx(uart_tx), .uart_rx(uart_rx), .adc_cs_n(1'b1),
      .heartbeat(heartbeat), .tx_act(tx_act), .rx_act(rx_act), .adc_act(adc_act));
  assign ledg_n = ~heartbeat;
  assign ledr_n = ~(tx_act | rx_act);
  wire unused = adc_act;
endmodule
`default_nettype wire
