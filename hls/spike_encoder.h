// spike_encoder: spikes -> address events for the host link, event-driven:
// only neurons that fired produce bytes. Bit-exact spec of the
// `spike_encoder` routine of the frame engine (rtl/ucode/dtmf_chain.fe).
//
// A spike window covers D frames (D = the taxel decimation); each spike in
// it becomes one 5-byte event {dt u16 LE, layer u8 (0 receptors, 1 the
// weighted layer), neuron u16 LE} with dt =
// t_spike - t_window (sample counters, mod 2^16) where t_window is the t of
// the window's first frame. Events are kept in frame order, layer 0 before
// layer 1, neurons in index order. At most MAX events per window: later
// spikes of that window are dropped and counted. The count is the STATUS
// packet's spikes_dropped field (u16, docs/protocol.md section 4): it
// saturates at 65535, as the microcode's SPKDROP does, and is never
// reset here (CLEAR_COUNTERS zeroes it on the top). No arithmetic beyond
// the subtraction and the count.
#pragma once

#include <cstdint>

namespace eskin::hls {

constexpr int kSpikeEventBytes = 5;
constexpr uint8_t kSpikesPacketType = 0x04;  // SPIKES (docs/protocol.md section 4)

template <int MAX>
class SpikeEncoder {
  static_assert(MAX >= 1 && MAX <= 65536 / kSpikeEventBytes, "MAX events per packet");

 public:
  // Opens a window at the first frame after the previous one closed.
  void frame(uint32_t t) {
    if (!open_) {
      open_ = true;
      t0_ = t;
      n_ = 0;
    }
    t_ = t;
  }
  // One spike of `layer` (0 or 1) neuron `neuron` in the current frame.
  void spike(uint8_t layer, uint16_t neuron) {
    if (n_ >= MAX) {
      if (dropped_ < kDroppedMax) ++dropped_;
      return;
    }
    uint8_t* e = ev_ + kSpikeEventBytes * n_++;
    const uint16_t dt = uint16_t(t_ - t0_);
    e[0] = uint8_t(dt & 0xFFu);
    e[1] = uint8_t(dt >> 8);
    e[2] = layer;
    e[3] = uint8_t(neuron & 0xFFu);
    e[4] = uint8_t(neuron >> 8);
  }
  // Closes the window: its events (n x 5 bytes) and t.
  int close(uint32_t& t_window) {
    open_ = false;
    t_window = t0_;
    return n_;
  }
  // Closes the window into its SPIKES packet (any type with type, t, len
  // and payload[] of MAX x 5 bytes): t = the window's first frame, the
  // events as payload. No events: no packet (false). rtl/spike_encoder.v
  // writes the same packet into the output FIFO.
  template <class Packet>
  bool close_packet(Packet& p) {
    uint32_t tw = 0;
    const int ne = close(tw);
    if (ne == 0) return false;
    p.type = kSpikesPacketType;
    p.t = tw;
    p.len = uint16_t(ne * kSpikeEventBytes);
    for (int b = 0; b < p.len; ++b) p.payload[b] = ev_[b];
    return true;
  }
  const uint8_t* events() const { return ev_; }
  static constexpr uint32_t kDroppedMax = 0xFFFFu;  // the STATUS field's full scale
  uint32_t dropped() const { return dropped_; }

 private:
  bool open_ = false;
  uint32_t t0_ = 0, t_ = 0;
  int n_ = 0;
  uint32_t dropped_ = 0;
  uint8_t ev_[MAX * kSpikeEventBytes] = {};
};

}  // namespace eskin::hls
