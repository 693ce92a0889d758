// The FPGA's DTMF path on the host: the same packets as hls/dtmf_chain.h
// (type, t, payload bytes, in the same order) for the same 12-bit ADC codes,
// computed fast and, for long recordings, on several threads.
//
// Composition (as hls/dtmf_chain.h): code - 2048 -> exact sliding DFT
// (host/engine/exact_sdft.h, bit-exact with hls/sdft_bank.h) -> every
// `step`-th sample: carrier_magnitude -> taxel_reconstruct ->
// izhikevich_layer (hls::izhikevich_update itself) -> packets.
//
// How a recording is split without changing one bit:
//   * the DFT sums depend only on the last N samples and their phases, so a
//     time segment starting at sample a is warmed up on samples a-N .. a-1
//     (exact_sdft.h) and segments run in parallel;
//   * magnitudes and taxels are functions of the sums of their own step;
//   * each neuron depends only on its own taxel's history, so the neuron
//     layer is split by neuron (each thread a slice, over every step);
//   * packets are assembled in one pass in step order, then neuron order
//     within a step, exactly as the chain emits them.
// The recording is processed in chunks of steps, so memory stays bounded
// (magnitudes and taxels of one chunk) however long it is.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "hls/izhikevich_layer.h"
#include "hls/taxel_reconstruct.h"
#include "host/engine/exact_sdft.h"

namespace eskin::engine {

// Runtime counterpart of hls::DtmfChainConfig plus the chain's template
// widths (DtmfChain<R, C, N, XW, CW, TW, ACC_W, MAG_W, MAG_SHIFT, TAX_W,
// MAX_SPIKES>).
struct EngineConfig {
  int rows = 3, cols = 3;
  SdftWidthsRt sdft;                 // n, xw, cw, tw, acc_w, fb
  int mag_w = 16, mag_shift = 2, tax_w = 16, max_spikes = 512;
  std::vector<uint32_t> inc;         // rows then columns, round(f / fs * 2^32)
  hls::TaxelReconstructConfig taxel; // rows/cols must equal the above
  hls::IzhikevichConfig neuron;
  int step = 1;
  uint16_t decim_amp = 35, decim_tax = 35;
  uint8_t mask = 7;                  // hls::kMaskAmplitudes | kMaskTaxels | kMaskSpikes

  int carriers() const { return rows + cols; }
  int taxels() const { return rows * cols; }
};

struct EnginePacket {
  uint8_t type = 0;
  uint32_t t = 0;
  uint32_t offset = 0, len = 0;  // payload bytes in PacketStream::bytes
};

struct PacketStream {
  std::vector<EnginePacket> packets;
  std::vector<uint8_t> bytes;
  uint32_t spikes_dropped = 0;  // spike events beyond max_spikes in a window
  const uint8_t* payload(const EnginePacket& p) const { return bytes.data() + p.offset; }
};

struct RunOptions {
  int threads = 1;
  size_t chunk_steps = 1 << 18;  // steps per chunk (memory: chunk x (K + T) x 2 bytes)
};

class DtmfEngine {
 public:
  // Throws std::invalid_argument naming the field when the configuration is
  // one hls::DtmfChain would reject (or cannot be instantiated with).
  explicit DtmfEngine(EngineConfig cfg);

  // Decodes codes[0..n) (12-bit ADC codes; sample counter t = index).
  PacketStream run(const uint16_t* codes, size_t n, const RunOptions& opt = {}) const;

  const EngineConfig& config() const { return cfg_; }

  // One taxel value from its row and column magnitudes (taxel_reconstruct).
  uint32_t taxel(uint32_t mi, uint32_t mj) const;

 private:
  struct Chunk;
  void stage_dft(const uint16_t* codes, size_t n_total, uint64_t s0, uint64_t s1, Chunk& c,
                 uint64_t chunk_s0) const;
  void taxel_row(const uint16_t* mags, uint16_t* out) const;

  EngineConfig cfg_;
  MagnitudeWidths mw_;
  hls::TaxelReconstruct<1, 1, 16, 16> tax_kernel_;  // Pressure mode (table search)
};

}  // namespace eskin::engine
