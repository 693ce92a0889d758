// Device-quantised Hall samples of a shipped scene as FPGA tokens, shared by
// the Hall HLS tests: the scene's world through the sampler (noise, the
// MLX90393 code law), codes sent in the device's format.
#pragma once

#include <string>
#include <vector>

#include "hls/hall_token.h"
#include "sim/hall_sampler.h"
#include "sim/scene.h"

namespace eskin::test {

struct HallTokens {
  sim::Scene scene;
  std::vector<hls::HallSampleToken> tokens;  // sensor by sensor, frame by frame
  std::vector<HallFrame> frames;
};

inline HallTokens hall_tokens(const std::string& scene_file, double seconds) {
  HallTokens h;
  h.scene = sim::load_scene(std::string(ESKIN_SOURCE_DIR) + "/scenes/" + scene_file);
  const sim::HallWorld w(h.scene.hall);
  const HallConfig& c = w.config();
  sim::HallSampler s(c, h.scene.seed);
  for (double t = 0; t < seconds; t += s.period_s()) {
    const HallFrame f = s.sample(w, t);
    h.frames.push_back(f);
    for (const HallSample& x : f) {
      hls::HallSampleToken k;
      k.id = x.sensor;
      k.t = x.t_us;
      uint16_t code[3];
      for (int a = 0; a < 3; ++a)
        code[a] = mlx90393::encode_uT(c.mlx, a, x.lsb[size_t(a)] * mlx90393::sensitivity_uT(c.mlx, a)).code;
      k.x = code[0], k.y = code[1], k.z = code[2];
      k.flags = x.flags;
      h.tokens.push_back(k);
    }
  }
  return h;
}

}  // namespace eskin::test
