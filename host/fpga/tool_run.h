// One run of the tools for `eskin bitstream` (host/fpga/flow.h): a board
// wrapper with its generated core through scripts/synth_ice40.sh or
// scripts/synth_ecp5.sh (Yosys, nextpnr, icepack / ecppack), and the
// verdict from what nextpnr reported. Every core (DTMF, Hall, mixed) goes
// through it. The script runs from an argument vector (no shell), its
// output into OUT/flow.log. An OUT under /tmp is fine for the ECP5 too:
// synth_ecp5.sh mounts the folder for the WebAssembly tools, whose own /tmp
// is a private one.
#pragma once

#include <string>
#include <vector>

#include "eskin/dtmf_top_plan.h"
#include "host/fpga/board.h"
#include "host/fpga/flow.h"

namespace eskin::fpga {

struct ToolRun {
  std::string top;                         // the board wrapper, rtl/<top>.v
  std::vector<std::string> reads;          // generated Verilog read with it
  std::vector<std::string> defines;        // NAME=VALUE Verilog macros
  std::string constraints;                 // the .pcf / .lpf (absolute path)
  long clk_hz = 0;                         // the clock nextpnr must meet
  std::vector<hls::VerilogParam> params;   // the wrapper's own (chparam)
};

// Runs the tools into opt.out_dir and fills r's resources, clocks, fits,
// meets_timing, bitstream, failure (with the numbers), log and seconds.
// Never throws for a design that does not fit or meet timing; throws
// std::runtime_error when a tool is missing (naming the bootstrap step) or
// cannot be run.
void run_tools(const Board& b, const FlowOptions& opt, const ToolRun& t, FlowReport& r);

// A file's text ("" if it cannot be read: the tools' logs may be missing).
std::string slurp(const std::string& path);

}  // namespace eskin::fpga
