// dtmf_chain: the whole DTMF FPGA path as composed HLS kernels, down to the
// host-link packet payloads. Bit-exact spec of rtl/dtmf_top.v: for the same
// ADC samples (and the same commands at the same samples) the top sends
// exactly these packets (type, t, payload), in this order per type.
//
// Per ADC sample (12-bit code from the AD7476A, sample counter t):
//   x = code - 2048 (signed, XW = 12 bits)
//   sdft_bank: K carriers (+ a DC channel, inc 0, when demixing)
// A frame is taken once the window is full (N samples since reset or since
// the last carrier reload: partly filled windows never make frames) and then
// every `step` samples. Per frame (hardware: the frame engine's microcode):
//   carrier_demix   (if demix) joint LS of the K carriers + DC: no cross-talk
//   carrier_magnitude  K magnitudes (u16, window-sum units of 12-bit codes
//                      >> mag_shift)
//   taxel_reconstruct  one root per line, g = root_i root_j recip (UQ1.15)
//   ghost_filter    (if ghost) active sites; taxel = g at sites, else 0
//   izhikevich_layer  layer 0: one RA receptor per taxel (input g, level or
//                     rectified change), addressed by taxel index
//   synapse_weights   3x3 kernel over layer 0's spikes -> layer 1 input
//   izhikevich_layer  layer 1: one neuron per taxel
//   spike_encoder     events of both layers per spike window
// (neurons, synapses and spikes only when cfg.neurons.)
//
// Packets (layouts: docs/protocol.md), frames counted from reset:
//   0x01 AMPLITUDES     frame f with f % decim_amp == 0, mask bit 0: K x u16
//   0x02 TAXELS_DENSE   f % decim_tax == 0, mask bit 1: rows, cols, T x u16 g
//   0x03 TAXELS_SPARSE  f % decim_tax == 0, mask bit 4: {row, col, g u16}
//                       for every taxel with g >= max(1, sparse_min)
//                       (both: taxel_packetizer)
//   0x04 SPIKES         when a spike window (the decim_tax frames ending at
//                       f % decim_tax == decim_tax - 1) closes with events,
//                       mask bit 2: t = the window's first frame
// All carry t = the ADC sample counter of the frame's newest sample. The
// RTL also sends STATUS (0x05) packets; they are not part of this spec.
// A decimation change restarts that stream's frame count at 0.
// Equality with the RTL assumes the link keeps up (dropped_frames 0) and
// no ADC sample or frame is lost (adc_overruns, frame_overruns 0); the
// system test checks all three.
//
// Widths: everything fixed width; no heap, no float.
#pragma once

#include <cstdint>

#include "hls/carrier_demix.h"
#include "hls/carrier_magnitude.h"
#include "hls/ghost_filter.h"
#include "hls/izhikevich_layer.h"
#include "hls/sdft_bank.h"
#include "hls/spike_encoder.h"
#include "hls/synapse_weights.h"
#include "hls/taxel_packetizer.h"
#include "hls/taxel_reconstruct.h"

namespace eskin::hls {

// The packet types (DtmfPacketType) are hls/taxel_packetizer.h's.

// Output enable mask bits (SET_OUTPUT_MASK writes them).
enum DtmfMaskBit : uint8_t {
  kMaskAmplitudes = 1,
  kMaskTaxels = 2,
  kMaskSpikes = 4,
  kMaskStatus = 8,  // periodic status (RTL only)
  kMaskSparse = 16,
};

constexpr int dtmf_clog2(int v) {
  int b = 0;
  while ((1 << b) < v) ++b;
  return b;
}

// Compile-time sizes of a chain: skin rows x cols, window N, ghost history
// depth, spike events per packet.
template <int R_, int C_, int N_, int L_MAX_ = 4, int MAX_SPIKES_ = 256>
struct DtmfChainSizes {
  static constexpr int R = R_, C = C_, N = N_, K = R_ + C_, T = R_ * C_;
  static constexpr int L_MAX = L_MAX_, MAX_SPIKES = MAX_SPIKES_;
  static constexpr int XW = 12;                        // code - 2048
  static constexpr int ACC_W = XW + 1 + dtmf_clog2(N);  // exact window sums
  static constexpr int DEMIX_W = 24;                   // demixed sums
  static constexpr int MAG_SHIFT = dtmf_clog2(N) > 5 ? dtmf_clog2(N) - 5 : 0;
};

template <class S>
struct DtmfChainConfig {
  static constexpr int K = S::K;
  SdftBankConfig<K + 1> sdft;    // K carriers (+ DC last when demixing)
  bool demix = true;
  CarrierDemixConfig<K> demix_cfg;
  TaxelReconstructConfig taxel;
  bool ghost = true;
  GhostFilterConfig ghost_cfg;
  bool neurons = true;
  IzhikevichConfig neuron[2];    // layer 0 receptors, layer 1 weighted
  SynapseWeightsConfig synapse;
  int step = 35;                 // samples per frame, >= 1
  uint16_t decim_amp = 1;        // frames per amplitude packet, >= 1
  uint16_t decim_tax = 1;        // frames per taxel packet and spike window
  uint16_t sparse_min = 0;       // TAXELS_SPARSE: g >= max(1, sparse_min)
  uint8_t mask = kMaskAmplitudes | kMaskTaxels | kMaskSpikes;
};

template <class S>
class DtmfChain {
 public:
  static constexpr int R = S::R, C = S::C, N = S::N, K = S::K, T = S::T;
  static constexpr int kMaxPayload = (5 * S::MAX_SPIKES > 4 * T + 2)
                                         ? 5 * S::MAX_SPIKES
                                         : (4 * T > 2 * K ? 4 * T + 2 : 2 * K + 2);
  static constexpr int kMaxPackets = 4;
  using Config = DtmfChainConfig<S>;
  using Bank = SdftBank<K + 1, N, S::XW, 16, 10, S::ACC_W>;
  using Demix = CarrierDemix<K, N, S::ACC_W, S::DEMIX_W>;
  using Magnitude = CarrierMagnitude<S::DEMIX_W, 16, S::MAG_SHIFT>;
  using Taxels = TaxelPacketizer<R, C>;
  static_assert(kSpikesPacketType == kDtmfSpikes, "one SPIKES type");

  struct Packet {
    uint8_t type = 0;
    uint32_t t = 0;
    uint16_t len = 0;
    uint8_t payload[kMaxPayload] = {};
  };

  explicit DtmfChain(const Config& cfg)
      : cfg_(cfg), l0_(cfg.neuron[0]), l1_(cfg.neuron[1]) {
    ok_ = cfg.step >= 1 && cfg.decim_amp >= 1 && cfg.decim_tax >= 1 &&
          taxel_.configure(cfg.taxel) && cfg.taxel.rows == R && cfg.taxel.cols == C &&
          ghost_.configure(cfg.ghost_cfg) && synapse_.configure(cfg.synapse) &&
          cfg.sdft.carriers == (cfg.demix ? K + 1 : K) && bank_.configure(cfg.sdft) &&
          (!cfg.demix || demix_.configure(cfg.demix_cfg));
  }
  bool ok() const { return ok_; }  // false: a configuration field was rejected
  uint32_t frames() const { return frames_; }  // frames processed so far
  uint32_t spikes_dropped() const { return enc_.dropped(); }

  // ---- commands (applied before the next sample) ----
  // New carrier table (and, when demixing, new demix tables): the window is
  // cleared and refills before the next frame.
  bool set_carriers(const SdftBankConfig<K + 1>& s, const CarrierDemixConfig<K>& d) {
    if (s.carriers != cfg_.sdft.carriers || !bank_.configure(s)) return false;
    if (cfg_.demix && !demix_.configure(d)) return false;
    cfg_.sdft = s;
    cfg_.demix_cfg = d;
    filled_ = 0;
    return true;
  }
  void set_ghost_thresholds(uint16_t onset, uint16_t pair_tol, uint16_t release) {
    ghost_.set_thresholds(onset, pair_tol, release);
  }
  void set_sparse_min(uint16_t v) { cfg_.sparse_min = v; }
  void set_neuron(int layer, const IzhikevichConfig& c) {
    (layer == 0 ? l0_ : l1_).set_config(c);
  }
  void set_weight(int id, int16_t w) { synapse_.set_weight(id, w); }
  bool set_demix_coef(int index, int16_t value) { return demix_.set_coef(index, value); }
  const CarrierDemixConfig<K>& demix_config() const { return demix_.config(); }
  const SdftBankConfig<K + 1>& chain_sdft_config() const { return cfg_.sdft; }
  const GhostFilterConfig& ghost_config() const { return ghost_.config(); }
  const IzhikevichConfig& neuron_config(int layer) const {
    return layer == 0 ? l0_.config() : l1_.config();
  }
  void set_mask(uint8_t m) { cfg_.mask = m; }
  void set_decimation(int stream, uint16_t d) {  // 0 amplitudes, 1 taxels/spikes
    if (stream == 0) cfg_.decim_amp = d, amp_cnt_ = 0;
    if (stream == 1) cfg_.decim_tax = d, tax_cnt_ = 0;
  }

  // One 12-bit ADC code with its sample counter; returns the packets made.
  int push(uint16_t code, uint32_t t, Packet (&out)[kMaxPackets]) {
    if (!ok_) return 0;
    typename Bank::Token tok[K + 1];
    bank_.push(int32_t(code & 0xFFFu) - 2048, tok);
    if (filled_ < N) {
      if (++filled_ < N) return 0;
      phase_ = 0;
    } else {
      phase_ = phase_ + 1 == cfg_.step ? 0 : phase_ + 1;
      if (phase_ != 0) return 0;
    }
    return frame(tok, t, out);
  }

  // Of the last frame (for tests and scoring).
  uint16_t magnitude(int k) const { return mag_[k]; }
  uint16_t taxel(int i) const { return g_[i]; }
  bool spiked(int layer, int i) const { return (layer == 0 ? s0_ : s1_)[i]; }
  const GhostFilter<R, C, S::L_MAX>& ghost() const { return ghost_; }

 private:
  int frame(const typename Bank::Token* tok, uint32_t t, Packet (&out)[kMaxPackets]) {
    ++frames_;
    // Amplitudes.
    typename Demix::Token dm[K];
    if (cfg_.demix)
      for (int k = 0; k <= K; ++k)
        demix_.push(typename Demix::Token{uint8_t(k), tok[k].re, tok[k].im, k == K}, dm);
    for (int k = 0; k < K; ++k) {
      const int32_t re = cfg_.demix ? dm[k].re : tok[k].re;
      const int32_t im = cfg_.demix ? dm[k].im : tok[k].im;
      mag_[k] = uint16_t(Magnitude::magnitude(re, im));
    }
    // Taxels.
    taxel_.lines(mag_);
    if (cfg_.ghost) {
      ghost_.frame(mag_);
      ghost_.release([this](int i, int j) { return taxel_.value(i, j); });
    }
    for (int i = 0; i < R; ++i)
      for (int j = 0; j < C; ++j)
        g_[i * C + j] = (!cfg_.ghost || ghost_.site(i, j)) ? taxel_.value(i, j) : 0;
    // Neurons and spikes.
    const bool record = cfg_.neurons && (cfg_.mask & kMaskSpikes);
    if (record) enc_.frame(t);
    if (cfg_.neurons) {
      for (int i = 0; i < T; ++i) s0_[i] = l0_.update(i, g_[i]);
      for (int i = 0; i < T; ++i) s1_[i] = l1_.update(i, synapse_.input(s0_, i / C, i % C));
      if (record) {
        for (int i = 0; i < T; ++i)
          if (s0_[i]) enc_.spike(0, uint16_t(i));
        for (int i = 0; i < T; ++i)
          if (s1_[i]) enc_.spike(1, uint16_t(i));
      }
    }
    // Packets.
    int n = 0;
    const bool amp_sel = amp_cnt_ == 0, tax_sel = tax_cnt_ == 0;
    const bool win_end = tax_cnt_ + 1u >= cfg_.decim_tax;
    amp_cnt_ = amp_cnt_ + 1u >= cfg_.decim_amp ? 0 : amp_cnt_ + 1u;
    tax_cnt_ = win_end ? 0 : tax_cnt_ + 1u;
    if (amp_sel && (cfg_.mask & kMaskAmplitudes)) {
      Packet& p = begin(out[n++], kDtmfAmplitudes, t);
      for (int k = 0; k < K; ++k) put16(p, mag_[k]);
    }
    if (tax_sel)
      n += Taxels::frame(g_, t, cfg_.mask & kMaskTaxels, cfg_.mask & kMaskSparse, cfg_.sparse_min,
                         out + n);
    if (win_end && record && enc_.close_packet(out[n])) ++n;
    return n;
  }
  static Packet& begin(Packet& p, uint8_t type, uint32_t t) {
    p.type = type;
    p.t = t;
    p.len = 0;
    return p;
  }
  static void put16(Packet& p, uint16_t v) {
    p.payload[p.len++] = uint8_t(v & 0xFFu);
    p.payload[p.len++] = uint8_t(v >> 8);
  }

  Config cfg_;
  bool ok_ = false;
  Bank bank_;
  Demix demix_;
  TaxelReconstruct<R, C> taxel_;
  GhostFilter<R, C, S::L_MAX> ghost_;
  IzhikevichLayer<T> l0_, l1_;
  SynapseWeights<R, C> synapse_;
  SpikeEncoder<S::MAX_SPIKES> enc_;
  uint32_t frames_ = 0;
  int filled_ = 0;  // samples in the window since the last clear (<= N)
  int phase_ = 0;   // sample within the step once the window is full
  uint32_t amp_cnt_ = 0, tax_cnt_ = 0;
  uint16_t mag_[K] = {};
  uint16_t g_[T] = {};
  bool s0_[T] = {}, s1_[T] = {};
};

}  // namespace eskin::hls
