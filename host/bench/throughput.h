// Throughput of the decoders on one scene's ADC stream, side by side in one
// run: an FFTW full-overlap STFT (window N, hop 1, r2c every sample, the
// magnitude of the bin nearest each carrier), every golden estimator
// (host/golden/sdft_bank.h: push, then every carrier's magnitude), the fast
// engine's amplitudes (host/engine/exact_sdft.h: push, then every carrier's
// exact carrier_magnitude: the same workload), and the whole decoders: the
// golden decoder (taxels, ghost correction, spikes) and the engine's FPGA
// chain (packets) on one thread, on `threads` threads (wall clock), and
// `threads` skins decoded at once, one a thread (wall clock, all samples).
#pragma once

#include <string>
#include <vector>

#include "eskin/dtmf_top_plan.h"
#include "sim/scene.h"

namespace eskin::bench {

struct ThroughputRow {
  std::string name;
  double samples_per_s = 0;
  double vs_fftw = 0;    // samples_per_s / FFTW's
  double checksum = 0;   // sum of |amplitude| over the pass (amplitude rows), packets (chain)
  std::string clock;     // "cpu" (thread CPU time) or "wall"
};

struct ThroughputResult {
  std::string scene;
  int carriers = 0, window = 0, chain_step = 1, threads = 1;
  long clk_hz = 0;  // clock of the top build the chain rows run
  double fs = 0;
  size_t samples = 0;
  std::vector<ThroughputRow> rows;
  const ThroughputRow& row(const std::string& name) const;
};

// The top's plan at the slowest of 12, 48, 100, 200, 400 MHz that can take
// the scene's skin (a big skin needs a faster clock for a legal neuron step).
hls::DtmfTopPlan feasible_plan(const sim::Scene& sc, long& clk_hz);

ThroughputResult measure_throughput(const std::string& scene_path, double min_seconds, int threads);
// Fixed-width table; `real_time_hz` adds a column "x real time".
std::string format_throughput(const ThroughputResult& r);

}  // namespace eskin::bench
