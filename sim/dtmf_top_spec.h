// The FPGA top's spec (hls/dtmf_top_config.h) for a scene: the skin's
// sizes, carriers, ADC and window, the scene's neuron, whether it wants
// spikes, and the FPGA clock.
#pragma once

#include "hls/dtmf_top_config.h"
#include "sim/scene.h"

namespace eskin::sim {

inline hls::DtmfTopSpec dtmf_top_spec(const Scene& sc, long clk_hz = 12000000) {
  hls::DtmfTopSpec s;
  s.rows = sc.skin.rows;
  s.cols = sc.skin.cols;
  s.carrier_hz = sc.skin.carrier_freqs_hz();
  s.sample_hz = sc.skin.adc.rate_hz;
  s.adc_bits = sc.skin.adc.bits;
  s.full_carrier_lsb = sc.skin.full_carrier_lsb();
  s.window = sc.decoder.window;
  s.neuron_preset = sc.neuron.preset;
  s.neuron_input_scale = sc.neuron.input_scale;
  s.spikes = sc.outputs.spikes;
  s.clk_hz = clk_hz;
  return s;
}

}  // namespace eskin::sim
