// eskin simulate: a scene on the SystemC virtual board (sim/vboard/), read
// over its serial port (a pty) like a real board; the golden model on the
// same samples; both scored against the scene's ground truth; one
// self-contained HTML report plus the raw outputs (docs/vboard.md). A DTMF
// skin, Hall sensors (rtl/hall_top.v) or both on one board
// (rtl/mixed_top.v), as the scene has them.
#pragma once

#include <string>

#include "sim/vboard/board_faults.h"
#include "sim/vboard/line_faults.h"

namespace eskin::simulate {

// How much of the board a run models (docs/vboard.md, "Fidelity levels"):
// rtl, the Verilated FPGA top clock by clock behind a pty; cycle, the same
// board with the FPGA's clock-exact C++ models (sim/cycle/dtmf_top.h);
// packet, the FPGA's integer chain's packets timed per packet
// (host/simulate/packet_board.h).
enum class Fidelity { rtl, cycle, packet };
// "rtl" / "cycle" / "packet"; parse_fidelity throws
// ConfigError("--fidelity", ...) for any other word.
const char* fidelity_name(Fidelity f);
Fidelity parse_fidelity(const std::string& s);

struct SimulateOptions {
  std::string scene;             // scene file (YAML)
  std::string out = "eskin-out"; // output directory (created)
  std::string trace;             // FST waveform of the FPGA, if not empty
  // Faults on the serial line (docs/vboard.md, "Line faults"); with any on,
  // the run also checks what the host delivered against what the FPGA
  // sent (line.json, and the report's table).
  vboard::LineFaultOptions line;
  // Faults of the board itself (docs/vboard.md, "Board faults"), passed to
  // the board, which times them (its done line's "board_faults").
  std::vector<vboard::BoardFault> faults;
  Fidelity fidelity = Fidelity::rtl;
  // The board executable to run instead of the one the scene's build
  // needs ("": that one), e.g. a Verilator variant of the default board
  // (eskin bench sim-speed --verilator); the board refuses a scene of
  // another build.
  std::string board;
};

// Loads the scene (a bad scene throws before anything runs), runs it on
// the virtual board and writes the report. Returns the process exit code.
int run_simulate(const SimulateOptions& o);

}  // namespace eskin::simulate
