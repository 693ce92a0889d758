// Host-side, not synthesised: the one place that derives the configuration
// of the DTMF FPGA top (rtl/dtmf_top.v) and of its bit-exact spec
// (hls/dtmf_chain.h) from a skin's numbers. Every build of the top — tests,
// the virtual board, `eskin bitstream`, benchmarks — takes its Verilog
// parameters from dtmf_top_params(), and every HLS chain its configuration
// from chain_config(), so the two can never disagree.
//
// The input is plain numbers (DtmfTopSpec): hls/ includes nothing of the
// rest of the tree; sim/dtmf_top_spec.h fills the spec from a scene.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "hls/carrier_demix_config.h"
#include "hls/dtmf_chain.h"
#include "hls/izhikevich_layer_config.h"
#include "hls/sdft_bank_config.h"

namespace eskin::hls {

// The FPGA clock of the DTMF top: the iCEBreaker's 12 MHz oscillator x 3/2
// by the UP5K's PLL (VCO 576 MHz / 32). The top's place-and-route Fmax is
// about 20 MHz (the frame engine's operand -> 48-bit adder path); 18 MHz
// is the fastest PLL clock below it that divides into the 3 Mbaud link (6
// clocks per bit). The default scene's longest frame and its share of
// the clocks between frames: docs/figures.csv (docs/fpga.md).
constexpr long kDtmfTopClkHz = 18000000;

// The datapath that does a frame's work after the DFT: the frame engine's
// microprogram (rtl/dtmf_top.v), or the streaming datapath for large FPGAs
// (rtl/dtmf_chain.v in dtmf_top STREAM = 1, the engine its control plane;
// host/fpga/flow.h choose_core_clock picks it). It sets how much of a
// frame the proven worst case may take (dtmf_frame_bound_limit_percent).
enum class DtmfDatapath { FrameEngine, Streaming };

// The most of a frame's clocks the static worst-case bound of a frame and
// a command (ucode/dtmf_frame_bound.h) may take: 90 % on the frame engine,
// whose bound covers every path of its microprogram; 70 % on a streaming
// datapath, whose fixed latencies leave less to prove and more to what the
// bound does not model (its blocks' back-pressure).
inline int dtmf_frame_bound_limit_percent(DtmfDatapath d) {
  return d == DtmfDatapath::Streaming ? 70 : 90;
}

// What a skin asks of the FPGA top.
struct DtmfTopSpec {
  DtmfDatapath datapath = DtmfDatapath::FrameEngine;
  int rows = 3, cols = 3;
  std::vector<double> carrier_hz;  // rows first, then columns
  double sample_hz = 35000.0;
  int adc_bits = 10;               // the scene's ADC; codes reach the top left-aligned to 12
  double full_carrier_lsb = 155.15;  // one full carrier at the ADC, in adc_bits LSB
  int window = 32;                 // N
  bool demix = true;               // carriers off bin centres: joint LS demixing
  bool ghost = true;               // multi-touch ghost correction
  double ghost_onset_g = 0.05, ghost_release_g = 0.05, ghost_pair_tol_g = 0.02;
  double frame_ms = 1.0;           // one frame (and neuron step) per frame_ms
  bool spikes = true;              // the scene wants spikes: neurons on
  std::string neuron_preset = "RA";
  bool neuron_change = false;      // receptor input: rectified change (else level)
  double neuron_input_scale = 10.0;  // taxel g (0..1) -> neuron input units
  std::string layer2_preset = "RS";
  double layer2_centre = 20.0, layer2_surround = -4.0;
  long clk_hz = kDtmfTopClkHz;     // FPGA clock
  // The ADC's own clock (rtl/dtmf_top.v ADC_CLK_HZ; its samples cross into
  // clk_hz's domain in rtl/stream_cdc.v), 0: the ADC runs on clk_hz. The
  // board flow sets it when the AD7476A's SCLK would pin the core clock to
  // a band the engine does not fit (1 MS/s: 37.3-40 MHz).
  long adc_clk_hz = 0;
  long baud = 3000000;
  // The frame engine's barrel shifter (rtl/frame_engine.v FAST_SHIFT): the
  // same packets in fewer clocks, for ~1000 logic cells more; the flow turns it
  // on for boards with room (host/fpga/board.h).
  bool engine_fast_shift = false;
  // Parallel DFT lanes (rtl/sdft_lanes.v), 1..min(64, KS): the board flow
  // picks them (host/fpga/flow.cpp choose_core_clock); 1 is sdft_bank.
  int sdft_lanes = 1;
  // Samples queued in front of the lanes (rtl/sdft_front.v's DEPTH: 0, or a
  // power of two up to 64): the ADC's samples wait there while a frame's
  // sample sends its KS tokens, one a clock. 0 is the ADC's one register
  // alone, rtl/dtmf_top.v's wiring until it instantiates sdft_front.
  int sdft_fifo = 0;
  // The hardware neuron unit (rtl/izhikevich_layer.v, NEURON_UNIT): the
  // engine hands it each neuron update (13 clocks, overlapped: 14 engine
  // clocks a neuron with level input, the spike test included) instead of
  // running the izhikevich_layer routine (about 120 clocks with the barrel
  // shifter, 210 without); the same packets, where the board flow puts it
  // (host/fpga/board.h).
  bool neuron_unit = false;
  // With neuron_unit: 0, the engine keeps the neurons' state; 2..8, that
  // many units keep it themselves (rtl/izhikevich_lanes.v, NEURON_LANES):
  // the engine sends each neuron's input (3 clocks a neuron instead of 14)
  // and reads the spike flags and events back. For boards with room (about
  // 1300 LUT4 and a multiplier a lane, the state in block RAM).
  int neuron_lanes = 0;
};

// The periodic STATUS packet's decimation at reset (docs/protocol.md §6):
// every this many frames, counted from frame 0.
constexpr int kDtmfStatusDecimReset = 1000;

// A Verilog parameter override: value in Verilog syntax (e.g. "16'd35").
struct VerilogParam {
  std::string name, value;
};


// Derived plan: sizes, widths, step and every constant of the chain, for
// any skin size (host side, vectors); chain_config<S>() turns it into the
// fixed-size configuration of hls/dtmf_chain.h, dtmf_engine_image() (in
// ucode/dtmf_engine_image.h) into the frame engine's constants.
struct DtmfTopPlan {
  DtmfTopSpec spec;
  int R = 0, C = 0, K = 0, T = 0, N = 0;
  int ks = 0;            // DFT channels: K (+ DC when demixing)
  int acc_w = 0;         // DFT window-sum width: 12 + 1 + ceil(log2 N)
  int mag_shift = 0;     // magnitude units: window sums >> mag_shift
  int step = 1;          // samples per frame
  int lookback = 1;      // ghost filter history, frames
  int max_spikes = 256;  // spike events per packet
  double full_mag = 0;   // one full carrier in magnitude units
  std::vector<uint32_t> inc;  // ks phase increments (DC last: 0)
  CarrierDemixTables demix;   // when spec.demix
  TaxelReconstructConfig taxel;
  GhostFilterConfig ghost;
  IzhikevichConfig neuron[2];  // layer 0 receptors, layer 1 weighted
  SynapseWeightsConfig synapse;
  uint16_t decim_amp = 1, decim_tax = 1, sparse_min = 0;
  uint8_t mask = 0;
  // Bytes of rtl/dtmf_top.v's output FIFO (OUT_DEPTH): a power of two, at
  // least 512 (one EBR pair), holding the plan's largest packet whole.
  int out_depth = 512;
};

// The longest packet a plan's top can queue, header (type, t, len: 7 bytes)
// included, from the payloads of docs/protocol.md section 4: AMPLITUDES 2K;
// TAXELS_DENSE 2 + 2T; TAXELS_SPARSE 4T (every taxel lit); SPIKES 5 bytes
// per event, at most every neuron of both layers once per frame of the
// spike window (decim_tax frames), capped by max_spikes; STATUS 28.
// frame_engine writes a packet only when the FIFO has room for all of it
// (pkt_begin in rtl/ucode/dtmf_chain.fe) and counts the rest as dropped,
// so a packet longer than the FIFO could never be sent.
inline int longest_packet_bytes(const DtmfTopPlan& p) {
  const long spikes = std::min<long>(p.max_spikes, 2L * p.T * p.decim_tax);
  return 7 + int(std::max({2L * p.K, 2L + 2L * p.T, 4L * p.T, 5 * spikes, 28L}));
}

// The streaming datapath (DtmfDatapath::Streaming, rtl/dtmf_chain.v) after
// a frame's last taxel with its layers on and the spikes recorded: a row
// of the synapse and both layers' pipelines (C + 40), layer 1's events a
// clock each (n1 of them, every spike recorded, dropped or not; layer 0's
// go to the encoder as its taxels pass, a clock each beside them), and
// the SPIKES packet (8 + 5 n clocks, n events in it) before the next
// frame's header is taken. tests/rtl/dtmf_chain_test.cpp FrameClocks*
// checks it against the RTL's periods. A plan's worst: n1 = T, n =
// MAX_SPIKES.
inline long dtmf_chain_spike_tail_clocks(int cols, long layer1_events, long events) {
  return cols + 40 + layer1_events + 5 * events + 8;
}
inline long dtmf_chain_spike_tail_clocks(const DtmfTopPlan& p) {
  return dtmf_chain_spike_tail_clocks(p.C, p.T, p.max_spikes);
}

// rtl/dtmf_chain.v's own clocks a frame, its control plane's step (the
// frame engine's, ucode/dtmf_frame_bound.h) aside, from the blocks' stated
// latencies (tests/rtl/dtmf_chain_test.cpp FrameClocks* checks them with
// nothing stalling): a frame's first token to its first taxel K + 45, then
// a taxel a clock (two with a dense packet: its two bytes), after the last
// taxel the dense packet's last bytes (3) or the sparse packet (12 + 4 n
// clocks, n = T: every taxel lit), and with the layers on and spikes
// recorded the spike tail. `mask`: the output mask the frames may have
// (the plan's, or 0xFF for any SET_OUTPUT_MASK).
inline long dtmf_chain_frame_clocks(const DtmfTopPlan& p, uint8_t mask) {
  const bool dense = mask & kMaskTaxels, sparse = mask & kMaskSparse;
  long c = p.K + 45 + (dense || sparse ? 2L : 1L) * (p.T - 1);
  c += sparse ? 12 + 4L * p.T : dense ? 3 : 1;
  if (p.spec.spikes && (mask & kMaskSpikes)) c += dtmf_chain_spike_tail_clocks(p);
  return c;
}

constexpr int kSynapseFrac = 8;  // synapse weights: int16, 8 fraction bits

namespace dtmf_top_detail {
inline int clog2(long v) {
  int b = 0;
  while ((1L << b) < v) ++b;
  return b;
}
}  // namespace dtmf_top_detail

// Throws std::invalid_argument naming the field when the spec cannot be
// built (sizes, carriers, demixing, neuron constants).
inline DtmfTopPlan make_dtmf_top_plan(const DtmfTopSpec& s) {
  using dtmf_top_detail::clog2;
  DtmfTopPlan p;
  p.spec = s;
  p.R = s.rows, p.C = s.cols, p.K = s.rows + s.cols, p.T = s.rows * s.cols, p.N = s.window;
  // At most 128 DFT channels (the carriers, + DC when demixing):
  // rtl/frame_capture.v's 2 KS words in its 8-bit address.
  if (s.rows < 1 || s.cols < 1 || p.K + (s.demix ? 1 : 0) > 128 || p.T > 4096)
    throw std::invalid_argument(
        "skin.rows/cols: expected 1..128 DFT channels (carriers" +
        std::string(s.demix ? " + the demixing's DC channel" : "") +
        ") and 1..4096 taxels, got " + std::to_string(s.rows) + "x" + std::to_string(s.cols));
  if (int(s.carrier_hz.size()) != p.K)
    throw std::invalid_argument("skin.carriers: expected " + std::to_string(p.K) +
                                " frequencies, got " + std::to_string(s.carrier_hz.size()));
  if (s.adc_bits < 1 || s.adc_bits > 12)
    throw std::invalid_argument("skin.adc.bits: expected 1..12 (AD7476A), got " +
                                std::to_string(s.adc_bits));
  if (s.window < 4 || s.window > 4096)
    throw std::invalid_argument("decoder.window: expected 4..4096 samples, got " +
                                std::to_string(s.window));
  p.acc_w = 12 + 1 + clog2(p.N);
  const int ks = s.demix ? p.K + 1 : p.K;
  if (s.sdft_lanes < 1 || s.sdft_lanes > std::min(64, ks))
    throw std::invalid_argument("sdft_lanes: expected 1.." + std::to_string(std::min(64, ks)) +
                                " (at most 64, at most the " + std::to_string(ks) +
                                " DFT channels), got " + std::to_string(s.sdft_lanes));
  if (s.datapath == DtmfDatapath::Streaming &&
      (s.demix || s.neuron_unit || s.neuron_lanes != 0 || p.R > 255 || p.C > 255 ||
       p.T > 16383))
    throw std::invalid_argument(
        "datapath: the streaming datapath (rtl/dtmf_chain.v) takes bin-centred carriers (no "
        "demixing), its own neuron layers (no neuron unit or lanes) and up to 255 rows, 255 "
        "columns and 16383 taxels; this plan has " +
        std::string(s.demix ? "demixing" : (s.neuron_unit || s.neuron_lanes) ? "the neuron unit"
                                                                             : "too many taxels"));
  if (s.sdft_fifo < 0 || s.sdft_fifo > 64 || (s.sdft_fifo & (s.sdft_fifo - 1)) != 0)
    throw std::invalid_argument("sdft_fifo: expected 0 or a power of two up to 64 samples, got " +
                                std::to_string(s.sdft_fifo));
  if (s.neuron_lanes != 0 && (!s.neuron_unit || s.neuron_lanes < 5 || s.neuron_lanes > 8 ||
                              2 * p.T > 2048))
    throw std::invalid_argument("neuron_lanes: expected 0, or 5..8 with the neuron unit and at "
                                "most 1024 taxels, got " + std::to_string(s.neuron_lanes) +
                                (s.neuron_unit ? "" : " without the unit") + " for " +
                                std::to_string(p.T) + " taxels");
  p.mag_shift = clog2(p.N) > 5 ? clog2(p.N) - 5 : 0;
  p.step = int(std::lround(s.frame_ms * s.sample_hz / 1000.0));
  if (p.step < 1)
    throw std::invalid_argument("frame_ms: expected at least one sample per frame, got " +
                                std::to_string(s.frame_ms) + " ms");
  if (p.step > 32767)  // the microcode forms STEP x inc on the 16 x 16 multiplier
    throw std::invalid_argument("frame_ms: expected at most 32767 samples per frame, got " +
                                std::to_string(p.step) + " (" + std::to_string(s.frame_ms) +
                                " ms at " + std::to_string(s.sample_hz) + " Hz)");
  const double frame_ms = 1000.0 * p.step / s.sample_hz;
  // Carriers (+ the DC channel last when demixing).
  p.ks = s.demix ? p.K + 1 : p.K;
  for (double f : s.carrier_hz) p.inc.push_back(sdft_phase_increment(f, s.sample_hz));
  if (s.demix) {
    p.inc.push_back(0);
    const double gain = (std::ldexp(1.0, 15) - 1) / std::ldexp(1.0, 15);  // sdft_bank's G
    const auto st = carrier_demix_tables(s.carrier_hz, s.sample_hz, gain, p.N, 64, 10, 16, 16,
                                         14, p.step, 0, p.demix);
    if (!st.ok) throw std::invalid_argument("decoder.variant (demixing): " + st.message);
  }
  // One full carrier in magnitude units: window sum N/2 * A (12-bit codes);
  // demixing removes the bank's gain G, the plain bank keeps it.
  const double a12 = s.full_carrier_lsb * std::ldexp(1.0, 12 - s.adc_bits);
  p.full_mag = p.N / 2.0 * a12 / std::ldexp(1.0, p.mag_shift) *
               (s.demix ? 1.0 : (std::ldexp(1.0, 15) - 1) / std::ldexp(1.0, 15));
  if (!(p.full_mag >= 64 && p.full_mag < 65536))
    throw std::invalid_argument("skin.amp_gain: one full carrier is " + std::to_string(p.full_mag) +
                                " magnitude units, expected 64..65535 (resolution / 16 bits)");
  p.taxel.rows = uint8_t(p.R), p.taxel.cols = uint8_t(p.C);
  int rs = 0;
  while (std::ldexp(1.0, 15 + rs) / p.full_mag < 16384.0) ++rs;
  p.taxel.recip_shift = uint8_t(rs);
  p.taxel.recip = uint16_t(std::lround(std::ldexp(1.0, 15 + rs) / p.full_mag));
  // Ghost filter: thresholds from g units; lookback one window of frames.
  p.lookback = std::max(1, p.N / p.step);
  auto mag_units = [&](double g, const char* field) {
    const double v = std::floor(g * p.full_mag);
    if (!(v >= 0 && v < 65536))
      throw std::invalid_argument(std::string(field) + ": expected 0 <= g < 1, got " +
                                  std::to_string(g));
    return uint16_t(v);
  };
  p.ghost.rows = uint8_t(p.R), p.ghost.cols = uint8_t(p.C);
  p.ghost.lookback = uint16_t(p.lookback);
  p.ghost.onset = mag_units(s.ghost_onset_g, "decoder.ghost_onset");
  p.ghost.pair_tol = mag_units(s.ghost_pair_tol_g, "decoder.ghost_pair_tol");
  p.ghost.release = uint16_t(std::min(65535.0, std::ceil(s.ghost_release_g * 32768.0)));
  // The onsets one frame may pair (hls/ghost_filter.h max_pairs): a frame
  // pairs at most R + C - 1 anyway; beyond 8 simultaneous new contacts the
  // thesis step takes over, and the frame engine's bound (its pairing loop,
  // O(K) a pair) stays independent of the skin's size.
  p.ghost.max_pairs = uint8_t(std::min(8, p.R + p.C - 1));
  // Neurons: one step per frame.
  const double lsb = s.neuron_input_scale / 32768.0 / (s.neuron_change ? frame_ms : 1.0);
  p.neuron[0] = make_izhikevich_config(izhikevich_fixed_preset(s.neuron_preset), frame_ms, lsb, 1);
  p.neuron[0].input_change = s.neuron_change;
  p.neuron[1] = make_izhikevich_config(izhikevich_fixed_preset(s.layer2_preset), frame_ms,
                                       std::ldexp(1.0, -kSynapseFrac), 0);
  p.synapse.rows = uint8_t(p.R), p.synapse.cols = uint8_t(p.C);
  auto weight = [](double w, const char* field) {
    const double q = std::nearbyint(std::ldexp(w, kSynapseFrac));
    if (!(q >= -32768 && q <= 32767))
      throw std::invalid_argument(std::string(field) + ": expected |w| < 128, got " +
                                  std::to_string(w));
    return int16_t(q);
  };
  for (int d = 0; d < 9; ++d)
    p.synapse.w[d] = weight(d == 4 ? s.layer2_centre : s.layer2_surround,
                            d == 4 ? "neuron.layer2.centre" : "neuron.layer2.surround");
  p.mask = kMaskAmplitudes | kMaskTaxels | (s.spikes ? kMaskSpikes : 0);
  // Packets every `decim` frames so that the link carries them with a 1.5x
  // margin (spikes, status, framing): amplitudes (10 + 2K bytes) and dense
  // taxels (12 + 2T) per frame against baud / 10 bytes per second.
  const double bytes = 1.5 * ((10.0 + 2 * p.K + 2) + (10.0 + 2 + 2.0 * p.T + 2));
  const double link = double(s.baud) / 10.0 * frame_ms / 1000.0;
  p.decim_amp = p.decim_tax = uint16_t(std::max(1.0, std::ceil(bytes / link)));
  p.out_depth = 512;
  while (p.out_depth < longest_packet_bytes(p)) p.out_depth *= 2;
  return p;
}

// The plan's constants after the DFT, the same in every configuration
// built from it (chain_config below; the fast engine's, host/engine).
template <class C>
void copy_chain_constants(const DtmfTopPlan& p, C& c) {
  c.taxel = p.taxel;
  c.ghost = p.spec.ghost;
  c.ghost_cfg = p.ghost;
  c.neurons = p.spec.spikes;
  c.neuron[0] = p.neuron[0];
  c.neuron[1] = p.neuron[1];
  c.synapse = p.synapse;
  c.step = p.step;
  c.decim_amp = p.decim_amp;
  c.decim_tax = p.decim_tax;
  c.sparse_min = p.sparse_min;
  c.mask = p.mask;
}

// The fixed-size configuration of hls/dtmf_chain.h for the plan; the chain's
// sizes S must be the plan's.
template <class S>
DtmfChainConfig<S> chain_config(const DtmfTopPlan& p) {
  if (S::R != p.R || S::C != p.C || S::N != p.N)
    throw std::invalid_argument("chain_config: the chain is built for " + std::to_string(S::R) +
                                "x" + std::to_string(S::C) + " N " + std::to_string(S::N) +
                                ", the plan is " + std::to_string(p.R) + "x" +
                                std::to_string(p.C) + " N " + std::to_string(p.N));
  if (p.lookback > S::L_MAX || p.max_spikes != S::MAX_SPIKES)
    throw std::invalid_argument("chain_config: lookback / spike capacity differ from the chain's");
  DtmfChainConfig<S> c;
  c.sdft.carriers = p.ks;
  for (int k = 0; k < p.ks; ++k) c.sdft.inc[k] = p.inc[size_t(k)];
  c.demix = p.spec.demix;
  if (c.demix) {
    c.demix_cfg.carriers = p.K;
    for (int k = 0; k < p.K; ++k)
      c.demix_cfg.inc[k] = p.demix.inc[size_t(k)], c.demix_cfg.phase0[k] = p.demix.phase0[size_t(k)];
    for (size_t i = 0; i < p.demix.qsin.size(); ++i) c.demix_cfg.qsin[i] = p.demix.qsin[i];
    for (size_t i = 0; i < p.demix.coef.size(); ++i) c.demix_cfg.coef[i] = p.demix.coef[i];
  }
  copy_chain_constants(p, c);
  return c;
}

// ---- clock budget (`eskin bitstream`, the scale table) ---------------------
// Whether rtl/dtmf_top.v keeps up with the plan's sample rate at clk_hz.
// The top's budgets, from its modules' headers:
//  - adc_ad7476, on its clock a (spec.adc_clk_hz, else clk): one conversion
//    every A = round(a / fs) clocks of a, SCLK = a / (2 H) with H = ceil(a /
//    40 MHz) (dtmf_top's SCLK_DIV, so SCLK <= 20 MHz at any clock); the
//    AD7476A needs (A - 28 H) clocks >= 250 ns of acquisition (tACQ) and
//    (A - 31 H) clocks >= 86 ns of quiet time (t8 + tQUIET) and (A - 32 H)
//    clocks >= 10 ns of CS high (t1) (dtmf_top_adc_problem, the same checks
//    as adc_ad7476's elaboration). On clk, the sample period P below is A. On
//    its own clock, samples reach clk's domain through stream_cdc's
//    synchroniser, a sample every A / a seconds give or take a clock of
//    clk either way (a synchroniser may resolve a clock late): P = floor(
//    clk A / a) - 1 clocks between two samples at the least, and a frame
//    of STEP samples floor(STEP clk A / a) - 1 clocks. The CDC holds two
//    samples more than the ADC's one register, so the one-register rule
//    below still holds.
//  - the DFT: a frame's sample (one in STEP) takes F = sdft_lanes_interval(
//    KS, L, 1) clocks to the next handshake, the lanes' II with a consumer
//    that takes a token every clock (rtl/frame_capture.v: it stores and
//    judges each token in its own clock). One lane: sdft_bank's 6 KS + 2,
//    the next sample's handshake in the clock of the last token; L >= 2
//    lanes: 9 + (KS - 1) + max(0, 6 - L) (ceil(KS / L) - 1), KS + 8 from 6
//    lanes on (rtl/sdft_lanes.v). Every other sample gives no tokens (dtmf_top
//    skips them) and takes S = sdft_skip_interval(KS, L) = 6 ceil(KS / L)
//    + 2. The ADC converts every period P clocks whatever the DFT does and
//    holds one sample: it loses one when the previous is not taken before
//    the next conversion lands. D = spec.sdft_fifo samples may queue in
//    front of the lanes (rtl/sdft_front.v). With S <= P a frame's sample
//    that takes F > P delays the next by F - P, and each sample after it
//    makes up P - S. No sample is lost iff
//      S <= P,  F < (D + 2) P  and  F - P <= (STEP - 1)(P - S)
//    (the samples converted while the frame's sample holds the lanes fit
//    the FIFO and the ADC's register; the delay is back to 0 by the next
//    frame's sample; STEP = 1: F <= P): dtmf_top_sdft_min_period, which is
//    hls::sdft_front_min_period. tests/rtl/sdft_front_test.cpp runs the
//    lanes into frame_capture at the ADC's pace at and one clock below that
//    period (a 64x64 skin at 1 MS/s, and without a FIFO);
//    tests/rtl/dft_capture_test.cpp at a 32x32 skin's 1 MS/s.
//  - frame_engine: frame_capture loses a frame unless the engine has
//    released the previous one when it is complete, so the engine's longest
//    frame plus the longest command it may have started just before that
//    frame (commands run between frames) must fit in STEP x period clocks.
//    `engine_clocks` is that sum; host/fpga/engine_load.h measures it on the
//    instruction-set model (the microcode's time depends on the data).
//    `bound_clocks` (when > 0) is the same sum proven from the microprogram
//    (ucode/dtmf_frame_bound.h: every path, every loop at its bound): it
//    must fit in dtmf_frame_bound_limit_percent of the frame (90 % on the
//    frame engine), so a build keeps a margin even over its proven worst
//    case.
//  - the UART: a bit is round(clk / baud) clocks (uart_tx/uart_rx, which
//    stop at elaboration beyond 3 %); within 2 % here, leaving the host's
//    own rate error room.
struct DtmfTopClockBudget {
  long clk_hz = 0;
  long adc_clk_hz = 0;     // the ADC's clock (clk_hz when it runs on clk)
  long adc_period = 0;     // its clocks per sample (A)
  long period = 0;         // clocks of clk per ADC sample, at the least (P)
  long sclk_div = 0;       // H
  long sdft_clocks = 0;    // a frame sample's II: dtmf_top_sdft_clocks()
  long sdft_skip_clocks = 0;  // any other sample's: dtmf_top_sdft_skip_clocks()
  long sdft_min_period = 0;   // what those need of the period: dtmf_top_sdft_min_period()
  // Samples waiting after a frame's at P (sdft_front_backlog): the FIFO
  // holds up to sdft_fifo of them, the ADC's register one more.
  long sdft_backlog = 0;
  long frame_clocks = 0;   // STEP x period: the engine's time per frame
  long engine_clocks = 0;  // what the engine needs of it
  long bound_clocks = 0;   // its static bound (0: not checked)
  long bound_limit_clocks = 0;  // the most of the frame the bound may take
  std::vector<std::string> problems;  // empty: the top keeps up
  bool ok() const { return problems.empty(); }
};

// Clocks from one sample's handshake into the DFT to the next that
// rtl/dtmf_top.v needs: a frame's sample, the DFT's II with frame_capture,
// the consumer, taking a token every clock (above) ...
inline long dtmf_top_sdft_clocks(int ks, int lanes) {
  return long(sdft_lanes_interval(ks, lanes, 1));
}
// ... and every other sample, whose tokens the top skips.
inline long dtmf_top_sdft_skip_clocks(int ks, int lanes) {
  return long(sdft_skip_interval(ks, lanes));
}
// The shortest sample period (clocks) at which the ADC loses no sample to
// the DFT (above), `fifo` samples queued in front of it: the least P with
// S <= P, F < (fifo + 2) P and STEP P >= F + (STEP - 1) S.
inline long dtmf_top_sdft_min_period(int ks, int lanes, long step, int fifo = 0) {
  return long(sdft_front_min_period(dtmf_top_sdft_clocks(ks, lanes),
                                    dtmf_top_sdft_skip_clocks(ks, lanes), step, fifo));
}

// Why the DFT loses samples at `period` (empty when it keeps up), `at`
// after the period (the clock and rate): the first of the three
// conditions above that fails, in words.
inline std::string dtmf_top_sdft_problem(int ks, int lanes, long step, int fifo, long period,
                                         const std::string& at = "") {
  const long f = dtmf_top_sdft_clocks(ks, lanes), sk = dtmf_top_sdft_skip_clocks(ks, lanes);
  const long min = dtmf_top_sdft_min_period(ks, lanes, step, fifo);
  if (period >= min) return "";
  auto n = [](long v) { return std::to_string(v); };
  if (lanes == 1)  // S = F: every sample needs the whole period
    return "sdft_bank: needs 6 KS + 2 = " + n(f) + " clocks per sample, the sample period is " +
           n(period) + at;
  std::string why;
  if (step <= 1)
    why = "every sample is a frame's";
  else if (sk > period)
    why = "the skipped samples take longer than a sample period";
  else if (f >= (fifo + 2) * period)
    why = "the " + n(f / period) + " samples converted while a frame's sample holds the lanes "
          "do not fit " + (fifo > 0 ? "the " + n(fifo) + "-sample FIFO and " : "") +
          "the ADC's one register (F < (" + n(fifo) + " + 2) P)";
  else
    why = "the samples queued after a frame's (the next " + n(f - period) +
          " clocks late) do not catch up before the next frame's (F - P <= (STEP - 1)(P - S))";
  return "sdft_lanes (" + n(lanes) + " lanes of KS = " + n(ks) + " channels" +
         (fifo > 0 ? ", a " + n(fifo) + "-sample FIFO" : "") + "): a frame's sample takes " +
         n(f) + " clocks, the others " + n(sk) + "; with STEP " + n(step) +
         " that needs a sample period of " + n(min) + " clocks, the sample period is " +
         n(period) + at + ": " + why;
}

// adc_ad7476's SCLK_DIV as rtl/dtmf_top.v sets it on an ADC clock of
// adc_hz: clocks per SCLK half period, SCLK at most 20 MHz.
inline long dtmf_top_sclk_div(long adc_hz) { return (adc_hz + 39999999) / 40000000; }

// What keeps adc_ad7476 on a clock of adc_hz from converting at fs (above),
// empty when nothing does.
inline std::string dtmf_top_adc_problem(double fs, long adc_hz) {
  const long period = std::lround(double(adc_hz) / fs);
  const long h = dtmf_top_sclk_div(adc_hz);
  const double ns = 1e9 / double(adc_hz);
  const double acq = double(period - 28 * h) * ns, quiet = double(period - 31 * h) * ns;
  const double t1 = double(period - 32 * h) * ns;
  if (acq >= 250.0 && quiet >= 86.0 && t1 >= 10.0) return "";
  char s[280];
  std::snprintf(s, sizeof s,
                "adc_ad7476: a sample period of %ld clocks leaves %.0f ns of acquisition "
                "(>= 250 ns), %.0f ns of quiet time (>= 86 ns) and %.0f ns of CS high (>= 10 ns) "
                "at SCLK_DIV %ld (%.6g MHz / %.6g S/s)",
                period, acq, quiet, t1, h, double(adc_hz) / 1e6, fs);
  return s;
}

// The frame clocks the bound may take: limit % of frame_clocks.
inline long dtmf_frame_bound_limit_clocks(const DtmfTopPlan& p, long frame_clocks) {
  return long(frame_clocks * int64_t(dtmf_frame_bound_limit_percent(p.spec.datapath)) / 100);
}

inline DtmfTopClockBudget dtmf_top_clock_budget(const DtmfTopPlan& p, long clk_hz,
                                                long engine_clocks, long bound_clocks = 0) {
  DtmfTopClockBudget b;
  const double fs = p.spec.sample_hz;
  b.clk_hz = clk_hz;
  b.adc_clk_hz = p.spec.adc_clk_hz > 0 ? p.spec.adc_clk_hz : clk_hz;
  b.adc_period = std::lround(double(b.adc_clk_hz) / fs);
  b.sclk_div = dtmf_top_sclk_div(b.adc_clk_hz);
  const int lanes = p.spec.sdft_lanes;
  b.sdft_clocks = dtmf_top_sdft_clocks(p.ks, lanes);
  b.sdft_skip_clocks = dtmf_top_sdft_skip_clocks(p.ks, lanes);
  b.sdft_min_period = dtmf_top_sdft_min_period(p.ks, lanes, p.step, p.spec.sdft_fifo);
  if (p.spec.adc_clk_hz > 0) {  // exact in integers: clk and a are whole Hz
    const long double per = (long double)clk_hz * b.adc_period / b.adc_clk_hz;
    b.period = long(std::floor(per)) - 1;
    b.frame_clocks = long(std::floor(per * p.step)) - 1;
  } else {
    b.period = b.adc_period;
    b.frame_clocks = long(p.step) * b.period;
  }
  b.engine_clocks = engine_clocks;
  b.bound_clocks = bound_clocks;
  b.bound_limit_clocks = dtmf_frame_bound_limit_clocks(p, b.frame_clocks);
  auto at = [&] {
    char s[64];
    std::snprintf(s, sizeof s, " (%.6g MHz / %.6g S/s)", double(clk_hz) / 1e6, fs);
    return std::string(s);
  };
  auto n = [](long v) { return std::to_string(v); };
  if (const std::string adc = dtmf_top_adc_problem(fs, b.adc_clk_hz); !adc.empty())
    b.problems.push_back(adc);
  b.sdft_backlog = long(sdft_front_backlog(b.sdft_clocks, b.period));
  if (const std::string dft =
          dtmf_top_sdft_problem(p.ks, lanes, p.step, p.spec.sdft_fifo, b.period, at());
      !dft.empty())
    b.problems.push_back(dft);
  if (engine_clocks > b.frame_clocks)
    b.problems.push_back(std::string(p.spec.datapath == DtmfDatapath::Streaming
                                         ? "streaming datapath: the control plane's longest "
                                           "frame and command and the chain's own clocks take "
                                         : "frame_engine: its longest frame and command take ") +
                         n(engine_clocks) +
                         " clocks, a frame is " +
                         (p.spec.adc_clk_hz > 0
                              ? "STEP samples of the ADC's clock = " + n(b.frame_clocks) +
                                    " clocks at the least"
                              : "STEP x period = " + n(p.step) + " x " + n(b.period) + " = " +
                                    n(b.frame_clocks)) +
                         at());
  if (bound_clocks > b.bound_limit_clocks) {
    char s[400];
    std::snprintf(s, sizeof s,
                  "%s: the static bound of a frame and a command, %ld clocks, is %.1f %% "
                  "of a frame of %ld clocks; a build may take at most %d %% (%ld clocks)",
                  p.spec.datapath == DtmfDatapath::Streaming ? "streaming datapath"
                                                             : "frame_engine",
                  bound_clocks, 100.0 * double(bound_clocks) / double(b.frame_clocks),
                  b.frame_clocks, dtmf_frame_bound_limit_percent(p.spec.datapath),
                  b.bound_limit_clocks);
    b.problems.push_back(std::string(s) + at());
  }
  const long cpb = std::lround(double(clk_hz) / double(p.spec.baud));
  const double err = cpb > 0 ? double(clk_hz) / double(cpb * p.spec.baud) - 1.0 : 1.0;
  if (cpb < 2 || std::fabs(err) > 0.02) {
    char s[160];
    std::snprintf(s, sizeof s, "uart: %ld baud is %ld clocks per bit at %.6g MHz (%.1f %% off)",
                  p.spec.baud, cpb, double(clk_hz) / 1e6, 100.0 * err);
    b.problems.push_back(s);
  }
  return b;
}

// The clock each budget asks for at the plan's rate (Hz, not rounded): the
// ADC's acquisition time with SCLK_DIV = 1 at best (adc_ok false when no
// clock lets the AD7476A convert that fast; none asked of clk when the ADC
// has its own, spec.adc_clk_hz), the engine's clocks a frame,
// and the DFT's least sample period at the spec's lanes.
struct DtmfTopClockNeeds {
  bool adc_ok = false;
  double adc_hz = 0, engine_hz = 0, dft_hz = 0;
  long dft_period = 0;  // dtmf_top_sdft_min_period
};

inline DtmfTopClockNeeds dtmf_top_clock_needs(const DtmfTopPlan& p, long engine_clocks) {
  DtmfTopClockNeeds n;
  const double fs = p.spec.sample_hz;
  const double room = 1.0 / fs - 250e-9;  // s per sample left after tACQ
  n.adc_ok = room > 28.0 / 40e6;          // 28 H / clk >= 0.7 us at any clock
  // On its own clock the ADC asks nothing of clk.
  n.adc_hz = n.adc_ok && p.spec.adc_clk_hz == 0 ? 28.0 / room : 0.0;
  n.engine_hz = fs * double(engine_clocks) / double(p.step);
  n.dft_period = dtmf_top_sdft_min_period(p.ks, p.spec.sdft_lanes, p.step, p.spec.sdft_fifo);
  n.dft_hz = fs * double(n.dft_period);
  return n;
}

// The slowest clock the ADC's acquisition time and the engine allow, the
// DFT aside: what its lanes must not exceed. 0 when the ADC cannot convert
// at the sample rate at any clock.
inline long dtmf_top_min_clock_hz_without_dft(const DtmfTopPlan& p, long engine_clocks) {
  const DtmfTopClockNeeds n = dtmf_top_clock_needs(p, engine_clocks);
  return n.adc_ok ? long(std::ceil(std::max(n.adc_hz, n.engine_hz))) : 0;
}

// The slowest clock the DFT (at the spec's lanes), the engine and the ADC's
// acquisition time allow. Only a lower bound: check a clock with
// dtmf_top_clock_budget (the SCLK divider steps up at every 40 MHz, and
// periods are rounded). 0 when the ADC cannot convert at the sample rate at
// any clock.
inline long dtmf_top_min_clock_hz(const DtmfTopPlan& p, long engine_clocks) {
  const DtmfTopClockNeeds n = dtmf_top_clock_needs(p, engine_clocks);
  return n.adc_ok ? long(std::ceil(std::max({n.adc_hz, n.engine_hz, n.dft_hz}))) : 0;
}

// What sets dtmf_top_min_clock_hz, in words, for the flow's messages: the
// clock each budget asks for (dtmf_top_clock_needs; the DFT's at the plan's
// lanes, which the flow picks as the fewest that ask no more than the other
// two at the board's clock: then the DFT's figure may be the largest while
// the others set it).
inline std::string dtmf_top_min_clock_reason(const DtmfTopPlan& p, long engine_clocks) {
  const DtmfTopClockNeeds n = dtmf_top_clock_needs(p, engine_clocks);
  if (!n.adc_ok) return "the AD7476A cannot convert that fast";
  char adc[96];
  if (p.spec.adc_clk_hz > 0)
    std::snprintf(adc, sizeof adc, "the AD7476A on its own %.6g MHz clock",
                  double(p.spec.adc_clk_hz) / 1e6);
  else
    std::snprintf(adc, sizeof adc, "the AD7476A's acquisition time %.1f MHz", n.adc_hz / 1e6);
  char s[400];
  std::snprintf(s, sizeof s,
                "%s, the %s %ld clocks a frame of %d samples %.1f MHz, the DFT's %ld "
                "clocks a sample in %d lane%s %.1f MHz",
                adc,
                p.spec.datapath == DtmfDatapath::Streaming ? "streaming datapath's"
                                                           : "frame engine's",
                engine_clocks, p.step, n.engine_hz / 1e6, n.dft_period, p.spec.sdft_lanes,
                p.spec.sdft_lanes == 1 ? "" : "s", n.dft_hz / 1e6);
  return s;
}

// "-GNAME=VALUE" arguments for verilator.
inline std::vector<std::string> verilator_g_args(const std::vector<VerilogParam>& ps) {
  std::vector<std::string> a;
  for (const auto& q : ps) a.push_back("-G" + q.name + "=" + q.value);
  return a;
}

}  // namespace eskin::hls
