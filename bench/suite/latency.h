// `eskin bench latency`: cycle-exact latency of every stage of the DTMF top
// and end to end, measured in Verilator for a table of reference builds,
// compared with the baseline in the repository (bench/baselines/latency.csv).
//
// Each build is the top as hls/dtmf_top_config.h plans it for a reference
// scene; its parameters (dtmf_top_params) go to Verilator as -G arguments,
// and bench/latency/latency_harness.cpp (the tests/rtl/dtmf_top_board.h
// bench: AD7476A pin model, UART line decoder, p_* probes) is compiled
// against it. Builds are cached by a hash of the parameters and the sources
// under build/bench/latency/.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

#include "hls/dtmf_top_config.h"

namespace eskin::bench {

// One reference build: a scene and the FPGA clock it is planned for.
struct LatencyConfig {
  std::string name;   // "3x3", "16x16"
  std::string scene;  // path, relative to the source tree
  long clk_hz = 12000000;
  int step = 0;       // 0: the plan's; else engine::with_step (see the table)
  int decim = 0;      // 0: the plan's
};
// The reference builds (the table to extend when a new top exists).
const std::vector<LatencyConfig>& latency_configs();

struct StageLatency {
  std::string stage;
  int64_t cycles = 0;
};

struct LatencyRun {
  LatencyConfig config;
  hls::DtmfTopPlan plan;
  uint32_t sample = 0;  // the measured frame's sample
  std::vector<StageLatency> stages;
  int overruns = 0, dropped = 0;
  double build_seconds = 0;  // 0 when the cached build was used
};

// Builds (or reuses) the harness and measures one reference build.
LatencyRun measure_latency(const LatencyConfig& c, const std::string& cache_dir,
                           std::ostream& log);

// Baseline CSV: "config,stage,cycles" rows.
std::vector<std::pair<std::string, StageLatency>> read_latency_baseline(const std::string& path);
void write_latency_baseline(const std::string& path, const std::vector<LatencyRun>& runs);

// Differences that fail the check (a stage slower than its baseline, or a
// stage in one and not the other), one message each naming config, stage
// and cycles; improvements go to `notes`.
std::vector<std::string> compare_latency(const std::vector<LatencyRun>& runs,
                                         const std::vector<std::pair<std::string, StageLatency>>& base,
                                         std::vector<std::string>& notes);

// The cycle model of a build (docs/fpga.md schedule): cycles from the ADC's
// last data edge to the step's last neuron update. DFT token 0 at 8;
// magnitudes every 26 cycles (token 0 at 8 + 3 behind a frame buffer),
// each 25 cycles after its input; taxels 18 cycles each from 1 cycle after
// the last magnitude; a neuron 11 cycles after its taxel. The trade study
// uses it; `eskin bench latency` checks it against Verilator.
int64_t model_cycles_to_last_neuron(const hls::DtmfTopPlan& plan);

// A board the top is built for, and its synthesised Fmax if a report exists.
struct Board {
  std::string name;
  double nominal_mhz;
  std::vector<std::string> reports;  // nextpnr --report JSON, relative to the build dir
};
const std::vector<Board>& boards();
// Lowest "achieved" Fmax (MHz) in a nextpnr report; 0 if none readable.
double report_fmax_mhz(const std::string& path);

// The latency table: cycles, and µs at each board's Fmax (or nominal clock,
// stated), beside the physical anchors.
std::string format_latency(const std::vector<LatencyRun>& runs, const std::string& build_dir);

}  // namespace eskin::bench
