// What every eskin-vboard executable shares (vboard_main.cpp: the DTMF top,
// vboard_hall_main.cpp: the Hall top, vboard_mixed_main.cpp: both): its
// command line, the board's two sides fed from the scene, the JSON status
// lines on stdout (docs/vboard.md, "Status lines"), and the end of a run.
#pragma once

#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sim/hall_sensor_array.h"
#include "sim/scene.h"
#include "sim/vboard/board_faults.h"
#include "sim/vboard/skin_samples.h"
#include "sim/vboard/line_faults.h"
#include "sim/vboard/pty_port.h"
#include "sim/vboard/virtual_board.h"

namespace eskin::vboard {

struct VboardArgs {
  std::string scene, pty_link, trace;
  bool no_wait = false;
  double reader_timeout_s = 60;
  uint64_t hold_for_host_bytes = 0;  // start only once the host has sent this many bytes
  double tail_s = kSkinTailS;  // idle time after the scene, to let the last frames out
  LineFaultArgs line_args;  // --ber, --drop-rate, ... as given
  LineFaultOptions line;    // ... parsed (docs/vboard.md, "Line faults")
  std::string tap_to_host;  // the FPGA's bytes before the line's faults, to this file
  std::vector<std::string> fault_args;  // --fault values as given
  std::vector<BoardFault> faults;       // ... parsed (docs/vboard.md, "Board faults")
  // The cycle level's board (vboard_cycle_main.cpp) is one executable for
  // every build: the build it models is given at run time (--clk-hz,
  // --baud, --engine-shifter, --neurons). Boards compiled for one build
  // have no such options.
  struct Build {
    long clk_hz = 0, baud = 0;
    bool fast_shift = false, neuron_unit = false;
  } build;
};

// sc_main's body: stdout kept for the JSON lines (`json` in `run`),
// (build_options: the board takes its build's options, VboardArgs::Build),
// everything else written to fd 1 (SystemC's banner) sent to stderr; the
// arguments parsed; `run` called; errors printed as "eskin-vboard: error:".
int vboard_cli_main(int argc, char** argv, const std::string& title, double default_tail_s,
                    const std::function<int(const VboardArgs&, FILE* json)>& run,
                    bool build_options = false);

// The start, trace and fault options into the board's configuration;
// throws std::invalid_argument for a board fault this board cannot have
// (check_board_faults).
void apply_start_options(const VboardArgs& a, BoardConfig& cfg, int carriers, int buses);

// Throws, naming both, when the scene needs another build (`kind`: "FPGA",
// "Hall", "mixed") than this board's: boards are made per build by
// `eskin simulate`.
void require_build(const std::string& scene_file, const std::string& kind,
                   const std::string& needed, const std::string& board_key);

// The ADC side: the skin's samples as 12-bit codes (scene codes << shift),
// then `tail_s` of mid-scale so the last frames get out; the run ends once
// the ADC has taken them; cfg.faults' ADC faults applied (carrier-off in
// the world, a stuck ADC on the codes). Returns the scene's own sample
// count.
size_t load_skin_samples(BoardConfig& cfg, const sim::Scene& scene, int adc_shift, double tail_s);

// Per Hall sensor slot, the times (ns) each conversion the FPGA read
// completed (DRDY rose): the start of the DRDY -> host latency, for the
// `done` line.
nlohmann::json drdy_times_ns(const sim::HallSensorArray& sensors);

// {"event":"ready","pty":...,"params":key,"clk_hz":...,"baud":..., extra...}
void print_ready(FILE* json, const PtyPort& pty, const std::string& key, double clk_hz, double baud,
                 const nlohmann::json& extra);
// {"event":"done", the board's figures, extra...}; throws if the board
// stopped with an error.
void print_done(FILE* json, const BoardStats& s, const nlohmann::json& extra);
// The end of a run, after the done line: the board hangs up (closes the
// pty master, removes its symlink), so that a reader sees the end of the
// stream instead of waiting on a board with nothing more to send. Closing
// the master discards what the reader has not read yet, so it hangs up
// once the reader has read every byte (the pty's queue seen empty twice,
// 10 ms apart: a write may still be on its way into the queue), or at
// once when nobody reads, or when the reader has read nothing for
// `timeout_s` (then it says so on stderr).
void hang_up_when_read(PtyPort& pty, const BoardStats& s, double timeout_s);

// A DTMF board's configuration: the build's clock and UART rate, the start
// options (faults), the skin's samples with `adc_shift` (FpgaBuild's);
// returns the ready line's fields (top, sample_hz, samples, scene_samples).
nlohmann::json dtmf_board_config(const VboardArgs& a, const sim::Scene& scene, double clk_hz,
                                 double baud, int adc_shift, BoardConfig& cfg);

// Every board's run from its ready line to its hang-up: the board on `fpga`
// and `pty` with `cfg`, the ready line (build `key`, ready_extra), the
// simulation, the FPGA's trace closed, the done line (done_extra(), read
// once the board has finished: nullptr for none) and the hang-up once the
// reader has read every byte. Returns the board's exit code (0).
int run_to_end(const VboardArgs& a, FILE* json, FpgaModel& fpga, PtyPort& pty,
               const BoardConfig& cfg, const std::string& key, const nlohmann::json& ready_extra,
               const std::function<nlohmann::json()>& done_extra = nullptr);

}  // namespace eskin::vboard
