// synapse_weights: the second spiking layer's input. Collects one step of
// first-layer output tokens (which neurons spiked) and emits, per
// postsynaptic neuron i, the weighted spike sum
//     x_i = sat_OUT_W( sum_j W[i][j] s_j ),   s_j in {0, 1}
// as the input token of another izhikevich_layer instance.
// Bit-exact executable spec of rtl/synapse_weights.v.
//
// Number formats: W[i][j] int16 (two's complement, any value); the sum is
// exact (N_IN <= 4096: |sum| <= 4096 * 2^15 = 2^27, held in ACC_W = 16 +
// ceil(log2(N_IN + 1)) bits in the RTL, int64 here) and saturates to signed
// OUT_W bits (2 <= OUT_W <= 32): [-2^(OUT_W-1), 2^(OUT_W-1) - 1]. No rounding
// (integer sums; the izhikevich_layer's gain and x_shift do the scaling).
// Since s_j is 0 or 1 no multiplier is used: W[i][j] is added when s_j = 1.
//
// Streams: in {neuron, t, spike, last} (izhikevich_layer output tokens, any
// order within a step; a neuron that sends no token counts as silent); the
// token with `last` closes the step. out {x, t, last}: N_OUT tokens in
// neuron order, x sign-extended to 32 bits, t of the closing input token,
// last on i = N_OUT - 1. Spike bits are cleared after each step.
// Weights: row-major W[i * N_IN + j], written through a configuration port
// (set_weight; RTL cfg_we/cfg_addr/cfg_data), 0 at power-up; rst clears the
// spike bits, not the weights.
// Timing of the RTL (asserted in tests/rtl/synapse_weights_test.cpp): one
// input token per cycle; after the `last` handshake (cycle 0) output token i
// is valid from cycle (i + 1) * (N_IN + 2) when every output is taken at once
// (II = N_IN + 2 cycles per output token: N_IN weight reads from block RAM,
// one pipeline cycle, one output cycle); in_ready again the cycle after the
// last output handshake.
#pragma once

#include <cstdint>

namespace eskin::hls {

struct SynapseIn {
  uint16_t neuron = 0;  // presynaptic neuron (< N_IN)
  uint32_t t = 0;
  bool spike = false;
  bool last = false;
};

struct SynapseOut {
  int32_t x = 0;  // signed OUT_W-bit weighted sum, sign-extended
  uint32_t t = 0;
  bool last = false;
};

template <int N_IN, int N_OUT, int OUT_W = 16>
class SynapseWeights {
  static_assert(N_IN >= 1 && N_IN <= 4096, "N_IN must be 1..4096");
  static_assert(N_OUT >= 1 && N_OUT <= 4096, "N_OUT must be 1..4096");
  static_assert(OUT_W >= 2 && OUT_W <= 32, "OUT_W must be 2..32");

 public:
  static constexpr int64_t kMax = (int64_t(1) << (OUT_W - 1)) - 1;
  static constexpr int64_t kMin = -(int64_t(1) << (OUT_W - 1));

  SynapseWeights() {
    for (int k = 0; k < N_IN * N_OUT; ++k) w_[k] = 0;
    for (int j = 0; j < N_IN; ++j) s_[j] = false;
  }

  // W[i][j] (postsynaptic i, presynaptic j).
  void set_weight(int i, int j, int16_t w) { w_[i * N_IN + j] = w; }
  int16_t weight(int i, int j) const { return w_[i * N_IN + j]; }

  // Returns the number of output tokens written to out: 0, or N_OUT when
  // `in` closed the step. Neuron indices >= N_IN are ignored (as in the RTL).
  int push(const SynapseIn& in, SynapseOut (&out)[N_OUT]) {
    if (in.neuron < N_IN && in.spike) s_[in.neuron] = true;
    if (!in.last) return 0;
    for (int i = 0; i < N_OUT; ++i) {
      int64_t acc = 0;
      for (int j = 0; j < N_IN; ++j)
        if (s_[j]) acc += w_[i * N_IN + j];
      out[i].x = int32_t(acc > kMax ? kMax : (acc < kMin ? kMin : acc));
      out[i].t = in.t;
      out[i].last = i == N_OUT - 1;
    }
    for (int j = 0; j < N_IN; ++j) s_[j] = false;
    return N_OUT;
  }

 private:
  int16_t w_[N_IN * N_OUT];
  bool s_[N_IN];
};

}  // namespace eskin::hls
