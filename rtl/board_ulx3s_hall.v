`default_nettype none
// board_ulx3s_hall: a scene with Hall sensors on the ULX3S (ECP5 LFE5U-85F
// or -25F, CABGA381): hall_top alone, or, with ESKIN_MIXED defined,
// mixed_top (dtmf_top and hall_top on one host link, docs/fpga.md).
//   Clock: the 25 MHz oscillator through ulx3s_pll (CLK_HZ = 25 MHz x
//     CLKFB_DIV / CLKI_DIV; default 30 MHz, 10 clocks per bit at 3 Mbaud).
//     hall_top needs a whole number of MHz; 25 MHz itself would leave the
//     UART at 1 Mbaud (host/fpga/board.cpp picks the clock).
//   I2C: bus b on i2c_scl[b] / i2c_sda[b], open drain (i2c_pads); DRDY of
//     sensor s = b * NSB + k on drdy[s]. Those pins go on the GPIO headers
//     J1 and J2 in the order host/fpga/hall_pins.cpp gives; `eskin
//     bitstream` writes them with constraints/ulx3s.lpf's into
//     OUT/board_ulx3s_hall.lpf.
//   ESKIN_MIXED: the Pmod AD1 on J1 gp[0..3] as in board_ulx3s.
//   FIRE1 (active high) -> reset, also held until the PLL locks
//     (power_on_reset makes hall_top's synchronous rst; mixed_top has its own).
//   LEDs: 0 heartbeat, 1 TX activity, 2 RX activity, 3 sensor activity (an
//     I2C line pulled low by the FPGA, or an ADC conversion), 4 PLL locked.
// The core: ESKIN_HALL_CORE names a generated module with hall_top's ports
// (without the packet port) or, with ESKIN_MIXED, mixed_top's, carrying the
// scene's parameters (host/fpga/core_wrapper.h); without it, hall_top /
// mixed_top with their defaults but CLK_HZ, NB and NSB (for lint).
module board_ulx3s_hall #(
    parameter integer NB = 2,
    parameter integer NSB = 2,
    parameter integer CLKI_DIV = 5,
    parameter integer CLKFB_DIV = 6,
    parameter integer CLKOP_DIV = 20
) (
    input  wire              clk_25mhz,
    input  wire              btn_fire1,
    input  wire              ftdi_txd,  // from the host (FT231X TXD)
    output wire              ftdi_rxd,  // to the host (FT231X RXD)
`ifdef ESKIN_MIXED
    output wire              adc_cs_n,
    output wire              adc_sclk,
    input  wire              adc_sdata,
`endif
    inout  wire [NB-1:0]     i2c_scl,
    inout  wire [NB-1:0]     i2c_sda,
    input  wire [NB*NSB-1:0] drdy,
    output wire [7:0]        led
);
  // The core's clock; ulx3s_pll stops elaboration on illegal dividers.
  localparam integer CLK_HZ = 25_000 / CLKI_DIV * CLKFB_DIV * 1000;
  wire clk, locked;
  /* verilator lint_off PINCONNECTEMPTY */
  ulx3s_pll #(.CLKI_DIV(CLKI_DIV), .CLKFB_DIV(CLKFB_DIV), .CLKOP_DIV(CLKOP_DIV)) u_pll (
      .clk_25mhz(clk_25mhz), .clk(clk), .clk_adc(), .locked(locked));  // one clock: no CLKOS
  /* verilator lint_on PINCONNECTEMPTY */

  wire [NB-1:0] scl_i, sda_i, scl_oe, sda_oe;
  i2c_pads #(.NB(NB)) u_pads (
      .scl(i2c_scl), .sda(i2c_sda), .scl_oe(scl_oe), .sda_oe(sda_oe), .scl_i(scl_i),
      .sda_i(sda_i));

  wire rst_n = locked & ~btn_fire1;
`ifdef ESKIN_MIXED
  `ifdef ESKIN_HALL_CORE
  `ESKIN_HALL_CORE u_core (
  `else
  mixed_top #(.CLK_HZ(CLK_HZ), .NB(NB), .NSB(NSB)) u_core (
  `endif
      .clk(clk), .rst_n(rst_n), .adc_cs_n(adc_cs_n), .adc_sclk(adc_sclk),
      .adc_sdata(adc_sdata), .scl_i(scl_i), .sda_i(sda_i), .scl_oe(scl_oe), .sda_oe(sda_oe),
      .drdy(drdy), .uart_txd(ftdi_rxd), .uart_rxd(ftdi_txd));
  // board_status watches one active-low line for "sensor activity".
  wire sensing_n = adc_cs_n & ~|{scl_oe, sda_oe};
`else
  wire rst;
  power_on_reset u_por (.clk(clk), .rst_n(rst_n), .rst(rst));
  `ifdef ESKIN_HALL_CORE
  `ESKIN_HALL_CORE u_core (
      .clk(clk), .rst(rst), .scl_i(scl_i), .sda_i(sda_i), .scl_oe(scl_oe), .sda_oe(sda_oe),
      .drdy(drdy), .uart_txd(ftdi_rxd), .uart_rxd(ftdi_txd));
  `else
  /* verilator lint_off PINCONNECTEMPTY */
  hall_top #(.CLK_HZ(CLK_HZ), .NB(NB), .NSB(NSB)) u_core (
      .clk(clk), .rst(rst), .scl_i(scl_i), .sda_i(sda_i), .scl_oe(scl_oe), .sda_oe(sda_oe),
      .drdy(drdy), .uart_txd(ftdi_rxd), .uart_rxd(ftdi_txd), .pkt_valid(), .pkt_ready(1'b0),
      .pkt_data());
  /* verilator lint_on PINCONNECTEMPTY */
  `endif
  wire sensing_n = ~|{scl_oe, sda_oe};
`endif

  wire heartbeat, tx_act, rx_act, sense_act;
  board_status #(.CLK_HZ(CLK_HZ)) u_status (
      .clk(clk), .uart_tx(ftdi_rxd), .uart_rx(ftdi_txd), .adc_cs_n(sensing_n),
      .heartbeat(heartbeat), .tx_act(tx_act), .rx_act(rx_act), .adc_act(sense_act));
  assign led = {3'b000, locked, sense_act, rx_act, tx_act, heartbeat};
endmodule
`default_nettype wire
