// `eskin bitstream`'s flow: the core a scene needs in a board wrapper,
// through Yosys, nextpnr and icepack / ecppack (run by
// scripts/synth_ice40.sh and scripts/synth_ecp5.sh, host/fpga/tool_run.h),
// and the report of what it used and how fast it runs. The core:
//   a skin only: rtl/dtmf_top.v (common/eskin/dtmf_top_plan.h) in rtl/board_<board>.v;
//   Hall sensors only: rtl/hall_top.v (sim/hall_top_spec.h) in
//     rtl/board_<board>_hall.v, with the sensors' I2C and DRDY pins
//     (hall_pins.h);
//   both: rtl/mixed_top.v (both parameter sets, one clock: the DTMF one's)
//     in rtl/board_<board>_hall.v with the ADC's pins as well.
#pragma once

#include <string>
#include <vector>

#include "eskin/dtmf_top_plan.h"
#include "host/fpga/board.h"
#include "host/fpga/engine_load.h"
#include "host/fpga/hall_pins.h"
#include "ucode/dtmf_frame_bound.h"
#include "sim/hall_top_spec.h"
#include "sim/scene.h"

namespace eskin::fpga {

// Which engine load the clock must carry (engine_load.h): the scene's own
// frames (its workload; a command may still delay one frame), or the
// stress signals' longest frame plus the longest command (no frame lost
// whatever the input).
enum class LoadPolicy { Scene, Stress };

struct FlowOptions {
  std::string source_dir;  // the eskin source tree (rtl/, scripts/, constraints/)
  std::string out_dir;     // where the wrapper, logs, reports and bitstream go
  int seed = 1;            // nextpnr placer seed (the first one tried)
  // Placer seeds to try: a design that fits but misses timing is placed
  // again at seed + 1, ... until one meets it, `seeds` runs at most.
  int seeds = 1;
  LoadPolicy load = LoadPolicy::Scene;
  long clk_hz = 0;         // 0: the slowest board clock (not below the board's
                           // default) at which the core keeps up
  int fast_shift = -1;     // the engine's barrel shifter: 1 on, 0 off, -1 the board's
  int neuron_unit = -1;    // the hardware neuron unit: 1 on, 2 with its lanes, 0 off, -1 the board's
  int datapath = -1;       // 0 the frame engine alone, 1 the streaming datapath, -1 the board's
                           // choice (choose_core_clock)
};

struct Resource {
  std::string name;  // nextpnr's name (ICESTORM_LC, TRELLIS_COMB, ...)
  long used = 0, available = 0;
};

struct ClockResult {
  std::string net;
  double achieved_mhz = 0, required_mhz = 0;
};

// Which top a scene needs.
enum class Core { Dtmf, Hall, Mixed };
Core scene_core(const sim::Scene& scene);
const char* core_top(Core c);  // "dtmf_top", "hall_top", "mixed_top"

// The Hall side of a Hall or mixed build.
struct HallReport {
  sim::HallTopSpec spec;            // buses, sensors, decoding (sim/hall_top_spec.h)
  std::vector<std::string> decode;  // the scene's decode: list, by name
  HallPins pins;                    // the I2C and DRDY pins (or the failure)
  int pins_available = 0;           // the board's free pins for them
};

struct FlowReport {
  std::string board, device, scene;
  Core core = Core::Dtmf;
  long clk_hz = 0, baud = 0;        // the core's clock and UART as built
  bool pll = true;                  // the clock comes from the PLL (else the oscillator)
  HallReport hall;                  // Hall and mixed builds
  hls::DtmfTopSpec spec;            // DTMF and mixed builds: clk_hz and baud as built
  int step = 1;                      // from the plan
  EngineLoad load;                   // the frame engine's clocks per frame
  hls::DtmfFrameBound bound;         // their static bound (budget.bound_clocks: its total)
  LoadPolicy policy = LoadPolicy::Scene;
  long engine_clocks = 0;            // what the policy makes the clock carry
  long core_min_hz = 0;              // no slower clock keeps up (a lower bound)
  std::string core_min_reason;       // what sets it (dtmf_top_min_clock_reason)
  hls::DtmfTopClockBudget budget;    // at the chosen clock
  std::vector<hls::VerilogParam> params;  // the core's, then the wrapper's
  std::vector<Resource> resources;   // nextpnr's utilisation (post-pack)
  std::string logic_resource;        // the board's logic cell resource name
  std::vector<ClockResult> clocks;   // per clock net
  bool ran_tools = false;            // false: stopped before Yosys (clock)
  bool fits = false, meets_timing = false;
  std::string bitstream;             // path, empty if none was written
  std::string failure;               // why it failed, with the numbers
  std::string log;                   // the tools' combined output
  double seconds = 0;                // wall time of the tools (every seed tried)
  int seed = 0, seeds_tried = 0;     // the placer seed of this report; how many ran

  bool ok() const { return fits && meets_timing && !bitstream.empty(); }
  const Resource* resource(const std::string& name) const;
  // The clock with the least margin (Fmax / required; the first of equals),
  // nullptr without clocks.
  const ClockResult* slowest_clock() const;
};

// The DFT lanes (rtl/sdft_lanes.v) for a plan on board `b`: the fewest, up
// to the board's max_sdft_lanes, with which the DFT needs no faster clock
// than the board clock the ADC and the engine (engine_clocks) already need
// (hls::dtmf_top_sdft_min_period at its sample period, a clock shorter
// when the ADC needs a clock of its own there); the board's most
// when none does (the budget then names the DFT). 1 when the ADC cannot
// convert at the rate at all. Counts the sample FIFO a board with more
// than one lane may have (choose_sdft_fifo).
int choose_sdft_lanes(const Board& b, const hls::DtmfTopPlan& plan, long engine_clocks);

// The sample FIFO in front of the lanes (DtmfTopSpec::sdft_fifo,
// rtl/sdft_front.v) for the plan's lanes: the plan's own when the DFT keeps
// up with it, else 4 where the board allows one (more than one lane) and
// that keeps up: a frame's sample may then hold the lanes for several
// sample periods (K = 128 at 1 MS/s: KS + 8 = 136 clocks against 40).
int choose_sdft_fifo(const Board& b, const hls::DtmfTopPlan& plan, long engine_clocks);

// The core's clock for a scene on board `b`: the plan, the engine's load
// (engine_load.h) under `policy`, the DFT lanes (choose_sdft_lanes; the
// plan's spec carries them), and the slowest of the board's clocks
// (not below its default) at which every budget holds, or exactly
// `clk_hz` when > 0. `budget.ok()` is false when no clock keeps up (the
// board's default or the asked-for clock is returned with the problems).
// The plan's spec carries the chosen clock and baud rate, and its packet
// decimation is planned for that baud rate.
// The clock is chosen for the measured load (`engine_clocks`); `bound` is
// its static bound (ucode/dtmf_frame_bound.h), which run_flow then checks
// at that clock: a build whose bound takes more than its datapath's share
// of the frame (hls::dtmf_frame_bound_limit_percent, 90 % on the frame
// engine) is refused before the tools, naming the bound, the frame and the
// limit (FlowReport::failure "frame bound: ...").
struct CoreClock {
  hls::DtmfTopPlan plan;
  EngineLoad load;
  hls::DtmfFrameBound bound;  // the plan's as built (its DFT lanes)
  long engine_clocks = 0;  // what the policy makes the clock carry
  long core_min_hz = 0;    // no slower clock keeps up (a lower bound)
  Clocking clocking;
  hls::DtmfTopClockBudget budget;
};
// The neuron lanes a build gets (DtmfTopSpec::neuron_lanes) for the option
// neuron_unit (FlowOptions): 2, the board's or 5 (a skin of more than 1024
// taxels is then refused by make_dtmf_top_plan, naming the limit); -1, the
// board's with its unit, 0 beyond 1024 taxels; else 0.
int neuron_lanes_for(const Board& b, int neuron_unit, int taxels);
// The engine a build of `spec` gets for the options fast_shift and
// neuron_unit (FlowOptions; -1 the board's): the shifter, the neuron unit
// and its lanes (neuron_lanes_for), set in `spec`.
void apply_engine_options(const Board& b, int fast_shift, int neuron_unit,
                          hls::DtmfTopSpec& spec);

// fast_shift: the engine's barrel shifter, 1 on, 0 off, -1 the board's
// (Board::engine_fast_shift); neuron_unit likewise (Board::neuron_unit; 2:
// with its lanes, neuron_lanes_for). On
// a board with Board::engine_when_needed the options left to it (-1) may
// change where its defaults do not keep up (the plan's spec says which).
// own_adc_clock: a clock whose budget fails only for the ADC (the AD7476A's
// SCLK bands) may give the ADC a clock of its own (with_adc_clock; the
// plan's spec.adc_clk_hz and the clocking say so); dtmf_top builds only,
// mixed_top has one clock.
// datapath: 0 the frame engine alone (DtmfDatapath::FrameEngine); 1 the
// streaming datapath (DtmfDatapath::Streaming: rtl/dtmf_chain.v, the engine
// its control plane, no neuron unit: neuron_unit 1 or 2 is refused with
// std::invalid_argument); -1 the board's choice: on a board with
// Board::streaming, a plan the chain can build (streaming_possible) and no
// neuron unit asked for (neuron_unit 1 or 2: the engine's), of
// the two whose measured load and static bound keep up at a board clock the
// one at the slower clock (the engine on a tie), the one that keeps up when
// only one does, the streaming one when neither does, and the streaming one
// when the engine cannot hold the skin at all; elsewhere the frame engine. The plan's
// spec.datapath says which. The clock chosen is the slowest at which the
// measured load keeps up, on the streaming datapath also the static bound
// within its 70 % of the frame (the frame engine's bound is checked by
// run_flow at the clock its measured load chose).
CoreClock choose_core_clock(const Board& b, const sim::Scene& scene, LoadPolicy policy,
                            long clk_hz = 0, int fast_shift = -1, int neuron_unit = -1,
                            bool own_adc_clock = true, int datapath = -1);
// "engine" or "streaming": `eskin bitstream --datapath`'s values, the
// report's and the scale table's.
const char* datapath_name(hls::DtmfDatapath d);
// Whether rtl/dtmf_chain.v can do a spec's frames: bin-centred carriers
// (no demixing), at most 255 rows and 255 columns.
bool streaming_possible(const hls::DtmfTopSpec& spec);

// Throws ConfigError("--out", ...) naming the path when the tools cannot be
// given it: the core wrapper names its $readmemh files in Verilog strings
// and Yosys takes file names in its own quotes, neither of which can hold a
// double quote, a backslash or a newline. Any other character (spaces,
// quotes, $, ;) is fine.
void check_out_dir_for_tools(const std::string& out_dir);

// Builds the scene's core (scene_core) on board `b`: for a skin the plan,
// the engine's load (engine_load.h), the clock, the microcode and constant
// files; for Hall sensors hall_top's parameters at the Hall clock
// (choose_hall_clock; a mixed build's is the DTMF one's) and the pins; the
// core wrapper and (Hall) the constraints in OUT; then the tools. Never
// throws for a design that does not fit, has too few pins or misses timing
// (the report says so, with the numbers); throws std::runtime_error when a
// tool is missing or fails otherwise, std::invalid_argument for a clock the
// board cannot make or a skin the plan or the frame engine cannot build,
// and ConfigError naming the hall: field hall_top cannot carry.
FlowReport run_flow(const Board& b, const sim::Scene& scene, const FlowOptions& opt);

// The report as JSON (written to OUT/bitstream_report.json) and as a table.
std::string report_json(const FlowReport& r);
// What the report should say even when the build passed (a load beyond the
// frame under the other policy).
std::vector<std::string> flow_warnings(const FlowReport& r);
std::string report_table(const FlowReport& r);

// Parsers of the tools' output (public for the tests): nextpnr's
// report.json, and its log's "Device utilisation" block when it stopped
// before writing one.
void parse_nextpnr_report(const std::string& json_text, FlowReport& r);
std::vector<Resource> parse_nextpnr_utilisation(const std::string& log_text);

}  // namespace eskin::fpga
