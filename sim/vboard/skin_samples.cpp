#include "sim/vboard/skin_samples.h"

#include <algorithm>
#include <cmath>

#include "sim/world_model.h"

namespace eskin::vboard {

SkinSamples skin_samples(const sim::Scene& scene, int adc_shift, double tail_s,
                         const std::vector<BoardFault>& faults) {
  sim::WorldModel world(scene);
  SkinSamples s;
  const double fs = scene.skin.adc.rate_hz;
  s.sample_hz = fs;
  for (const BoardFault& f : faults)
    if (f.kind == BoardFaultKind::carrier_off)
      world.carrier_off(f.index, f.first_sample(fs), f.end_sample(fs));
  for (int c : world.all_codes()) s.codes.push_back(uint16_t(c << adc_shift));
  for (const BoardFault& f : faults) {
    if (f.kind != BoardFaultKind::adc_stuck_low && f.kind != BoardFaultKind::adc_stuck_high)
      continue;
    const uint16_t rail = f.kind == BoardFaultKind::adc_stuck_low ? 0 : 0x0FFF;
    for (size_t n = f.first_sample(fs); n < std::min(f.end_sample(fs), s.codes.size()); ++n)
      s.codes[n] = rail;
  }
  const size_t tail = size_t(std::ceil(tail_s * fs));
  s.codes.resize(s.codes.size() + tail, uint16_t(1u << 11));
  s.samples = s.codes.size();
  s.codes.resize(s.codes.size() + 64, uint16_t(1u << 11));  // a batch may end past it
  s.scene_samples = world.total_samples();
  return s;
}

}  // namespace eskin::vboard
