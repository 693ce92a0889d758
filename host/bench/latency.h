// `eskin bench latency`: cycle-exact latency of every stage of the DTMF top
// and end to end, measured in Verilator for a table of reference builds,
// compared with the baseline in the repository (bench/baselines/latency.csv).
//
// Each build is the top as common/eskin/dtmf_top_plan.h plans it for a reference
// scene and clock; hls::write_dtmf_top_build writes its microcode and
// constants and returns its parameters, which go to Verilator as -G
// arguments, and bench/latency/latency_harness.cpp (the
// tests/rtl/dtmf_top_board.h bench: AD7476A pin model, UART line decoder,
// p_* probes) is compiled against it. Builds are cached by a hash of the
// parameters, the hex files and the sources under build/bench/latency/.
//
// Stages of one frame, cycles from the ADC's last data edge of its newest
// sample: the sample into sdft_bank, its last DFT token, the frame handed
// to the frame engine, the engine's first output byte, the frame released,
// the first start bit of its packets on the UART, the stop bit of their
// last byte (end to end). The engine's part is checked against the frame
// engine's instruction-set model (host/bench/engine_model.h).
//
// The Hall top (rtl/hall_top.v as sim/hall_top_spec.h generates it for a
// Hall scene; bench/latency/hall_latency_harness.cpp on the bench of
// tests/rtl/hall_top_board.h): from the DRDY of the reading that completes
// a frame to the frame's first and last byte on the UART.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

#include "eskin/dtmf_top_plan.h"

namespace eskin::bench {

// One reference build: a scene, the top built for it and its clock.
struct LatencyConfig {
  enum class Top { Dtmf, Hall };
  std::string name;   // "3x3", "10x10", "16x16", "hall000"
  std::string scene;  // path, relative to the source tree
  long clk_hz = hls::kDtmfTopClkHz;
  Top top = Top::Dtmf;
  // > 0: not the scene itself but fpga::scale_scene(scene, scale_n, 35 kS/s),
  // the bitstream flow's n x n skin (host/fpga/scale_table.h).
  int scale_n = 0;
  // Measured by the CI test (tests/system/bench_latency_test.cpp); the
  // others only by the full `eskin bench latency` (simulation time).
  bool ci = true;
  // TAXELS_SPARSE instead of TAXELS_DENSE: a dense packet of 16x16 taxels
  // (12 + 2 x 256 = 524 bytes) never fits dtmf_top's 512-byte output FIFO, which takes a
  // packet whole or drops it.
  bool sparse_taxels = false;
  // The scene as the ULX3S flow builds it on the streaming datapath
  // (host/fpga/flow.h choose_core_clock, datapath 1, at clk_hz; the
  // bit-serial shifter, which the instruction-set model counts).
  bool streaming = false;
};
// The reference builds (the table to extend when a new top exists).
const std::vector<LatencyConfig>& latency_configs();

struct StageLatency {
  std::string stage;
  int64_t cycles = 0;
};

struct LatencyRun {
  LatencyConfig config;
  hls::DtmfTopPlan plan;  // the DTMF builds' plan (empty for the Hall top)
  uint32_t sample = 0;  // the measured frame's sample
  std::vector<StageLatency> stages;
  int64_t engine_clocks = 0, engine_first_byte = 0;  // Verilator: from frame_capture
  int64_t model_clocks = -1, model_first_byte = -1;  // the ISS model of the same frame
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

// The latency table: cycles, and µs at each build's clock, beside the
// physical anchors and the model check.
std::string format_latency(const std::vector<LatencyRun>& runs);

}  // namespace eskin::bench
