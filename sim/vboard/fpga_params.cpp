#include "sim/vboard/fpga_params.h"

#include <cmath>
#include <cstdint>
#include <cstdio>

#include "eskin/skin_config.h"

namespace eskin::vboard {
namespace {

// What a parameter set is fixed for: sizes, window, rates, the carriers'
// phase increments round(f / fs * 2^32), and the taxel scale
// round(2^27 / (N/2 * full carrier in LSB)) (rtl/dtmf_top.v).
struct Signature {
  int rows, cols, window, bits;
  double rate_hz;
  std::vector<uint32_t> inc;
  long tax_recip;
  bool operator==(const Signature& o) const {
    return rows == o.rows && cols == o.cols && window == o.window && bits == o.bits &&
           rate_hz == o.rate_hz && inc == o.inc && tax_recip == o.tax_recip;
  }
};

Signature signature_of(const sim::Scene& sc) {
  Signature s{sc.skin.rows, sc.skin.cols, sc.decoder.window, sc.skin.adc.bits, sc.skin.adc.rate_hz,
              {}, 0};
  for (double f : sc.skin.carrier_freqs_hz())
    s.inc.push_back(uint32_t(std::llround(f / sc.skin.adc.rate_hz * 4294967296.0)));
  s.tax_recip = std::lround(std::ldexp(1.0, 27) / (sc.decoder.window / 2.0 * sc.skin.full_carrier_lsb()));
  return s;
}

struct KnownSet {
  Signature sig;
  FpgaParams params;
};

std::vector<KnownSet> known_sets() {
  std::vector<KnownSet> k;
  // rtl/dtmf_top.v defaults: scenes/neuroskin2.yaml.
  k.push_back({{3, 3, 32, 10, 35000.0,
                {233155367u, 404954059u, 613566757u, 876173328u, 1018520816u, 1227133513u},
                54067},
               {"default", {}, 12e6, 3e6, 2}});
  // tests/rtl/dtmf_top_test.cmake: 16x16, carriers on odd bins of N = 128.
  Signature s16{16, 16, 128, 10, 35000.0, {}, 13517};
  std::string inc_hex;
  for (int b = 63; b >= 1; b -= 2) {
    char w[9];
    std::snprintf(w, sizeof w, "%08x", unsigned(b) << 25);
    inc_hex += w;
  }
  for (int b = 1; b <= 63; b += 2) s16.inc.push_back(uint32_t(b) << 25);
  k.push_back({s16,
               {"skin16x16",
                {{"R", "16"}, {"C", "16"}, {"N", "128"}, {"ACC_W", "20"}, {"STEP", "16"},
                 {"TOKEN_FIFO", "32"}, {"DECIM_AMP", "16'd8"}, {"DECIM_TAX", "16'd8"},
                 {"TAX_RECIP", "13517"}, {"CARRIER_INC", "1024'h" + inc_hex},
                 {"U_FRAC", "23"}, {"C_CONST", "-30222956"}, {"S2", "12"}, {"S3", "9"},
                 {"S4", "21"}, {"GAIN_SHIFT", "1"}},
                12e6, 3e6, 2}});
  return k;
}

}  // namespace

std::string FpgaParams::key() const {
  if (overrides.empty()) return "default";
  uint64_t h = 1469598103934665603ull;  // FNV-1a over "name=value;"
  for (const auto& [n, v] : overrides)
    for (char c : n + "=" + v + ";") h = (h ^ uint8_t(c)) * 1099511628211ull;
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", (unsigned long long)h);
  return name + "-" + buf;
}

std::vector<std::string> FpgaParams::verilator_args() const {
  std::vector<std::string> a;
  for (const auto& [n, v] : overrides) a.push_back("-G" + n + "=" + v);
  return a;
}

FpgaParams dtmf_top_params(const sim::Scene& scene) {
  if (scene.neuron.preset != "RA" || scene.neuron.input_scale != 10.0 ||
      scene.neuron.input != NeuronInput::Level)
    throw ConfigError("neuron", "the FPGA top has the RA neuron with input: level and "
                                "input_scale: 10 built in; this scene sets other neuron settings");
  const Signature s = signature_of(scene);
  for (const KnownSet& k : known_sets())
    if (k.sig == s) return k.params;
  throw ConfigError("skin", "no FPGA parameter set fits this scene (" + std::to_string(s.rows) +
                                "x" + std::to_string(s.cols) + ", window " +
                                std::to_string(s.window) +
                                "): the virtual board has the default 3x3 build "
                                "(scenes/neuroskin2.yaml) and the 16x16 test build "
                                "(carriers: auto, window 128, 10-bit ADC at 35 kHz)");
}

}  // namespace eskin::vboard
