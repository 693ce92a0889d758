// spike_encoder: spike tokens -> address-event (AER) words for the host link.
// Bit-exact executable spec of rtl/spike_encoder.v.
//
// Input: izhikevich_layer output tokens plus the layer id {layer, neuron, t,
// spike}; tokens with spike = 0 are consumed and dropped, each spike becomes
// one word. Word format (W = 32 + LAYER_W + ADDR_W bits, default 48):
//   bits [W-1 : LAYER_W+ADDR_W]      t       sample counter, 32 bits
//   bits [LAYER_W+ADDR_W-1 : ADDR_W] layer   LAYER_W bits (default 4)
//   bits [ADDR_W-1 : 0]              neuron  ADDR_W bits (default 12)
// held in the low W bits of a uint64_t (upper bits zero). Suggested byte
// order on the link: most significant byte first (link_framer decides).
// Widths: the RTL ports for layer and neuron are LAYER_W and ADDR_W bits
// wide, so higher bits do not exist there; here they are masked off the
// same way (callers keep neuron < 2^ADDR_W, layer < 2^LAYER_W).
// No arithmetic, no rounding, no saturation.
// Timing of the RTL: a register stage, one token per cycle (II = 1),
// out_valid the cycle after the input handshake (LATENCY 1); in_ready =
// !out_valid || out_ready.
#pragma once

#include <cstdint>

namespace eskin::hls {

struct SpikeEncoderIn {
  uint8_t layer = 0;
  uint16_t neuron = 0;
  uint32_t t = 0;
  bool spike = false;
};

template <int LAYER_W = 4, int ADDR_W = 12>
struct SpikeEncoder {
  static_assert(LAYER_W >= 1 && LAYER_W <= 8, "LAYER_W must be 1..8");
  static_assert(ADDR_W >= 1 && ADDR_W <= 16, "ADDR_W must be 1..16");
  static constexpr int kWordBits = 32 + LAYER_W + ADDR_W;

  // Returns true and sets word when the token carries a spike.
  bool push(const SpikeEncoderIn& in, uint64_t& word) const {
    if (!in.spike) return false;
    const uint64_t layer = in.layer & ((1u << LAYER_W) - 1u);
    const uint64_t neuron = in.neuron & ((1u << ADDR_W) - 1u);
    word = (uint64_t(in.t) << (LAYER_W + ADDR_W)) | (layer << ADDR_W) | neuron;
    return true;
  }
};

}  // namespace eskin::hls
