// Integer square root, one result bit per step (restoring, digit by digit).
// The HLS kernels' root (taxel_reconstruct, ghost_filter); the frame engine
// (rtl/frame_engine.v) computes the same digits with its `sqrt` instruction,
// one digit per two clocks.
//
// isqrt<W>(x) = floor(sqrt(x)) for any x < 2^(2W), W <= 16; isqrt64(x) for
// any 64-bit x.
// Widths: radicand 2W bits, root W bits, partial remainder W + 2 bits.
// No multiplier: only shifts, a (W+2)-bit compare and subtract per step.
#pragma once

#include <cstdint>

namespace eskin::hls {

// State of one digit-by-digit square root in progress (what the RTL keeps in
// registers): the radicand bits not consumed yet, the root so far, the
// partial remainder.
template <int W>
struct IsqrtState {
  static_assert(W >= 1 && W <= 16, "isqrt: W must be 1..16 (radicand <= 32 bits)");
  uint32_t rad = 0;   // radicand, consumed from the top, two bits per step
  uint32_t root = 0;  // W bits when done
  uint32_t rem = 0;   // W + 2 bits

  void start(uint32_t x) { rad = x; root = 0; rem = 0; }
  // One step: bring down the next two radicand bits, try root digit 1.
  void step() {
    const uint32_t top = (rad >> (2 * W - 2)) & 3u;
    rad = (W == 16) ? (rad << 2) : ((rad << 2) & ((uint32_t(1) << (2 * W)) - 1u));
    const uint32_t r = (rem << 2) | top;
    const uint32_t trial = (root << 2) | 1u;
    if (r >= trial) { rem = r - trial; root = (root << 1) | 1u; }
    else            { rem = r;         root = root << 1; }
  }
};

template <int W>
inline uint32_t isqrt(uint32_t x) {
  IsqrtState<W> s;
  s.start(x);
  for (int i = 0; i < W; ++i) s.step();
  return s.root;
}

// floor(sqrt(x)) for any 64-bit x, the same method two radicand bits per
// step (32 steps); for models of wider roots (ucode/frame_engine.h).
inline uint64_t isqrt64(uint64_t x) {
  uint64_t rem = 0, root = 0;
  for (int i = 31; i >= 0; --i) {
    rem = (rem << 2) | ((x >> (2 * i)) & 3u);
    const uint64_t trial = (root << 2) | 1u;
    root <<= 1;
    if (rem >= trial) {
      rem -= trial;
      root |= 1u;
    }
  }
  return root;
}

}  // namespace eskin::hls
