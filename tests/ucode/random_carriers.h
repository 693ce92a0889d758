// Stimulus for the DTMF chain's whole-skin tests: the ADC's 12-bit codes of
// random on/off carriers. Every `hold` samples each carrier is drawn on (at
// `on` full carriers) or off; phases are fixed (0.7 k rad for carrier k)
// and a small offset (17 codes) is added, as the ADC rounds and clips. Many
// lines rise and fall at once: the ghost filter's pairing and candidate
// list, and spikes all over the skin, borders included.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

namespace dtmf_stimulus {

// f_hz: the carriers; full_lsb12: one full carrier's amplitude in 12-bit
// codes (the spec's full_carrier_lsb scaled to 12 bits).
inline std::vector<uint16_t> random_carrier_codes(const std::vector<double>& f_hz, double fs,
                                                  double full_lsb12, int samples, int hold,
                                                  uint32_t seed, double on = 1.2) {
  std::mt19937 rng(seed);
  std::bernoulli_distribution coin(0.5);
  std::vector<double> level(f_hz.size(), 0.0);
  std::vector<uint16_t> codes;
  codes.reserve(size_t(samples));
  for (int m = 0; m < samples; ++m) {
    if (m % hold == 0)
      for (auto& l : level) l = coin(rng) ? on : 0.0;
    double v = 17.0;
    for (size_t k = 0; k < f_hz.size(); ++k)
      v += level[k] * full_lsb12 *
           std::cos(2 * M_PI * std::fmod(f_hz[k] / fs * m, 1.0) + 0.7 * double(k));
    codes.push_back(uint16_t(std::clamp(std::lround(v), -2048L, 2047L) + 2048));
  }
  return codes;
}

}  // namespace dtmf_stimulus
