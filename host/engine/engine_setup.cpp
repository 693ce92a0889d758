#include "host/engine/engine_setup.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "hls/izhikevich_layer_config.h"
#include "sim/dtmf_top_spec.h"

namespace eskin::engine {

hls::DtmfTopPlan top_plan(const SkinConfig& skin, const DecoderConfig& dec,
                          const NeuronConfig& neuron, bool spikes, long clk_hz) {
  sim::Scene sc;
  sc.skin = skin;
  sc.decoder = dec;
  sc.neuron = neuron;
  sc.outputs.spikes = spikes;
  return hls::make_dtmf_top_plan(sim::dtmf_top_spec(sc, clk_hz));
}

hls::DtmfTopPlan with_step(const hls::DtmfTopPlan& plan, int step, int decim) {
  if (step < 1) throw std::invalid_argument("step: expected >= 1, got " + std::to_string(step));
  if (decim < 0 || decim > 65535)
    throw std::invalid_argument("decim: expected 0..65535, got " + std::to_string(decim));
  hls::DtmfTopPlan p = plan;
  if (decim > 0) p.decim = uint16_t(decim);
  if (step == p.step) return p;
  p.step = step;
  if (decim == 0) p.decim = uint16_t(std::max(1L, std::lround(p.spec.sample_hz / 1000.0 / step)));
  p.neuron = hls::make_izhikevich_config(hls::izhikevich_fixed_preset(p.spec.neuron_preset),
                                         step * 1000.0 / p.spec.sample_hz,
                                         p.spec.neuron_input_scale / 32768.0, 1);
  return p;
}

EngineConfig engine_config(const hls::DtmfTopPlan& p, uint8_t mask) {
  return engine_config(p, p.step, p.decim, mask);
}

EngineConfig engine_config(const hls::DtmfTopPlan& p, int step, uint16_t decim, uint8_t mask) {
  EngineConfig c;
  c.rows = p.spec.rows;
  c.cols = p.spec.cols;
  c.sdft.n = p.N;
  c.sdft.xw = 12;  // dtmf_top: x = code - 2048; CW, TW, FB: the top's defaults
  c.sdft.acc_w = p.acc_w;
  c.mag_shift = p.mag_shift;
  c.inc = p.carrier_inc;
  c.taxel.rows = uint8_t(p.spec.rows);
  c.taxel.cols = uint8_t(p.spec.cols);
  c.taxel.mode = hls::TaxelMode::Conductance;
  c.taxel.recip_shift = 12;
  c.taxel.recip = p.tax_recip;
  c.neuron = with_step(p, step).neuron;
  c.step = step;
  c.decim_amp = c.decim_tax = decim;
  c.mask = mask;
  return c;
}

std::vector<uint16_t> codes12(const std::vector<int>& codes, int adc_bits) {
  std::vector<uint16_t> out(codes.size());
  const int sh = 12 - adc_bits;
  for (size_t i = 0; i < codes.size(); ++i) out[i] = uint16_t(codes[i] << sh);
  return out;
}

}  // namespace eskin::engine
