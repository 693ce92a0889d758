// `eskin bench stability`: the long runs (a benchmark, not CI).
//  * Exact sliding DFT (host/engine/exact_sdft.h, bit-exact with
//    hls/sdft_bank.h) over `samples` worst-case samples: at every checkpoint
//    its sums equal the direct sum of the window's terms recomputed from the
//    kernel's own term definition (0 LSB expected, forever).
//  * The golden naive recursive and damped sliding DFTs (double) on the same
//    input: their amplitude error against the direct DFT at the same
//    checkpoints (the naive form drifts; the damped one is biased, bounded).
//  * Izhikevich neurons (hls/izhikevich_layer.h, both layers as the top's
//    plan configures them) held at the edges of their
//    input range for long runs: v and U stay in range (no wrap), a neuron
//    driven to the maximum spikes every step, one at the minimum is pinned at
//    V_MIN, and afterwards both answer a normal input exactly as a fresh
//    neuron does (no stuck state).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "hls/izhikevich_layer.h"

namespace eskin::bench {

struct DriftPoint {
  uint64_t sample;
  int64_t exact_lsb;           // max |sliding - direct| over carriers, re and im
  double naive_err, damped_err;  // max amplitude error (LSB) over carriers
};

struct NeuronEdge {
  std::string phase;
  uint64_t steps = 0, spikes = 0;
  bool in_range = true;       // v in [V_MIN, V_PEAK), U in [U_MIN, U_MAX] at every step
  std::string note;
};

struct StabilityResult {
  uint64_t samples = 0;
  int carriers = 0, window = 0;
  std::vector<DriftPoint> drift;
  std::vector<NeuronEdge> neurons;
  bool recovered = false;     // after the extremes, same spikes as a fresh neuron
  double seconds = 0;
};

// neurons: the two layers' configurations (the top's plan for a scene).
StabilityResult run_stability(uint64_t samples, uint64_t neuron_steps, int checkpoints,
                              const hls::IzhikevichConfig (&neurons)[2]);
std::string format_stability(const StabilityResult& r);
void write_stability_report(const std::string& path, const StabilityResult& r);

}  // namespace eskin::bench
