// Frames as the FPGA sends them, for the stream tests: random packets of
// every type, and the default scene's packets from hls/dtmf_chain.h (what
// rtl/dtmf_top.v sends, packet for packet: tests/rtl/dtmf_top_test.cpp),
// framed by host/link/link_encoder with one seq per packet.
#pragma once

#include <memory>
#include <random>
#include <vector>

#include "host/link/link_decoder.h"
#include "host/link/link_encoder.h"
#include "hls/dtmf_chain.h"
#include "eskin/dtmf_top_plan.h"
#include "sim/dtmf_top_spec.h"
#include "sim/scene.h"
#include "sim/world_model.h"

namespace eskin::testing {

using eskin::link::LinkEncoder;
using eskin::link::Packet;

struct Sent {
  uint8_t type, seq;
  uint32_t t;
  std::vector<uint8_t> payload;
};

// Random packets of every FPGA -> host type; returns wire bytes per frame.
inline std::vector<std::vector<uint8_t>> random_frames(size_t n, uint32_t seed,
                                                     std::vector<Sent>& sent) {
  std::mt19937 rng(seed);
  LinkEncoder enc;
  std::vector<std::vector<uint8_t>> frames;
  for (size_t i = 0; i < n; ++i) {
    const uint32_t t = uint32_t(i * 35);
    const uint8_t seq = enc.next_seq();
    std::vector<uint8_t> w;
    switch (i % 5) {
      case 0: {
        std::vector<uint16_t> m(6);
        for (auto& x : m) x = uint16_t(rng());
        w = enc.amplitudes(t, m);
        break;
      }
      case 1: {
        std::vector<uint16_t> v(9);
        for (auto& x : v) x = uint16_t(rng() % 3 ? rng() : 0);
        w = enc.taxels_dense(t, 3, 3, v);
        break;
      }
      case 2:
        w = enc.taxels_sparse(t, {{1, 2, uint16_t(rng())}, {0, 0, 0}});
        break;
      case 3:
        w = enc.spikes(t, {{uint16_t(rng() % 35), 0, uint16_t(rng() % 9)}, {34, 1, 8}});
        break;
      default: {
        eskin::link::StatusBlock s;
        s.cmd_crc_errors = uint16_t(rng()), s.cmd_frame_errors = uint16_t(rng());
        s.cmd_accepted = uint16_t(i), s.cmd_rejected = uint16_t(rng());
        s.last_reject_type = uint8_t(0x80 | rng() % 10), s.last_reject_reason = uint8_t(rng() % 6);
        s.last_reject_seq = uint8_t(rng()), s.output_mask = uint8_t(rng() % 32);
        s.dropped_frames = uint16_t(rng()), s.adc_overruns = uint16_t(rng());
        s.uart_rx_errors = uint16_t(rng()), s.frame_overruns = uint16_t(rng());
        s.spikes_dropped = uint16_t(rng()), s.cmd_overflows = uint16_t(rng());
        s.samples = t + 1;
        w = enc.status(t, s);
      }
    }
    // The raw frame is recovered from the encoder's own fields for comparison.
    Packet probe;
    eskin::link::LinkDecoder d;
    d.feed(w);
    d.pop(probe);
    sent.push_back({probe.type, seq, t, probe.payload});
    frames.push_back(std::move(w));
  }
  return frames;
}

inline std::vector<uint8_t> concat(const std::vector<std::vector<uint8_t>>& frames) {
  std::vector<uint8_t> all;
  for (const auto& f : frames) all.insert(all.end(), f.begin(), f.end());
  return all;
}

// The default scene (scenes/neuroskin2.yaml) through the 3x3 chain
// (hls/dtmf_chain.h) configured as its FPGA top is built (the plan of
// common/eskin/dtmf_top_plan.h at the top's clock: amplitudes + dense taxels +
// spikes every frame; `mask`, when given, replaces that output mask, e.g.
// 0x1F adds sparse taxels), up to sample `limit`. The world model's codes
// reach the chain left-aligned to 12 bits, as the AD7476A delivers them.
inline std::vector<uint8_t> scene_frames(std::vector<Sent>& sent, size_t limit = SIZE_MAX,
                                         int mask = -1) {
  using Sizes3 = eskin::hls::DtmfChainSizes<3, 3, 32>;
  using Chain3 = eskin::hls::DtmfChain<Sizes3>;
  const auto scene = eskin::sim::load_scene(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml");
  const auto plan = eskin::hls::make_dtmf_top_plan(
      eskin::sim::dtmf_top_spec(scene, eskin::hls::kDtmfTopClkHz));
  auto chain = std::make_unique<Chain3>(eskin::hls::chain_config<Sizes3>(plan));
  if (mask >= 0) chain->set_mask(uint8_t(mask));
  const int shift = 12 - plan.spec.adc_bits;
  std::vector<uint16_t> codes;
  for (int v : eskin::sim::WorldModel(scene).all_codes()) codes.push_back(uint16_t(v << shift));
  auto out = std::make_unique<Chain3::Packet[]>(Chain3::kMaxPackets);
  auto& pk = *reinterpret_cast<Chain3::Packet(*)[Chain3::kMaxPackets]>(out.get());
  LinkEncoder enc;
  std::vector<uint8_t> wire;
  for (size_t i = 0; i < codes.size() && i < limit; ++i) {
    const int n = chain->push(codes[i], uint32_t(i), pk);
    for (int j = 0; j < n; ++j) {
      std::vector<uint8_t> pl(pk[j].payload, pk[j].payload + pk[j].len);
      sent.push_back({pk[j].type, enc.next_seq(), pk[j].t, pl});
      const auto f = enc.frame(pk[j].type, pk[j].t, pl);
      wire.insert(wire.end(), f.begin(), f.end());
    }
  }
  return wire;
}

}  // namespace eskin::testing
