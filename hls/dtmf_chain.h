// dtmf_chain: the whole DTMF FPGA path as composed HLS kernels, down to the
// host-link packet payloads. Bit-exact spec of rtl/dtmf_top.v (with
// rtl/frame_packetizer.v): for the same ADC samples the top sends exactly
// these packets (type, t, payload), in this order per type.
//
// Per ADC sample (12-bit unsigned code from the AD7476A, sample counter t):
//   x = code - 2048 (signed, XW = 12 bits)                [12-bit codes]
//   SdftBank<K, N, XW, CW, TW, ACC_W>: K tokens {k, re, im}
//   every cfg.step-th sample (a "step"; the first sample is one):
//     CarrierMagnitude<ACC_W, MAG_W, MAG_SHIFT>: K magnitudes (u16)
//     TaxelReconstruct<R, C, MAG_W, TAX_W>: the frame's taxels, row-major
//     IzhikevichLayer<R*C>: one update per taxel, input x = taxel value
// A 10-bit scene code c10 enters as c10 << 2 (the AD7476A's 12 bits, left
// aligned); with MAG_SHIFT = 2 at N = 32 the magnitudes are back in 10-bit
// code units (window sum, gain G = 1 - 2^-(CW-1)).
//
// Packets (layouts: host/link/link_decoder.h), steps counted from 0:
//   amplitudes (0x01), step s with s % decim_amp == 0 and mask bit 0:
//     t = the step's sample counter, payload K x mag u16 LE (k order).
//   taxels dense (0x02), steps with s % decim_tax == 0, mask bit 1: rows u8,
//     cols u8, then the taxel values u16 LE row-major (every taxel: activity
//     threshold 0).
//   spikes (0x04), mask bit 2: window w covers steps w*D .. w*D + D - 1
//     (D = decim_tax); when it closes (after its last step) and holds at least
//     one spike: t = the window's first step's t, payload n x {dt u16 =
//     t_spike - t, layer u8 = 0, neuron u16}, in step then neuron order.
//   The RTL also sends status packets (0x05) on request / with mask bit 3;
//   their counters are not part of this spec.
// Carrier table change (SET_CARRIER_INC): set_carriers() before the first
// sample the new table applies to (sdft_bank state is cleared, as in RTL).
// Equality with the RTL assumes the link keeps up (nothing dropped: the
// status packet's dropped_frames stays 0) and that no ADC sample is lost
// (adc_overruns 0); the system test checks both.
//
// Widths: everything fixed width; no heap, no float. Interface: configure
// once (constructor), then push() one sample at a time; it returns the
// number of packets completed by this sample (0..3) in `out`.
#pragma once

#include <cstdint>

#include "hls/carrier_magnitude.h"
#include "hls/izhikevich_layer.h"
#include "hls/sdft_bank.h"
#include "hls/taxel_reconstruct.h"

namespace eskin::hls {

enum DtmfPacketType : uint8_t {
  kDtmfAmplitudes = 0x01,
  kDtmfTaxelsDense = 0x02,
  kDtmfSpikes = 0x04,
  kDtmfStatus = 0x05,
};

// Output enable mask bits (the command SetOutputMask writes them).
enum DtmfMaskBit : uint8_t {
  kMaskAmplitudes = 1,
  kMaskTaxels = 2,
  kMaskSpikes = 4,
  kMaskStatus = 8,  // periodic status (RTL only)
};

template <int K>
struct DtmfChainConfig {
  SdftBankConfig<K> sdft;        // carriers = K, phase increments
  TaxelReconstructConfig taxel;  // rows, cols, mode, recip ...
  IzhikevichConfig neuron;
  int step = 1;                  // samples per processing step, >= 1
  uint16_t decim_amp = 35;       // amplitude packets every decim_amp steps, >= 1
  uint16_t decim_tax = 35;       // taxel packets and spike windows, >= 1
  uint8_t mask = kMaskAmplitudes | kMaskTaxels | kMaskSpikes;
};

// Template defaults = dtmf_top's parameter defaults (ACC_W = 18 fits N <= 32;
// in general ACC_W >= XW + 1 + ceil(log2 N), checked by SdftBank).
template <int R, int C, int N, int XW = 12, int CW = 16, int TW = 10, int ACC_W = 18,
          int MAG_W = 16, int MAG_SHIFT = 2, int TAX_W = 16, int MAX_SPIKES = 512>
class DtmfChain {
 public:
  static constexpr int K = R + C;
  static constexpr int T = R * C;
  static_assert(MAG_W <= 16 && TAX_W <= 16, "packets carry u16 magnitudes and taxels");
  static constexpr int kMaxPayload =
      (5 * MAX_SPIKES > 2 + 2 * T) ? 5 * MAX_SPIKES : 2 + 2 * T;

  using Config = DtmfChainConfig<K>;
  struct Packet {
    uint8_t type = 0;
    uint32_t t = 0;
    uint16_t len = 0;
    uint8_t payload[kMaxPayload] = {};
  };

  explicit DtmfChain(const Config& cfg) : cfg_(cfg), neurons_(cfg.neuron) {
    ok_ = sdft_.configure(cfg.sdft) && taxels_.configure(cfg.taxel) && cfg.step >= 1 &&
          cfg.decim_amp >= 1 && cfg.decim_tax >= 1 && cfg.taxel.rows == R &&
          cfg.taxel.cols == C;
  }
  // New carrier table from the next sample on; false (unchanged) if invalid.
  bool set_carriers(const SdftBankConfig<K>& c) {
    if (c.carriers != K || !sdft_.configure(c)) return false;
    cfg_.sdft = c;
    return true;
  }
  // False when a configuration field was rejected (then push() does nothing).
  bool ok() const { return ok_; }
  uint32_t spikes_dropped() const { return spikes_dropped_; }

  // One 12-bit ADC code with its sample counter.
  int push(uint16_t code, uint32_t t, Packet (&out)[3]) {
    if (!ok_) return 0;
    SdftBankToken tok[K];
    sdft_.push(int32_t(code & 0xFFFu) - 2048, tok);
    const bool stepping = phase_ == 0;
    phase_ = phase_ + 1 == cfg_.step ? 0 : phase_ + 1;
    if (!stepping) return 0;

    int n = 0;
    const bool amp_sel = amp_cnt_ == 0;
    const bool frame_sel = frame_cnt_ == 0;
    amp_cnt_ = amp_cnt_ + 1u >= cfg_.decim_amp ? 0 : amp_cnt_ + 1u;
    uint16_t mags[K];
    for (int k = 0; k < K; ++k) {
      CarrierMagnitudeIn in{tok[k].k, tok[k].re, tok[k].im, tok[k].last};
      CarrierMagnitudeOut o;
      mag_.push(in, o);
      mags[k] = uint16_t(o.mag);
      taxels_.push(MagToken{uint8_t(k), uint16_t(o.mag)});
    }
    if (amp_sel && (cfg_.mask & kMaskAmplitudes)) {
      Packet& p = out[n++];
      begin(p, kDtmfAmplitudes, t);
      for (int k = 0; k < K; ++k) put16(p, mags[k]);
    }
    Packet* tax = nullptr;
    if (frame_sel && (cfg_.mask & kMaskTaxels)) {
      tax = &out[n++];
      begin(*tax, kDtmfTaxelsDense, t);
      tax->payload[tax->len++] = uint8_t(R);
      tax->payload[tax->len++] = uint8_t(C);
    }
    if (!win_open_) {
      win_open_ = true;
      win_t_ = t;
    }
    TaxelToken tx;
    while (taxels_.pop(tx)) {
      if (tax) put16(*tax, uint16_t(tx.value));
      IzhikevichOut o;
      neurons_.push(IzhikevichIn{int32_t(tx.value), t}, o);
      if (o.spike && (cfg_.mask & kMaskSpikes)) {
        if (n_spikes_ < MAX_SPIKES) {
          spikes_[n_spikes_++] = Spike{uint16_t(t - win_t_), o.neuron};
        } else {
          ++spikes_dropped_;
        }
      }
    }
    if (frame_cnt_ + 1u >= cfg_.decim_tax) {  // the window's last step
      if (n_spikes_ > 0) {
        Packet& p = out[n++];
        begin(p, kDtmfSpikes, win_t_);
        for (int i = 0; i < n_spikes_; ++i) {
          put16(p, spikes_[i].dt);
          p.payload[p.len++] = 0;  // layer 0: receptors
          put16(p, spikes_[i].neuron);
        }
      }
      n_spikes_ = 0;
      win_open_ = false;
      frame_cnt_ = 0;
    } else {
      ++frame_cnt_;
    }
    return n;
  }

 private:
  struct Spike { uint16_t dt, neuron; };
  static void begin(Packet& p, uint8_t type, uint32_t t) {
    p.type = type;
    p.t = t;
    p.len = 0;
  }
  static void put16(Packet& p, uint16_t v) {
    p.payload[p.len++] = uint8_t(v & 0xFFu);
    p.payload[p.len++] = uint8_t(v >> 8);
  }

  Config cfg_;
  bool ok_ = false;
  SdftBank<K, N, XW, CW, TW, ACC_W> sdft_;
  CarrierMagnitude<ACC_W, MAG_W, MAG_SHIFT> mag_;
  TaxelReconstruct<R, C, MAG_W, TAX_W> taxels_;
  IzhikevichLayer<T> neurons_;
  int phase_ = 0;             // sample within the step
  uint32_t amp_cnt_ = 0;      // step within the amplitude decimation
  uint32_t frame_cnt_ = 0;    // step within the taxel decimation / spike window
  bool win_open_ = false;
  uint32_t win_t_ = 0;
  Spike spikes_[MAX_SPIKES] = {};
  int n_spikes_ = 0;
  uint32_t spikes_dropped_ = 0;
};

}  // namespace eskin::hls
