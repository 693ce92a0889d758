// `eskin decode --engine fpga`: a recording decoded by host/engine (the
// FPGA's integers, bit for bit) instead of the golden model. Same NDJSON
// fields as the golden decoder, one line per packet step (every `hop`
// samples, default: the build's packet rate): "sample", "t_ms", "amp_lsb"
// (2 |sum| / N, skin code LSB peak),
// with --taxels "pressure_kpa" (the taxel's g after the ghost filter
// unless --no-ghost, UQ1.15, through the skin's conductance curve), with
// --spikes "spikes" (receptors, layer 0) and "spikes_layer2" (the weighted
// layer): taxels whose neuron fired in the hop starting at this line's
// frame, once per spike. "sample" is the frame's newest sample.
#pragma once

#include <vector>

#include "eskin/neuron_config.h"
#include "eskin/skin_config.h"

namespace eskin::engine {

struct FpgaDecodeOptions {
  bool taxels = false, spikes = false, ghost_correct = true;
  int threads = 1;
  int hop = 0;  // samples between lines (0: the build's decimation)
};

// codes: the skin's unsigned ADC codes. Throws ConfigError naming the
// option the FPGA path cannot honour.
int decode_fpga(const SkinConfig& skin, const DecoderConfig& dec, const NeuronConfig& neuron,
                const std::vector<int>& codes, const FpgaDecodeOptions& opt);

}  // namespace eskin::engine
