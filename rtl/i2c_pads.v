`default_nettype none
// i2c_pads: the open-drain pads of NB I2C buses at a board wrapper's pins.
// A line is driven low while its *_oe is set and released (high impedance)
// otherwise, so the bus's pull-up (external: the FPGA's weak pull-ups are far
// too weak for 400 kHz) makes the high level and every device can hold it
// low (wired AND, clock stretching). Yosys turns the 1'bz into a tristate
// buffer on the top-level inout (synth_ice40 / synth_ecp5: tribuf -logic),
// which nextpnr packs into the pin's SB_IO / TRELLIS_IO with its output
// enable; the pin's input path gives the line as the bus sees it (*_i).
module i2c_pads #(
    parameter integer NB = 1
) (
    inout  wire [NB-1:0] scl,
    inout  wire [NB-1:0] sda,
    input  wire [NB-1:0] scl_oe,
    input  wire [NB-1:0] sda_oe,
    output wire [NB-1:0] scl_i,
    output wire [NB-1:0] sda_i
);
  generate
    if (NB < 1) begin : g_bad
      i2c_pads_needs_at_least_one_bus bad ();
    end
    genvar b;
    for (b = 0; b < NB; b = b + 1) begin : g_bus
      assign scl[b] = scl_oe[b] ? 1'b0 : 1'bz;
      assign sda[b] = sda_oe[b] ? 1'b0 : 1'bz;
    end
  endgenerate
  assign scl_i = scl;
  assign sda_i = sda;
endmodule
`default_nettype wire
