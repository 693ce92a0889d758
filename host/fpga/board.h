// The boards `eskin bitstream` builds for: which FPGA, which tools, which
// wrapper (rtl/board_*.v) and pins (constraints/), and how the board makes
// the core's clock from its oscillator.
#pragma once

#include <string>
#include <vector>

#include "hls/dtmf_top_config.h"

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
};

// The clocks the board can give the core exactly, with the fastest UART
// baud rate (3, 2 or 1 Mbaud) that divides each one exactly, ascending.
std::vector<Clocking> board_clocks(const Board& b);

// The slowest of board_clocks() at or above min_hz (the board's default
// clock if that is faster); clk_hz > 0 asks for exactly that clock instead.
// Throws std::invalid_argument listing the clocks the board can make.
Clocking choose_clock(const Board& b, long min_hz, long clk_hz = 0);

}  // namespace eskin::fpga
