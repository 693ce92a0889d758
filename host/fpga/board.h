// The boards `eskin bitstream` builds for: which FPGA, which tools, which
// wrappers (rtl/board_*.v: the DTMF top's, and the one for scenes with Hall
// sensors) and pins (constraints/; the Hall sensors' in hall_pins.h), and
// how the board makes the core's clock from its oscillator.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "eskin/dtmf_top_plan.h"

namespace eskin::fpga {

enum class Family { Ice40, Ecp5 };

struct Board {
  std::string name;         // "icebreaker", "ulx3s"
  Family family;
  std::string device;       // nextpnr device: "up5k"; "25k", "45k", "85k"
  std::string package;      // "sg48", "CABGA381"
  std::string wrapper;      // top module, rtl/<wrapper>.v
  std::string constraints;  // path relative to the source tree
  long osc_hz;              // the board's oscillator
  long default_clk_hz;      // the core's clock unless a scene needs more
  std::string logic_resource;  // nextpnr's logic cell: ICESTORM_LC, TRELLIS_COMB
  std::string hall_wrapper;    // rtl/<hall_wrapper>.v: hall_top or mixed_top
  bool hall_osc_clock = false; // the Hall wrapper can run on the oscillator itself (PLL = 0)
  // The frame engine's barrel shifter (DtmfTopSpec::engine_fast_shift): on
  // where its ~1000 logic cells are cheap (the ECP5s); off on the UP5K, whose
  // default scene keeps its 18 MHz clock either way (but see
  // engine_when_needed).
  bool engine_fast_shift = false;
  // The most parallel DFT lanes (rtl/sdft_lanes.v) the flow may give
  // dtmf_top: each costs a multiplier, a block RAM and logic. A frame's
  // sample gets no shorter beyond 6 (the merger gives a token a clock:
  // KS + 8), but the other samples, which give no tokens, take
  // 6 ceil(KS / L) + 2 (common/eskin/dtmf_top_plan.h's budget), so a 32x32 skin
  // (KS 64) at 1 MS/s and 40 MHz needs 11.
  // iCEBreaker 1: the UP5K has no block RAM left for a second window.
  // ULX3S 32 (a 64x64 skin's 128 carriers at 1 MS/s need 22; 32 lanes of
  // them: 9288 LUT4, 32 MULT18X18D, 33 DP16KD, rtl/sdft_front.v): of the
  // ECP5's 28 (25F) or 156 (85F)
  // multipliers and 56 or 208 DP16KDs; a lane of a 12x12 skin (K_MAX 24,
  // N 64) is about 390 LUT4, 75 CCU2C, 38 DPR16X4 and 360 FF (Yosys 0.23),
  // about 1100 TRELLIS_COMB placed (12x12 at 1 MS/s, 3 -> 5 lanes: 7665 ->
  // 9900).
  int max_sdft_lanes = 1;
  // The hardware neuron unit (DtmfTopSpec::neuron_unit, rtl/izhikevich_layer.v):
  // on the ECP5s, whose logic is cheap; off on the UP5K by default (about
  // 1800 logic cells), but see engine_when_needed.
  bool neuron_unit = false;
  // With the unit: its lanes (DtmfTopSpec::neuron_lanes, rtl/izhikevich_lanes.v),
  // which keep the neurons' state themselves: 3 engine clocks a neuron
  // instead of 14. ULX3S 5 (the fewest the microcode's loop takes; each
  // about 1300 LUT4 and a multiplier, the state in DP16KDs); 0 on the UP5K,
  // which has neither the cells nor the block RAM.
  int neuron_lanes = 0;
  // The engine when needed (choose_core_clock), for the options the user
  // left to the board: when the core of engine_fast_shift / neuron_unit
  // would need a clock above default_clk_hz, the board takes the first of
  // bit-serial, barrel, serial + unit, barrel + unit (fewest logic cells
  // first: about 600 UP5K cells for the shifter, 1800 for the unit) whose
  // core keeps up at default_clk_hz, else the one that needs the slowest
  // clock. The UP5K: a 6x6 skin at 35 kS/s gets the barrel shifter (24.9 ->
  // 15.9 MHz), an 8x8 the bit-serial shifter and the unit (16 670 clocks a
  // frame: 18 MHz; 5229 / 5280 LC), which its PLL's clocks above 18 MHz
  // could not replace (the fabric reaches about 21).
  bool engine_when_needed = false;
  // The streaming datapath (DtmfDatapath::Streaming: rtl/dtmf_chain.v
  // beside the engine, its control plane) when the frame engine alone
  // does not keep up (choose_core_clock): where its logic, multipliers and
  // block RAM are cheap (the ECP5s: a 64x64 skin's chain with its
  // 32 KB FIFO); not on the UP5K, whose skins the engine keeps up with.
  bool streaming = false;
};

// "icebreaker" or "ulx3s"; device_override ("25k", "85k"; empty: the
// board's own) picks another member of the family in the same package.
// Throws std::invalid_argument naming the bad value.
Board find_board(const std::string& name, const std::string& device_override = "");
std::vector<std::string> board_names();

// How the wrapper makes the core's clock: the clock, the UART baud rate that
// divides it exactly, and the wrapper's parameters (PLL dividers).
struct Clocking {
  long clk_hz = 0;
  long baud = 0;
  std::vector<hls::VerilogParam> wrapper_params;
  long adc_clk_hz = 0;  // the ADC's own clock (with_adc_clock), 0: it runs on clk_hz
};

// The clocks the board can give the core exactly, with the fastest UART
// baud rate (3, 2 or 1 Mbaud) that divides each one exactly, ascending.
std::vector<Clocking> board_clocks(const Board& b);

// The slowest of board_clocks() at or above min_hz and the board's default
// clock; none when the board makes no clock that fast.
std::optional<Clocking> slowest_clock_from(const Board& b, long min_hz);

// `core` with a second clock for the ADC (rtl/dtmf_top.v ADC_CLK_HZ) from
// the same PLL, on which adc_ad7476 converts at sample_hz
// (hls::dtmf_top_adc_problem): the fastest such clock up to 40 MHz (SCLK
// at most half of it: the most acquisition time, and the ADC's logic no
// faster than a one-clock 1 MS/s core's). ECP5 only (the ULX3S's EHXPLLL CLKOS, wrapper
// parameter CLKOS_DIV); none on the iCE40 or when no divider gives one.
std::optional<Clocking> with_adc_clock(const Board& b, const Clocking& core, double sample_hz);

// slowest_clock_from(b, min_hz); clk_hz > 0 asks for exactly that clock
// instead. Throws std::invalid_argument listing the clocks the board can
// make.
Clocking choose_clock(const Board& b, long min_hz, long clk_hz = 0);

// The clock of a build with hall_top (alone, or in mixed_top), which counts
// microseconds and so needs a whole number of MHz: exactly clk_hz when > 0,
// else the oscillator itself where the Hall wrapper takes it (iCEBreaker:
// 12 MHz, hall_top's clock, docs/hall_fpga.md), else the board's default
// clock. On the iCE40 the wrapper's PLL parameter (0: oscillator, 1: PLL)
// is among the wrapper parameters. Throws std::invalid_argument naming
// --clk-mhz and the clocks the board can make.
Clocking choose_hall_clock(const Board& b, long clk_hz = 0);

}  // namespace eskin::fpga
