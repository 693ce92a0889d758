#include "host/engine/decode_fpga.h"

#include <fmt/format.h>

#include <cstdio>
#include <map>
#include <string>

#include "hls/dtmf_chain.h"
#include "host/engine/dtmf_engine.h"
#include "host/engine/engine_setup.h"

namespace eskin::engine {

int decode_fpga(const SkinConfig& skin, const DecoderConfig& dec, const NeuronConfig& neuron,
                const std::vector<int>& codes, const FpgaDecodeOptions& opt) {
  if (dec.variant != DftVariant::Exact && dec.variant != DftVariant::Auto &&
      dec.variant != DftVariant::LsDemix)
    throw ConfigError("--variant", std::string("the fpga engine runs the exact sliding DFT, "
                                               "demixed by least squares when the carriers are "
                                               "off bin centres (auto, exact or ls), got ") +
                                       to_string(dec.variant));
  if (dec.hann) throw ConfigError("decoder.hann", "the fpga engine has a rectangular window only");
  // The top's build for this skin (common/eskin/dtmf_top_plan.h); --hop (samples)
  // sets both packet decimations, a whole number of the build's frames.
  hls::DtmfTopPlan plan = engine::top_plan(skin, dec, neuron, opt.spikes);
  plan.spec.ghost = opt.ghost_correct;
  plan.mask = uint8_t(hls::kMaskAmplitudes | (opt.taxels || opt.spikes ? hls::kMaskTaxels : 0) |
                      (opt.spikes ? hls::kMaskSpikes : 0));
  if (opt.hop > 0) {
    if (opt.hop % plan.step || opt.hop / plan.step > 65535)
      throw ConfigError("--hop", "the fpga build makes a frame every " + std::to_string(plan.step) +
                                     " samples: expected a multiple of it up to 65535 frames, got " +
                                     std::to_string(opt.hop));
    plan.decim_amp = plan.decim_tax = uint16_t(opt.hop / plan.step);
  }
  // Spike windows and taxel packets share a decimation; lines need the
  // amplitudes on the same frames.
  plan.decim_amp = plan.decim_tax;
  const engine::DtmfEngine eng(engine::engine_config(plan));
  const auto c12 = engine::codes12(codes, skin.adc.bits);
  const engine::PacketStream ps = eng.run(c12.data(), c12.size(), {opt.threads});

  struct Line { std::string amp, tax, spikes[2]; };
  std::map<uint32_t, Line> lines;  // by the packet step's sample
  const double to_lsb = 2.0 / dec.window;
  for (const auto& p : ps.packets) {
    const uint8_t* b = ps.payload(p);
    const auto u16 = [b](uint32_t at) { return unsigned(b[at] | b[at + 1] << 8); };
    Line& l = lines[p.t];
    if (p.type == hls::kDtmfAmplitudes)
      for (uint32_t i = 0; i < p.len; i += 2)
        l.amp += fmt::format("{}{:.6g}", i ? "," : "", u16(i) * to_lsb);
    if (p.type == hls::kDtmfTaxelsDense)
      for (uint32_t i = 2; i < p.len; i += 2)
        l.tax += fmt::format("{}{:.6g}", i > 2 ? "," : "", skin.conductance.inverse(u16(i) / 32768.0));
    if (p.type == hls::kDtmfSpikes)
      for (uint32_t i = 0; i < p.len; i += 5) {
        std::string& s = l.spikes[b[i + 2] & 1];
        s += fmt::format("{}{}", s.empty() ? "" : ",", u16(i + 3));
      }
  }
  for (const auto& [t, l] : lines) {
    if (l.amp.empty()) continue;
    std::string out = fmt::format("{{\"sample\":{},\"t_ms\":{:.4f},\"amp_lsb\":[{}]", t,
                                  1000.0 * double(t) / skin.adc.rate_hz, l.amp);
    if (opt.taxels || opt.spikes) out += ",\"pressure_kpa\":[" + l.tax + "]";
    if (opt.spikes)
      out += ",\"spikes\":[" + l.spikes[0] + "],\"spikes_layer2\":[" + l.spikes[1] + "]";
    out += "}\n";
    std::fwrite(out.data(), 1, out.size(), stdout);
  }
  return 0;
}

}  // namespace eskin::engine
