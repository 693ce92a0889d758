// synapse_weights: the second spiking layer's input, a 3x3 synaptic kernel
// over the taxel grid. Postsynaptic neuron (i, j) of layer 2 sums the
// weights of the layer-1 receptors around taxel (i, j) that spiked this
// step:
//     x_ij = sum_{di, dj in -1..1} W[di+1][dj+1] * s(i+di, j+dj),
//     s in {0, 1}, s = 0 outside the grid.
// One kernel for every position: the weights do not grow with the skin (a
// dense R C x R C matrix would need 2^20 weights at 32x32), and the default
// (centre-surround: centre +, neighbours -) makes layer 2 fire for a
// contact's centre rather than its whole area. Bit-exact spec of the
// `synapse_weights` routine of the frame engine (rtl/ucode/dtmf_chain.fe).
//
// Number formats: W int16 (any value), s one bit; the sum is exact, |x| <=
// 9 * 2^15 < 2^19 (no rounding, no saturation: izhikevich_layer's x_shift
// and gain do the scaling). Weights change at run time (SET_WEIGHT).
#pragma once

#include <cstdint>

namespace eskin::hls {

struct SynapseWeightsConfig {
  uint8_t rows = 3, cols = 3;
  int16_t w[9] = {};  // W[di+1][dj+1] at index (di+1)*3 + (dj+1)
};

template <int R_MAX, int C_MAX>
class SynapseWeights {
  static_assert(R_MAX >= 1 && C_MAX >= 1 && R_MAX * C_MAX <= 65536, "sizes");

 public:
  using Config = SynapseWeightsConfig;

  bool configure(const Config& c) {
    if (c.rows < 1 || c.rows > R_MAX || c.cols < 1 || c.cols > C_MAX) return false;
    cfg_ = c;
    return true;
  }
  void set_weight(int id, int16_t w) { cfg_.w[id] = w; }
  const Config& config() const { return cfg_; }

  // spiked: layer-1 spikes of this step, row-major rows x cols.
  int32_t input(const bool* spiked, int i, int j) const {
    int32_t x = 0;
    for (int di = -1; di <= 1; ++di)
      for (int dj = -1; dj <= 1; ++dj) {
        const int r = i + di, c = j + dj;
        if (r < 0 || r >= cfg_.rows || c < 0 || c >= cfg_.cols) continue;
        if (spiked[r * cfg_.cols + c]) x += cfg_.w[(di + 1) * 3 + (dj + 1)];
      }
    return x;
  }

 private:
  Config cfg_{};
};

}  // namespace eskin::hls
