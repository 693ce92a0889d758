#include "host/engine/engine_setup.h"

#include <stdexcept>
#include <string>

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
  if (step != plan.step) {
    hls::DtmfTopSpec s = plan.spec;
    s.frame_ms = step * 1000.0 / s.sample_hz;  // make_dtmf_top_plan rounds it back to `step`
    p = hls::make_dtmf_top_plan(s);
    if (p.step != step) throw std::logic_error("with_step: the plan rounded the step");
  }
  if (decim > 0) p.decim_amp = p.decim_tax = uint16_t(decim);
  return p;
}

EngineConfig engine_config(const hls::DtmfTopPlan& p) {
  EngineConfig c;
  c.rows = p.R;
  c.cols = p.C;
  c.sdft.n = p.N;
  c.sdft.xw = 12;  // dtmf_chain: x = code - 2048; CW 16, TW 10, FB 0 (SdftWidthsRt's)
  c.sdft.acc_w = p.acc_w;
  c.mag_shift = p.mag_shift;
  c.inc = p.inc;
  c.demix = p.spec.demix;
  if (c.demix) c.demix_tables = p.demix;
  hls::copy_chain_constants(p, c);
  c.max_spikes = p.max_spikes;
  return c;
}

std::vector<uint16_t> codes12(const std::vector<int>& codes, int adc_bits) {
  std::vector<uint16_t> out(codes.size());
  const int sh = 12 - adc_bits;
  for (size_t i = 0; i < codes.size(); ++i) out[i] = uint16_t(codes[i] << sh);
  return out;
}

}  // namespace eskin::engine
