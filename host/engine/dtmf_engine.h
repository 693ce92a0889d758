// The FPGA's DTMF path on the host: the same packets as hls/dtmf_chain.h
// (type, t, payload bytes, in the same order) for the same 12-bit ADC codes,
// computed fast and, for long recordings, on several threads.
//
// Composition (as hls/dtmf_chain.h, kernels called natively where their
// sizes are run-time): code - 2048 -> exact sliding DFT of K carriers (+ the
// DC channel when demixing; host/engine/exact_sdft.h, bit-exact with
// hls/sdft_bank.h); a frame once the window is full (sample N-1) and every
// `step` samples after -> hls::CarrierDemix (when demixing) -> magnitudes
// (hls/carrier_magnitude.h's rounding) -> line roots and taxel values
// (hls/taxel_reconstruct.h) -> hls::GhostFilter (when on) -> izhikevich
// layer 0 (hls::izhikevich_update) -> hls::SynapseWeights -> layer 1 ->
// spike windows -> AMPLITUDES, TAXELS_DENSE, TAXELS_SPARSE, SPIKES.
//
// How a recording is split without changing one bit:
//   * the DFT sums depend only on the last N samples and their phases, so a
//     run of frames starting at frame f is warmed up on its own window
//     (exact_sdft.h); the demixer's rotation phase of frame f is
//     phase0 + f inc, so each run starts its own copy there; magnitudes,
//     roots and (no ghost filter) taxel values are per frame. Runs of
//     frames go in parallel;
//   * the ghost filter carries state from frame to frame: one pass in frame
//     order (cheap: K rises and the active sites per frame);
//   * a layer-0 neuron depends only on its own taxel's history, a layer-1
//     neuron on its own history and layer 0's spikes of the same frame, so
//     each layer is split by neuron (each thread a slice, over every frame),
//     layer 0 before layer 1;
//   * packets are assembled in one pass in frame order, layer 0 then layer
//     1, neuron order within a frame, exactly as the chain emits them.
// The recording goes through in chunks of frames, so memory stays bounded
// however long it is.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "hls/carrier_demix_config.h"
#include "hls/ghost_filter.h"
#include "hls/izhikevich_layer.h"
#include "hls/synapse_weights.h"
#include "hls/taxel_reconstruct.h"
#include "host/engine/exact_sdft.h"

namespace eskin::engine {

// Runtime counterpart of hls::DtmfChainConfig with the chain's sizes
// (DtmfChainSizes<R, C, N>: XW 12, ACC_W, DEMIX_W 24, MAG_SHIFT). Built
// from the top's plan by engine_config() (host/engine/engine_setup.h).
struct EngineConfig {
  int rows = 3, cols = 3;
  SdftWidthsRt sdft;                  // n, xw 12, cw 16, tw 10, acc_w, fb 0
  int mag_shift = 0;                  // magnitudes: sums >> mag_shift (u16)
  std::vector<uint32_t> inc;          // DFT channels: K carriers (+ DC, inc 0, when demixing)
  bool demix = false;
  hls::CarrierDemixTables demix_tables;  // when demixing (common/eskin/dtmf_top_plan.h's plan)
  hls::TaxelReconstructConfig taxel;
  bool ghost = true;
  hls::GhostFilterConfig ghost_cfg;
  bool neurons = true;
  hls::IzhikevichConfig neuron[2];    // layer 0 receptors, layer 1 weighted
  hls::SynapseWeightsConfig synapse;
  int step = 35;                      // samples per frame
  uint16_t decim_amp = 1, decim_tax = 1, sparse_min = 0;
  uint8_t mask = 7;                   // hls::DtmfMaskBit
  int max_spikes = 256;               // events per spike packet

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
  uint32_t spikes_dropped = 0;  // spike events beyond max_spikes in a window (saturates at 65535)
  uint64_t frames = 0;
  const uint8_t* payload(const EnginePacket& p) const { return bytes.data() + p.offset; }
};

struct RunOptions {
  int threads = 1;
  size_t chunk_frames = 0;  // frames per chunk (0: about 64 MB of buffers)
  // Neuron updates (frames x neurons of a chunk) per thread at least: a
  // smaller layer runs on fewer threads (0: 4096 updates, of the order of
  // what starting a thread costs).
  uint64_t neuron_work = 0;
};

class DtmfEngine {
 public:
  // The largest ghost-filter lookback (frames) the engine holds.
  static constexpr int kMaxLookback = 4096;

  // Throws std::invalid_argument naming the field when the configuration is
  // one hls::DtmfChain would reject (or the engine cannot hold).
  explicit DtmfEngine(EngineConfig cfg);

  // Decodes codes[0..n) (12-bit ADC codes; sample counter t = index).
  PacketStream run(const uint16_t* codes, size_t n, const RunOptions& opt = {}) const;

  const EngineConfig& config() const { return cfg_; }

 private:
  struct Chunk;
  struct State;
  void stage_frames(const uint16_t* codes, uint64_t f0, uint64_t f1, Chunk& c,
                    uint64_t chunk_f0) const;
  void stage_ghost(State& st, Chunk& c, size_t frames) const;
  void stage_neurons(State& st, Chunk& c, size_t frames, int threads, uint64_t work) const;
  void stage_packets(State& st, const Chunk& c, uint64_t chunk_f0, size_t frames,
                     PacketStream& ps) const;

  EngineConfig cfg_;
  MagnitudeWidths mw_;
};

}  // namespace eskin::engine
