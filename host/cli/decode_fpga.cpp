#include "cli/decode_fpga.h"

#include <fmt/format.h>

#include <cstdio>
#include <map>
#include <string>

#include "host/engine/dtmf_engine.h"
#include "host/engine/engine_setup.h"

namespace eskin::cli {

int decode_fpga(const SkinConfig& skin, const DecoderConfig& dec, const NeuronConfig& neuron,
                const std::vector<int>& codes, const FpgaDecodeOptions& opt) {
  if (dec.variant != DftVariant::Exact && dec.variant != DftVariant::Auto)
    throw ConfigError("--variant", std::string("the fpga engine runs the exact sliding DFT only "
                                               "(auto or exact), got ") + to_string(dec.variant));
  if (dec.hann) throw ConfigError("decoder.hann", "the fpga engine has a rectangular window only");
  if (opt.taxels && opt.ghost_correct)
    throw ConfigError("--no-ghost", "the fpga engine has no ghost filter (yet): pass --no-ghost "
                                    "with --taxels/--spikes, or use --engine golden");
  const uint8_t mask = 1 | (opt.taxels || opt.spikes ? 2 : 0) | (opt.spikes ? 4 : 0);
  // The 12 MHz top's build for this skin; --hop (samples) sets the packet
  // decimation, a whole number of the build's steps.
  const hls::DtmfTopPlan plan = engine::top_plan(skin, dec, neuron, opt.spikes);
  int decim = plan.decim;
  if (opt.hop > 0) {
    if (opt.hop % plan.step || opt.hop / plan.step > 65535)
      throw ConfigError("--hop", "the fpga build steps every " + std::to_string(plan.step) +
                                     " samples: expected a multiple of it up to 65535 steps, got " +
                                     std::to_string(opt.hop));
    decim = opt.hop / plan.step;
  }
  const engine::DtmfEngine eng(engine::engine_config(plan, plan.step, uint16_t(decim), mask));
  const auto c12 = engine::codes12(codes, skin.adc.bits);
  const engine::PacketStream ps = eng.run(c12.data(), c12.size(), {opt.threads});

  struct Line { std::string amp, tax, spikes; };
  std::map<uint32_t, Line> lines;  // by the packet step's sample
  const double to_lsb = 2.0 / dec.window;
  for (const auto& p : ps.packets) {
    const uint8_t* b = ps.payload(p);
    const auto u16 = [b](uint32_t at) { return unsigned(b[at] | b[at + 1] << 8); };
    Line& l = lines[p.t];
    std::string& s = p.type == 1 ? l.amp : p.type == 2 ? l.tax : l.spikes;
    if (p.type == 1)
      for (uint32_t i = 0; i < p.len; i += 2) s += fmt::format("{}{:.6g}", i ? "," : "", u16(i) * to_lsb);
    if (p.type == 2)
      for (uint32_t i = 2; i < p.len; i += 2)
        s += fmt::format("{}{:.6g}", i > 2 ? "," : "", skin.conductance.inverse(u16(i) / 32768.0));
    if (p.type == 4)
      for (uint32_t i = 0; i < p.len; i += 5)
        s += fmt::format("{}{}", i ? "," : "", u16(i + 3));
  }
  for (const auto& [t, l] : lines) {
    if (l.amp.empty()) continue;
    std::string out = fmt::format("{{\"sample\":{},\"t_ms\":{:.4f},\"amp_lsb\":[{}]", t,
                                  1000.0 * double(t) / skin.adc.rate_hz, l.amp);
    if (opt.taxels || opt.spikes) out += ",\"pressure_kpa\":[" + l.tax + "]";
    if (opt.spikes) out += ",\"spikes\":[" + l.spikes + "]";
    out += "}\n";
    std::fwrite(out.data(), 1, out.size(), stdout);
  }
  return 0;
}

}  // namespace eskin::cli
