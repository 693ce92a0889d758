// Host-side, not synthesised: the frame engine's view of a DTMF top plan
// (common/eskin/dtmf_top_plan.h) — the DMEM layout, the KROM words and the symbol
// table that rtl/ucode/dtmf_chain.fe is assembled with. One function builds
// all three, so the microprogram, its constants and the HLS chain come from
// the same plan.
//
// KROM = [config words, copied to DMEM 0 .. NCFG-1 at boot and changed by
// commands afterwards] ++ [read-only constants KC_*, tables, the packed
// quarter sine]. DMEM = [config] ++ [state, zeroed at boot] up to DEND.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "eskin/dtmf_commands.h"
#include "eskin/dtmf_top_plan.h"
#include "ucode/dtmf_io_map.h"

namespace eskin::hls {

constexpr int kNeuronBlock = 20;  // words of constants per layer (NCS)
constexpr int kDtmfImemBits = 11;     // microcode address bits
constexpr int kDtmfImemWords = 1280;  // microcode words: 10 EBRs (256 x 16 each)

// The largest frame engine rtl/frame_engine.v builds (its DW and KW
// limits), with or without the barrel shifter: the configuration the C++
// models of the top run the microcode on (ucode/frame_engine.h), any
// plan's image fitting it.
template <bool FAST>
struct DtmfEngineMax {
  static constexpr int IW = kDtmfImemBits, DW = 15, KW = 12;
  static constexpr bool FAST_SHIFT = FAST;
};

// SET_NEURON parameter p (id & 15): its word in the layer block, its range.
struct NeuronParam {
  const char* name;
  int word;          // its word in the block (gain_shift: 13 right, 14 left; u_frac: 4 = u_frac - 22)
  int64_t lo, hi;    // accepted values
};
inline const NeuronParam* neuron_params() {
  static const NeuronParam p[16] = {
      {"v_reset", 2, -(int64_t(1) << 29), (int64_t(30) << 22) - 1},
      {"u_jump", 3, -(int64_t(1) << 30), (int64_t(1) << 30) - 1},
      {"gain", 12, -32768, 32767},
      {"gain_shift", 13, -15, 40},
      {"x_shift", 15, 0, 16},
      {"c_const", 5, -68157440, 0},  // -16.25 mV 2^22 (k <= 1) .. 0
      {"m2", 6, -32768, 32767},
      {"s2", 7, 0, 40},
      {"m3", 8, -32768, 32767},
      {"s3", 9, 0, 40},
      {"m4", 10, -32768, 32767},
      {"s4", 11, 0, 40},
      {"u_frac", 4, 22, 30},
      {"input_change", 16, 0, 1},
      {"v_init", 0, -(int64_t(1) << 29), (int64_t(30) << 22) - 1},
      {"u_init", 1, -(int64_t(1) << 30), (int64_t(1) << 30) - 1},
  };
  return p;
}

// The same change applied to the HLS configuration (false: out of range).
inline bool apply_neuron_param(IzhikevichConfig& c, int param, int64_t v) {
  if (param < 0 || param > 15) return false;
  const NeuronParam& p = neuron_params()[param];
  if (v < p.lo || v > p.hi) return false;
  switch (param) {
    case 0: c.v_reset = int32_t(v); break;
    case 1: c.u_jump = int32_t(v); break;
    case 2: c.gain = int16_t(v); break;
    case 3: c.gain_shift = int8_t(v); break;
    case 4: c.x_shift = uint8_t(v); break;
    case 5: c.c_const = int32_t(v); break;
    case 6: c.m2 = int16_t(v); break;
    case 7: c.s2 = uint8_t(v); break;
    case 8: c.m3 = int16_t(v); break;
    case 9: c.s3 = uint8_t(v); break;
    case 10: c.m4 = int16_t(v); break;
    case 11: c.s4 = uint8_t(v); break;
    case 12: c.u_frac = uint8_t(v); break;
    case 13: c.input_change = v != 0; break;
    case 14: c.v_init = int32_t(v); break;
    case 15: c.u_init = int32_t(v); break;
  }
  return true;
}

// A layer's constant block as the microcode keeps it in DMEM (NC + NCS l)
// and the neuron unit takes it (words 2..16): the words of neuron_params().
inline std::array<int64_t, kNeuronBlock> neuron_block(const IzhikevichConfig& n) {
  return {n.v_init, n.u_init, n.v_reset, n.u_jump, n.u_frac - 22, n.c_const, n.m2, n.s2, n.m3,
          n.s3, n.m4, n.s4, n.gain, n.gain_shift > 0 ? n.gain_shift : 0,
          n.gain_shift < 0 ? -n.gain_shift : 0, n.x_shift, n.input_change ? 1 : 0, 0, 0, 0};
}


struct EngineImage {
  std::vector<uint32_t> krom;
  std::vector<std::pair<std::string, int64_t>> symbols;
  int ncfg = 0, dend = 0;  // DMEM words: configuration, all
  int64_t symbol(const std::string& name) const {
    for (const auto& s : symbols)
      if (s.first == name) return s.second;
    throw std::out_of_range("EngineImage: no symbol " + name);
  }
};

inline EngineImage dtmf_engine_image(const DtmfTopPlan& p) {
  const int K = p.K, R = p.R, C = p.C, T = p.T;
  const bool demix = p.spec.demix;
  const int ks = p.ks, dim = demix ? 2 * K + 1 : 0;
  // The streaming datapath (rtl/dtmf_chain.v) keeps the taxels, the sites,
  // the neurons and the spikes: the engine, its control plane, none of them.
  const bool stream = p.spec.datapath == DtmfDatapath::Streaming;
  const int t_words = stream ? 0 : T;
  EngineImage im;
  auto sym = [&im](const std::string& n, int64_t v) { im.symbols.emplace_back(n, v); };
  int at = 0;
  auto alloc = [&](const std::string& n, int words) {
    sym(n, at);
    at += words;
  };
  auto put = [&im](int64_t v) { im.krom.push_back(uint32_t(v)); };

  // ---- configuration (initial values, in KROM order = DMEM order) ----
  alloc("NC", 2 * kNeuronBlock);
  for (int l = 0; l < 2; ++l)
    for (int64_t v : neuron_block(p.neuron[l])) put(v);
  alloc("MASK", 1), put(p.mask);
  alloc("DECIM", 3), put(p.decim_amp), put(p.decim_tax), put(kDtmfStatusDecimReset);
  alloc("THR", 4), put(p.sparse_min), put(p.ghost.onset), put(p.ghost.release),
      put(p.ghost.pair_tol);
  alloc("W", 9);
  for (int d = 0; d < 9; ++d) put(p.synapse.w[d]);
  alloc("INC", ks);
  for (int k = 0; k < ks; ++k) put(p.inc[size_t(k)]);
  alloc("FINC", 2 * K);
  for (int k = 0; k < K; ++k) put(demix ? p.demix.inc[size_t(k)] : 0), put(0);
  alloc("COEF", dim * dim);
  for (int i = 0; i < dim * dim; ++i) put(p.demix.coef[size_t(i)]);
  im.ncfg = at;
  sym("NCFG", at);
  const int64_t thr = im.symbol("THR");
  sym("ONSET", thr + 1), sym("RELEASE", thr + 2), sym("PAIRTOL", thr + 3);
  sym("MAXPAIR", p.ghost.max_pairs);  // ghost_filter's pairs a frame

  // ---- state ----
  const int lk = p.lookback * K;
  alloc("PHASE", 2 * K), alloc("HIST", lk), alloc("HEAD", 1), alloc("REM", K);
  alloc("PL", K), alloc("NPL", 1), alloc("SITE", t_words), alloc("MAG", K);
  alloc("ROOT", stream ? 0 : R), alloc("CRT", stream ? 0 : C);  // line_roots: rows, then columns
  alloc("G", t_words);
  if (!p.spec.neuron_lanes && !stream) {  // the lanes keep the neurons' state and flags themselves
    alloc("X2IN", T);          // layer 1's input: neuron_unit needs X2IN = G + T
    alloc("NV", 2 * T), alloc("NU", 2 * T), alloc("NXP", 2 * T);  // neuron l T + i
    alloc("SZ", C);                  // zero, never written: synapse_weights' row above row 0
    alloc("S0", T), alloc("S1", T);  // and S1 = S0 + T
  }
  alloc("SWT", stream ? 0 : 512);  // synapse_weights: the sum for each 3x3 spike pattern
  alloc("BV", dim + 2), alloc("Y", stream ? 0 : 2 * K), alloc("SPK", stream ? 0 : 2 * p.max_spikes);
  alloc("CB", 9);
  alloc("AMPC", 3), alloc("SEL", 3), alloc("SEND", 3);  // frame counts per stream (amp, tax, status)
  for (const char* n :
       {"VT", "TPASS", "REC", "SPKOPEN", "SPKT0", "SPKN", "SPKDROP", "PKTDROP",
        "ACC", "REJ", "LRT", "LRR", "LRS", "CTYPE", "CSEQ", "CLEN", "PT", "PTT", "PLEN", "TLO",
        "TIDX", "TS", "TC", "TQD", "TOFF", "TV", "TROW", "TACC", "TRI", "TR", "TCL",
        "TBR", "TBC", "TRR", "TRC", "TOK", "TRW", "TB", "TB2", "SEB", "NX", "ND", "NXS",
        "NJ", "NU22", "NW", "NSQ", "NC2", "NVH", "NC3", "NUN", "SWMASK", "SWD", "SWM", "SWI",
        "NDROP", "CHG", "PKTSUM"})
    alloc(n, 1);
  im.dend = at;
  sym("DEND", at);

  // ---- read-only constants ----
  auto kc = [&](const std::string& n, int64_t v) {
    sym(n, int64_t(im.krom.size()));
    put(v);
  };
  kc("KC_ZERO", 0), kc("KC_MINUS1", -1), kc("KC_ONE", 1), kc("KC_TWO", 2), kc("KC_THREE", 3), kc("KC_FOUR", 4);
  kc("KC_EIGHT", 8), kc("KC_FIFTEEN", 15), kc("KC_SIXTEEN", 16), kc("KC_U16", 65535);
  kc("KC_S16MIN", -32768);
  kc("KC_S16MAX", 32767), kc("KC_S24MIN", -(1 << 23)), kc("KC_S24MAX", (1 << 23) - 1);
  kc("KC_I32MIN", INT32_MIN), kc("KC_I32MAX", INT32_MAX), kc("KC_UMIN", izh::kUMin);
  kc("KC_UMAX", izh::kUMax), kc("KC_VMIN", izh::kVMin), kc("KC_VPEAK", izh::kVPeak);
  kc("KC_WOFF", izh::kWOffset), kc("KC_RECIP", p.taxel.recip), kc("KC_C", C);
  kc("KC_H29", 0), put(1 << 29);  // line_roots: mag.h15 2^29, by mag.h15 (0, 1)
  // The chain's IO_RECIP and IO_GHOST words (stream).
  kc("KC_RECIPW", int64_t(p.taxel.recip) | int64_t(p.taxel.recip_shift) << 16);
  kc("KC_GHOSTON", p.spec.ghost ? 1 << 16 : 0), kc("KC_NEURONS", p.spec.spikes ? 1 : 0);
  kc("KC_MASKRES", 0xE0);
  kc("KC_NCOEF", dim * dim), kc("KC_STEP", p.step);
  constexpr int kQ = 1 << (10 - 2);  // quarter table of CarrierDemix<..., TW = 10>
  kc("KC_QM1", kQ - 1);
  kc("KC_SINEQ", demix ? p.demix.qsin[size_t(kQ)] : 0);
  auto table = [&](const std::string& n, auto f, int count) {
    sym(n, int64_t(im.krom.size()));
    for (int i = 0; i < count; ++i) put(f(i));
  };
  table("KC_NLO", [](int q) { return neuron_params()[q].lo; }, 16);
  table("KC_NHI", [](int q) { return neuron_params()[q].hi; }, 16);
  table("KC_NOFF", [](int q) { return neuron_params()[q].word; }, 16);
  table("KC_CLEN", [](int t) { return kDtmfCommands[t].payload_bytes(); }, kDtmfCommandCount);
  // synapse_weights' pattern bit (a power of two) of weight d = (dr + 1) 3 +
  // (dc + 1): bit 3 (1 - dc) + (1 - dr): the newest column (dc = 1) in
  // bits 0..2, row r + 1 the lowest bit of each column (rtl/ucode/dtmf_chain.fe).
  table("KC_SWBIT", [](int d) { return 1 << (3 * (2 - d % 3) + (2 - d / 3)); }, 9);
  // ghost_filter's key of line k (row k, or column k - R): rem 2^15 +
  // KC_IDX[k], the first row or column the largest of its dimension.
  if (p.spec.ghost) table("KC_IDX", [R](int k) { return 0x7FFF - (k < R ? k : k - R); }, K);
  // STATUS fields in payload order: an IO port (bit 15 set) or a DMEM word
  // (address in bits 13..0), one byte wide when bit 14 is set.
  const int64_t io = 0x8000;
  const int64_t byte = 0x4000;
  const int64_t stat[14] = {io | kIoCrcErr, io | kIoFrmErr, im.symbol("ACC"), im.symbol("REJ"),
                            byte | im.symbol("LRT"), byte | im.symbol("LRR"),
                            byte | im.symbol("LRS"), byte | im.symbol("MASK"),
                            // stream: the engine's and the chain's drops (status)
                            im.symbol(stream ? "PKTSUM" : "PKTDROP"), io | kIoAdcOvr,
                            io | kIoRxErr, io | kIoFrameOvr,
                            stream ? io | kIoSpkDrop : im.symbol("SPKDROP"), io | kIoCmdOvf};
  table("KC_STAT", [&stat](int f) { return stat[f]; }, 14);
  kc("KC_BIT15", 0x8000), kc("KC_BIT14", 0x4000), kc("KC_LOW14", 0x3FFF);
  sym("SINE", int64_t(im.krom.size()));
  if (demix)
    for (int e = 0; e <= kQ; e += 2)
      put(uint32_t(p.demix.qsin[size_t(e)] & 0xFFFF) |
          (e + 1 <= kQ ? uint32_t(p.demix.qsin[size_t(e + 1)] & 0xFFFF) << 16 : 0u));

  // ---- sizes, flags, arithmetic ----
  sym("K", K), sym("KS", ks), sym("R", R), sym("C", C), sym("T", T), sym("DIM", dim);
  sym("STEP", p.step), sym("MAXSPK", p.max_spikes), sym("LK", lk), sym("NCS", kNeuronBlock);
  sym("DEMIX", demix), sym("GHOST", p.spec.ghost), sym("NEURONS", p.spec.spikes && !stream);
  sym("SPIKES", p.spec.spikes);  // the layers run (NEURONS: on the engine)
  sym("NEURON_UNIT", p.spec.neuron_unit);
  sym("FAST_SHIFT", p.spec.engine_fast_shift);  // the barrel shifter: a shift is a clock
  sym("STREAM", stream);
  sym("NEURON_LANES", p.spec.neuron_lanes);
  sym("CMD_FIRST", kDtmfCommandFirst), sym("NCMD", kDtmfCommandCount);  // KC_CLEN's types
  // Layer 0's spike flags for synapse_weights: S0 in DMEM (SZ, zeros, the
  // row above it; S1 below), or the lanes' columns of three at FLAGS + n.
  if (p.spec.neuron_lanes) sym("FLAGS", kIoIzFlag + C);
  // The most clocks IO_SDFT_BUSY reads 1 after a carrier write: the DFT
  // takes it once the sample it is on is done (a frame's sample, the
  // longest: dtmf_top_sdft_clocks), and the port is registered (+ 2).
  const long sdft_busy = dtmf_top_sdft_clocks(ks, p.spec.sdft_lanes) + 2;
  sym("SDFT_BUSY", sdft_busy);
  // The most polls of IO_SDFT_BUSY in all while sdft_program loads KS - 1
  // carriers (the last one's wait has SDFT_BUSY of its own): a sample the
  // DFT is on when a write comes (F = SDFT_BUSY clocks at most) delays it,
  // and samples come every P clocks (the plan's sample period at its
  // clock), so over the D clocks of the loop the DFT starts at most D / P
  // + 3 samples (those arriving, one held by the ADC, one in progress), and
  // D = (KS - 1) L + busy with busy <= F (D / P + 3): busy <= F ((KS - 1) L
  // / P + 3) / (1 - F / P) when F < P. L: the loop's clocks besides its
  // polls (10; 16 leaves room for changes). A poll takes 3 clocks (2 at
  // the least): busy / 2 + one more per write. Without F < P, or when
  // smaller: each write waits for the sample the DFT is on, and no more
  // (a pending carrier write holds the next sample back: sdft_lanes'
  // in_ready), which is a frame's (F) only for the frame samples among
  // them, a skipped one's (S + 2 = dtmf_top_sdft_skip_clocks + 2) for the
  // rest: a frame's sample starts at most once in any STEP - D - 2
  // samples (D the FIFO's: those queued may start back to back), each
  // taking S clocks at least, so over the loop's span, each write's L
  // clocks and its wait at most, at most span / ((STEP - D - 2) S) + 1.
  // SDFT_POLLS_CMD: the same for SET_CARRIER_INC's writes besides its
  // carrier's and the last: the other lanes' highest carriers (KS - L ..
  // KS - 2), which rtl/sdft_lanes.v sends each lane again with the last
  // write (its K).
  {
    constexpr long kLoop = 16;
    const long period = dtmf_top_clock_budget(p, p.spec.clk_hz, 0).period;
    const long skip_busy = dtmf_top_sdft_skip_clocks(ks, p.spec.sdft_lanes) + 2;
    auto polls_for = [&](long writes) {
      long polls = writes * ((sdft_busy + 1) / 2);
      const long apart = (long(p.step) - p.spec.sdft_fifo - 2) * (skip_busy - 2);
      if (apart > 0) {
        const long span = writes * (kLoop + sdft_busy);
        const long frames = span / apart + 1;
        polls = std::min(polls, writes * ((skip_busy + 1) / 2) +
                                    frames * ((sdft_busy - skip_busy + 1) / 2 + 1));
      }
      if (period > sdft_busy) {
        const double busy = double(sdft_busy) * (double(writes * kLoop) / double(period) + 3.0) /
                            (1.0 - double(sdft_busy) / double(period));
        polls = std::min(polls, long(std::ceil(busy / 2.0)) + writes);
      }
      return polls;
    };
    sym("SDFT_POLLS", polls_for(ks - 1));
    sym("SDFT_LANES", p.spec.sdft_lanes);
    sym("SDFT_POLLS_CMD", polls_for(std::max(1, p.spec.sdft_lanes - 1)));
  }
  // The static frame bound's assumptions (ucode/dtmf_frame_bound.h): the
  // largest count of each izhikevich_layer shift by a constant word, the
  // plan's (over both layers: NSH<word>), the spike window's events at the
  // plan's decimation, sparse packets as its mask asks, and the longest
  // command payload, the protocol's.
  for (int w : {4, 7, 9, 11, 13, 14, 15})
    sym("NSH" + std::to_string(w), std::max(neuron_block(p.neuron[0])[size_t(w)] & 63,
                                             neuron_block(p.neuron[1])[size_t(w)] & 63));
  // The events a spike window can hold: every neuron of both layers once a
  // frame of the window (decim_tax frames), at most MAXSPK
  // (longest_packet_bytes' rule).
  sym("SPKWIN", std::min<long>(p.max_spikes, 2L * T * p.decim_tax));
  // Whether the plan's mask asks for sparse taxel packets (their two passes
  // over every taxel).
  sym("SPARSE", (p.mask & kMaskSparse) ? 1 : 0);
  // Streaming: the polls of stream_cfg's wait for the chain's layers to
  // finish the last frame (its spike tail, dtmf_chain_spike_tail_clocks)
  // before new constants go in: one. The frame bound that admits a build
  // (ucode/dtmf_frame_bound.h: the control plane's bound, a command and the
  // chain's own clocks, tail included, within 70 % of the frame) holds each
  // frame's chain work inside its period, so by induction over the frames
  // the chain is idle when the next frame's setup reads it; the loop stays
  // for builds run slower than that. Without spikes the layers are off: no
  // header enters their event queue (rtl/dtmf_chain.v hq_push), so
  // layers_idle holds, and their init (nu_busy) is the boot's, which
  // stream_setup waits out.
  sym("STREAM_TAIL", 1);
  int payload = 0;
  for (const auto& c : kDtmfCommands) payload = std::max(payload, c.payload_bytes());
  sym("CMD_PAYLOAD", payload);
  sym("CF", 14), sym("TW", 10), sym("QUART", kQ);
  sym("SHL_Q", p.mag_shift == 0 ? 2 : 0), sym("SHR_Q", p.mag_shift == 0 ? 0 : 2 * p.mag_shift - 2);
  sym("GRND", p.taxel.recip_shift + 14);
  for (const DtmfIoEntry& e : kDtmfIoPorts) sym(e.symbol, e.value);  // the IO map
  for (const DtmfIoEntry& e : kDtmfEvents) sym(e.symbol, e.value);
  return im;
}

// dtmf_top's parameter overrides for a plan, its engine image and the
// $readmemh files of its microcode and constants (ucode/dtmf_ucode.h writes
// them).
inline std::vector<VerilogParam> dtmf_top_params(const DtmfTopPlan& p, const EngineImage& im,
                                                 const std::string& ucode_hex,
                                                 const std::string& krom_hex) {
  using dtmf_top_detail::clog2;
  auto i = [](long v) { return std::to_string(v); };
  std::vector<VerilogParam> v = {{"CLK_HZ", i(p.spec.clk_hz)},
          {"SAMPLE_HZ", i(std::lround(p.spec.sample_hz))},
          {"BAUD", i(p.spec.baud)},
          {"KS", i(p.ks)},
          {"N", i(p.N)},
          {"ACC_W", i(p.acc_w)},
          {"STEP", i(p.step)},
          {"IW", i(kDtmfImemBits)},
          {"IMEM_WORDS", i(kDtmfImemWords)},
          {"DW", i(std::max(4, clog2(im.dend)))},
          {"KW", i(std::max(1, clog2(long(im.krom.size()))))},
          {"OUT_DEPTH", i(p.out_depth)},
          {"ENGINE_FAST_SHIFT", i(p.spec.engine_fast_shift ? 1 : 0)},
          {"SDFT_LANES", i(p.spec.sdft_lanes)},
          {"NEURON_UNIT", i(p.spec.neuron_unit ? 1 : 0)},
          {"ADC_CLK_HZ", i(p.spec.adc_clk_hz)},
          {"UCODE_HEX", "\"" + ucode_hex + "\""},
          {"KROM_HEX", "\"" + krom_hex + "\""}};
  if (p.spec.sdft_fifo)  // (without, dtmf_top's default: none)
    v.insert(v.end() - 3, {"SDFT_FIFO", i(p.spec.sdft_fifo)});
  if (p.spec.datapath == DtmfDatapath::Streaming)  // rtl/dtmf_chain.v's sizes
    v.insert(v.end() - 3, {{"STREAM", "1"},
                           {"ROWS", i(p.R)},
                           {"COLS", i(p.C)},
                           {"MAG_SHIFT", i(p.mag_shift)},
                           {"MAX_SPIKES", i(p.max_spikes)}});
  if (p.spec.neuron_lanes)  // (without lanes dtmf_top's defaults, unused)
    v.insert(v.end() - 3, {{"NEURON_LANES", i(p.spec.neuron_lanes)},
                           {"NEURON_BITS", i(std::max(1, clog2(2L * p.T)))},
                           {"COLS", i(p.C)}});
  return v;
}

}  // namespace eskin::hls
