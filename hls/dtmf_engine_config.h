// Host-side, not synthesised (a *_config.h builder): the frame engine's view of a DTMF top plan
// (hls/dtmf_top_config.h) — the DMEM layout, the KROM words and the symbol
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
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "hls/dtmf_top_config.h"

namespace eskin::hls {

// IO ports of the frame engine in rtl/dtmf_top.v (reads / writes). The top
// decodes reads partially (bit 9: frame or register; bits 3:0: which
// register; with neuron lanes bit 12: a spike flag, bit 13: an event) and
// writes fully; the microcode uses only these addresses.
enum DtmfIoPort : uint16_t {
  kIoFrame = 0x000,      // r: frame token k: re at 2k, im at 2k + 1 (k = 0..KS-1)
  kIoFrameT = 0x200,     // r: t of the frame's newest sample
  kIoStatus = 0x201,     // r: bit 0 frame pending, bit 1 command available
  kIoCmd = 0x202,        // r: command FIFO head byte
  kIoOutFree = 0x203,    // r: bytes free in the output FIFO
  kIoAdcT = 0x204,       // r: the ADC sample counter now
  kIoAdcOvr = 0x205,     // r: ADC overruns (16-bit, saturating)
  kIoRxErr = 0x206,      // r: UART receive errors
  kIoCrcErr = 0x207,     // r: command frames with a bad CRC
  kIoFrmErr = 0x208,     // r: command frames with bad framing
  kIoFrameOvr = 0x209,   // r: frames lost because the engine was busy
  kIoSdftBusy = 0x20A,   // r: a DFT carrier write is pending
  kIoCmdOvf = 0x20B,     // r: command frames dropped: FIFO full
  kIoIzSpike = 0x20C,    // r: neuron unit: 1 when the last update spiked
  kIoIzV = 0x20D,        // r: neuron unit: v after the last update; w: v operand
  kIoIzU = 0x20E,        // r: neuron unit: U after the last update; w: U operand
  kIoOutByte = 0x200,    // w: one byte to the output FIFO
  kIoOutWord = 0x209,    // w: two bytes to it, bits 7:0 then 15:8 (OutFifoPort)
  kIoFrameDone = 0x201,  // w: release the frame buffer
  kIoCmdPop = 0x202,     // w: drop the command FIFO head byte
  kIoSdftK = 0x203,      // w: carrier index of the next DFT write, bit 8 = last
  kIoSdftInc = 0x204,    // w: its phase increment (starts the write)
  kIoClear = 0x205,      // w: clear the hardware counters
  kIoIzX = 0x206,        // w: neuron unit: the input x operand
  kIoIzGo = 0x207,       // w: neuron unit: the x_prev operand; starts the update
  kIoIzUGo = 0x208,      // w: neuron unit: the U operand; starts a level-input update a clock later
  kIoIzCfg = 0x220,      // w: neuron unit: constant word w of the layer block at 0x220 + w
  // Neuron lanes (NEURON_LANES: rtl/izhikevich_lanes.v, IzhikevichLanesPort below):
  kIoIzN = 0x20A,        // w: the next neuron to start or initialise; the event count restarts
  kIoIzXGo = 0x20B,      // w: that neuron's x: starts its update on the next lane
  kIoIzSV = 0x20C,       // w: v of the next initialisation
  kIoIzSU = 0x20F,       // w: U: initialises the neuron (v, U, x_prev 0, flag 0)
  kIoIzEvN = 0x20F,      // r: spike events since the last kIoIzN
  kIoIzFlag = 0x1000,    // r: at 0x1000 + C + n: neuron n's flag (bit 1), n - C's (2), n + C's (0)
  kIoIzEv = 0x2000,      // r: the neuron of event i at 0x2000 + i
};
// Engine events (the `wait` mask bits) of rtl/dtmf_top.v.
enum DtmfEvent : uint16_t {
  kEvFramePending = 1,
  kEvCmdAvail = 2,
  kEvIzDone = 4,  // the neuron unit holds the results of its last update (lanes: all written back)
};

constexpr int kNeuronBlock = 20;  // words of constants per layer (NCS)
constexpr int kDtmfImemBits = 11;     // microcode address bits
constexpr int kDtmfImemWords = 1280;  // microcode words: 10 EBRs (256 x 16 each)

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

// Clocks of one update of the neuron unit (rtl/izhikevich_layer.v): its
// results come kIzhikevichUnitClocks edges after the handshake edge, the
// end of the clock c of the write that starts it, so they show, and raise
// kEvIzDone, from clock c + kIzhikevichUnitClocks + 1 on; until then the
// ports show the previous update's results. The unit takes the next start
// from that clock on (back to back, one update per 14 clocks); before
// that a start is ignored (busy; the port model below throws on one).
// (Until 2026-11-27 the model showed the results a clock early, from
// c + 13: no loop read them there, but a wait for them ended a clock
// before the RTL's; tests/rtl/izhikevich_lanes_test.cpp measures it.)
constexpr int kIzhikevichUnitClocks = 13;

// rtl/dtmf_top.v's output FIFO write ports as the engine sees them, for the
// C++ models of the top. kIoOutByte writes one byte; kIoOutWord two, bits
// 7:0 in the clock of the `out` and bits 15:8 from a register in the next
// clock, so that clock must not write the FIFO (the top would lose a
// byte): write() throws on that, so every microcode test checks it.
struct OutFifoPort {
  uint64_t held_clock = ~uint64_t(0);  // the clock that writes a word's second byte
  // An IO write at `clock`; false when `a` is not a FIFO port. `out` (may
  // be null) gets the bytes.
  bool write(uint16_t a, uint32_t d, uint64_t clock, std::vector<uint8_t>* out) {
    if (a != kIoOutByte && a != kIoOutWord) return false;
    if (clock == held_clock)
      throw std::logic_error("the microcode wrote the output FIFO in clock " +
                             std::to_string(clock) +
                             ", which writes the second byte of the word written before it");
    if (out) out->push_back(uint8_t(d));
    if (a == kIoOutWord) {
      if (out) out->push_back(uint8_t(d >> 8));
      held_clock = clock + 1;
    }
    return true;
  }
};

// rtl/dtmf_top.v's neuron unit ports (NEURON_UNIT = 1) as the engine sees
// them, for the C++ models of the top (its IO objects): constant words as
// the microcode keeps them in DMEM, operands, and the update of
// hls/izhikevich_layer.h (IzhikevichLayer::update for one neuron) when the
// last operand, x_prev, is written.
struct IzhikevichUnitPort {
  bool present = false;  // the plan's neuron_unit: without it the ports are not decoded
  uint32_t cfg[32] = {};
  int32_t x = 0, v = 0, u = 0;
  struct Results {
    bool spike = false;
    int32_t v = 0, u = 0;  // x_prev' is the microcode's (nu_layer)
  };
  Results shown, next;  // the ports until done_clock, and from it on
  uint64_t done_clock = 0, ready_clock = 0;  // results shown; the next start taken
  uint64_t cfg_clock = 0;  // a constant word lands at or after the update's last edge

  // The layer's constants from the words (neuron_block's inverse; shift
  // counts: the low 6 bits, as the engine's shifts take them; the gain
  // shifts: left when word 14 is set).
  IzhikevichConfig config() const {
    IzhikevichConfig c;
    c.v_reset = int32_t(cfg[2]), c.u_jump = int32_t(cfg[3]);
    c.u_frac = uint8_t(22 + (cfg[4] & 63)), c.c_const = int32_t(cfg[5]);
    c.m2 = int16_t(cfg[6]), c.s2 = uint8_t(cfg[7] & 63);
    c.m3 = int16_t(cfg[8]), c.s3 = uint8_t(cfg[9] & 63);
    c.m4 = int16_t(cfg[10]), c.s4 = uint8_t(cfg[11] & 63);
    c.gain = int16_t(cfg[12]);
    c.gain_shift = int8_t((cfg[14] & 63) != 0 ? -int(cfg[14] & 63) : int(cfg[13] & 63));
    c.x_shift = uint8_t(cfg[15] & 63), c.input_change = cfg[16] != 0;
    return c;
  }
  // An IO write at `clock`; false when `a` is not a unit port. Throws
  // std::logic_error on a constant word written while an update runs (the
  // unit reads its constants during the update: rtl/izhikevich_layer.v,
  // "Configuration", so the microcode must write them between updates) and
  // on a start while an update runs (the unit would ignore it).
  bool write(uint16_t a, uint32_t d, uint64_t clock) {
    if (!present) return false;
    if ((a & 0xFFE0) == kIoIzCfg) {
      if (clock < cfg_clock)
        throw std::logic_error("the microcode wrote the neuron unit's constant word " +
                               std::to_string(a & 31) + " in clock " + std::to_string(clock) +
                               ", while an update ran (until clock " +
                               std::to_string(cfg_clock) + ")");
      return cfg[a & 31] = d, true;
    }
    switch (a) {
      case kIoIzX: x = int32_t(d); return true;
      case kIoIzV: v = int32_t(d); return true;
      case kIoIzU: u = int32_t(d); return true;
      case kIoIzGo: return start(int32_t(d), clock), true;
      case kIoIzUGo:
        // rtl/dtmf_top.v registers this start, so that the unit takes U from
        // its operand register: it starts in the next clock, with no x_prev
        // (the bus's next word), which only a level-input update ignores.
        if (config().input_change)
          throw std::logic_error("the microcode started the neuron unit by its U write in clock " +
                                 std::to_string(clock) +
                                 " with input_change set: that start has no x_prev");
        return u = int32_t(d), start(0, clock + 1), true;
      default: return false;
    }
  }
  // The update with x_prev, started by a write in `clock`.
  void start(int32_t x_prev, uint64_t clock) {
    // The unit ignores a start while busy; no microcode may rely on that
    // (nu_layer's level loop counts its clocks instead of waiting).
    if (clock < ready_clock)
      throw std::logic_error("the microcode started the neuron unit in clock " +
                             std::to_string(clock) + ", before it takes a start (clock " +
                             std::to_string(ready_clock) + ")");
    shown = next;
    IzhikevichLayer<1> one(config());
    one.set_state(0, v, u, x_prev);
    next.spike = one.update(0, x);
    next.v = one.v(0), next.u = one.U(0);
    cfg_clock = clock + kIzhikevichUnitClocks;  // its write lands at the last edge: safe
    done_clock = cfg_clock + 1;
    ready_clock = done_clock;
  }
  // An IO read in `clock` (the engine's cycle A); false when `a` is not a
  // unit port.
  bool read(uint16_t a, uint32_t& d, uint64_t clock) const {
    if (!present) return false;
    const Results& r = clock >= done_clock ? next : shown;
    switch (a) {
      case kIoIzSpike: d = r.spike ? 1u : 0u; return true;
      case kIoIzV: d = uint32_t(r.v); return true;
      case kIoIzU: d = uint32_t(r.u); return true;
      default: return false;
    }
  }
  uint16_t events(uint64_t clock) const {
    return present && clock >= done_clock ? kEvIzDone : 0;
  }
};

// rtl/izhikevich_lanes.v's ports as the frame engine sees them in
// rtl/dtmf_top.v (NEURON_LANES), for the C++ models of the top (beside
// IzhikevichUnitPort): the clock-exact spec of the lanes' timing, and the
// checks of the contract the microcode must keep (each throws
// std::logic_error naming the clock).
//
// The lanes keep v, U and x_prev of every neuron n (layer l's neuron i is
// l T + i), its spike flag and the layer's spike events; the engine writes
// each neuron's x (kIoIzXGo), which starts its update on the next lane,
// and reads the flags a column of three at a time (kIoIzFlag: a taxel's
// flag with those of the rows above and below, for synapse_weights).
// The update is hls/izhikevich_layer.h's IzhikevichLayer::update (whose
// header states the Q formats, rounding and saturation); nothing here is
// arithmetic of its own.
//
// Timing, from the clock c of the x write (its `out`'s cycle B): the lane
// starts in c + 1; the results are written back at the end of clock
// c + kLaneWriteBack (15); a read of the flag in that clock is undefined in
// the block RAM (throws), earlier ones give the old flag, later ones the new.
// Events, their count and kEvIzDone (all written back) from clock c +
// kLaneWriteBack + 1. A lane takes its next start kLaneRate clocks after
// its last, so the same lane's x writes must be kLaneRate apart.
struct IzhikevichLanesPort {
  // A lane's results show in clock c + 1 + kIzhikevichUnitClocks + 1 (its
  // start is registered: clock c + 1), and are written back at its end.
  static constexpr int kLaneWriteBack = kIzhikevichUnitClocks + 2;
  static constexpr int kLaneRate = kIzhikevichUnitClocks + 1;       // a unit's start to start

  int lanes = 0;          // the plan's neuron_lanes: 0, the ports are not decoded
  int flag_offset = 0;    // the skin's columns C: F(C + n) is neuron n's flag
  IzhikevichUnitPort unit;  // the constant words and their decoding (one copy in every lane)

  struct Neuron {
    int32_t v = 0, u = 0, x_prev = 0;
    bool flag = false, old_flag = false;
    uint64_t written = 0;  // the clock whose end wrote v .. flag
  };
  std::vector<Neuron> neurons;
  std::vector<uint32_t> spiked;  // the layer's spike events: its spiking neurons, in order
  uint32_t idx = 0;              // the next neuron to start or initialise
  int32_t init_v = 0;
  int next_lane = 0;
  std::vector<uint64_t> lane_ready;  // the first clock each lane takes a start
  uint64_t idle_clock = 0;           // all written back from this clock on

  // n neurons (2 T), the skin's columns, `count` lanes (0: absent).
  void configure(int count, int n, int columns) {
    lanes = count, flag_offset = columns;
    neurons.assign(size_t(n), Neuron{});
    lane_ready.assign(size_t(count), 0);
  }

  bool write(uint16_t a, uint32_t d, uint64_t clock) {
    if (lanes == 0) return false;
    if ((a & 0xFFE0) == kIoIzCfg) {
      busy_check("wrote the neurons' constant word " + std::to_string(a & 31), clock);
      unit.cfg[a & 31] = d;
      return true;
    }
    switch (a) {
      case kIoIzN:
        busy_check("set the next neuron", clock);
        idx = d, spiked.clear();
        return true;
      case kIoIzXGo: return start(int32_t(d), clock), true;
      case kIoIzSV: init_v = int32_t(d); return true;
      case kIoIzSU: {
        busy_check("initialised neuron " + std::to_string(idx), clock);
        Neuron& s = at(idx, clock);
        s.old_flag = s.flag;
        s = Neuron{init_v, int32_t(d), 0, false, s.old_flag, clock};
        ++idx;
        return true;
      }
      default: return false;
    }
  }

  bool read(uint16_t a, uint32_t& d, uint64_t clock) const {
    if (lanes == 0) return false;
    if ((a & 0xF000) == kIoIzFlag) {  // a column: F(f - C) << 2 | F(f) << 1 | F(f + C)
      const int f = int(a & 0x0FFF);
      d = flag(f - flag_offset, clock) << 2 | flag(f, clock) << 1 | flag(f + flag_offset, clock);
      return true;
    }
    if ((a & 0xF000) == kIoIzEv || a == kIoIzEvN) {
      if (clock < idle_clock)
        throw std::logic_error("the microcode read the spike events in clock " +
                               std::to_string(clock) + ", before the updates end (clock " +
                               std::to_string(idle_clock) + ")");
      if (a == kIoIzEvN) return d = uint32_t(spiked.size()), true;
      const size_t i = a & 0x0FFF;
      if (i >= spiked.size())
        throw std::logic_error("the microcode read spike event " + std::to_string(i) + " of " +
                               std::to_string(spiked.size()) + " in clock " +
                               std::to_string(clock));
      return d = spiked[i], true;
    }
    return false;
  }

  uint16_t events(uint64_t clock) const {
    return lanes != 0 && clock >= idle_clock ? kEvIzDone : 0;
  }

 private:
  // F(f): neuron f - C's flag as a read in `clock` sees it; 0 where no
  // neuron's flag is (the row above layer 0, past the last layer).
  uint32_t flag(int f, uint64_t clock) const {
    const int n = f - flag_offset;
    if (n < 0 || size_t(n) >= neurons.size()) return 0;
    const Neuron& s = neurons[size_t(n)];
    if (clock == s.written && s.written != 0)
      throw std::logic_error("the microcode read neuron " + std::to_string(n) +
                             "'s spike flag in clock " + std::to_string(clock) +
                             ", the clock that writes it");
    return (clock > s.written ? s.flag : s.old_flag) ? 1u : 0u;
  }
  Neuron& at(uint32_t n, uint64_t clock) {
    if (n >= neurons.size())
      throw std::logic_error("the microcode addressed neuron " + std::to_string(n) + " of " +
                             std::to_string(neurons.size()) + " in clock " +
                             std::to_string(clock));
    return neurons[n];
  }
  void busy_check(const std::string& what, uint64_t clock) const {
    if (clock < idle_clock)
      throw std::logic_error("the microcode " + what + " in clock " + std::to_string(clock) +
                             ", while the neuron lanes ran (until clock " +
                             std::to_string(idle_clock) + ")");
  }
  void start(int32_t x, uint64_t clock) {
    uint64_t& ready = lane_ready[size_t(next_lane)];
    if (clock + 1 < ready)
      throw std::logic_error("the microcode started neuron " + std::to_string(idx) +
                             " in clock " + std::to_string(clock) + " on lane " +
                             std::to_string(next_lane) + ", which takes a start from clock " +
                             std::to_string(ready) + " (the write from clock " +
                             std::to_string(ready - 1) + ")");
    Neuron& s = at(idx, clock);
    IzhikevichLayer<1> one(unit.config());
    one.set_state(0, s.v, s.u, s.x_prev);
    const bool spike = one.update(0, x);
    s.old_flag = s.flag;
    s.v = one.v(0), s.u = one.U(0), s.x_prev = one.x_prev(0), s.flag = spike;
    s.written = clock + kLaneWriteBack;
    if (spike) spiked.push_back(idx);
    ready = clock + 1 + kLaneRate;
    next_lane = (next_lane + 1) % lanes;
    idle_clock = s.written + 1;
    ++idx;
  }
};

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
  alloc("DECIM", 3), put(p.decim_amp), put(p.decim_tax), put(1000);
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

  // ---- state ----
  const int lk = p.lookback * K;
  alloc("PHASE", 2 * K), alloc("HIST", lk), alloc("HEAD", 1), alloc("REM", K);
  alloc("PL", K), alloc("NPL", 1), alloc("SITE", T), alloc("MAG", K);
  alloc("ROOT", R), alloc("CRT", C);  // line_roots: rows, then columns for the taxel loop
  alloc("G", T);
  if (!p.spec.neuron_lanes) {  // the lanes keep the neurons' state and flags themselves
    alloc("X2IN", T);          // layer 1's input: neuron_unit needs X2IN = G + T
    alloc("NV", 2 * T), alloc("NU", 2 * T), alloc("NXP", 2 * T);  // neuron l T + i
    alloc("SZ", C);                  // zero, never written: synapse_weights' row above row 0
    alloc("S0", T), alloc("S1", T);  // and S1 = S0 + T
  }
  alloc("SWT", 512);  // synapse_weights: the sum for each 3x3 spike pattern (its 9 bits)
  alloc("BV", dim + 2), alloc("Y", 2 * K), alloc("SPK", 2 * p.max_spikes), alloc("CB", 9);
  alloc("AMPC", 3), alloc("SEL", 3), alloc("SEND", 3);  // frame counts per stream (amp, tax, status)
  for (const char* n :
       {"VT", "TPASS", "REC", "SPKOPEN", "SPKT0", "SPKN", "SPKDROP", "PKTDROP",
        "ACC", "REJ", "LRT", "LRR", "LRS", "CTYPE", "CSEQ", "CLEN", "PT", "PTT", "PLEN", "TLO",
        "TIDX", "TS", "TC", "TQD", "TOFF", "TV", "TROW", "TACC", "TRI", "TR", "TCL",
        "TBR", "TBC", "TRR", "TRC", "TOK", "TRW", "TB", "TB2", "SEB", "NX", "ND", "NXS",
        "NJ", "NU22", "NW", "NSQ", "NC2", "NVH", "NC3", "NUN", "SWMASK", "SWD", "SWM", "SWI",
        "NDROP"})
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
  kc("KC_M32", 0xFFFFFFFFll), kc("KC_2P31", 0x80000000ll), kc("KC_S16MIN", -32768);
  kc("KC_S16MAX", 32767), kc("KC_S24MIN", -(1 << 23)), kc("KC_S24MAX", (1 << 23) - 1);
  kc("KC_I32MIN", INT32_MIN), kc("KC_I32MAX", INT32_MAX), kc("KC_UMIN", izh::kUMin);
  kc("KC_UMAX", izh::kUMax), kc("KC_VMIN", izh::kVMin), kc("KC_VPEAK", izh::kVPeak);
  kc("KC_WOFF", izh::kWOffset), kc("KC_RECIP", p.taxel.recip), kc("KC_C", C);
  kc("KC_NCS", kNeuronBlock), kc("KC_LAYER1", 1 << 16), kc("KC_MASKRES", 0xE0);
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
  static const int kCmdLen[9] = {5, 3, 5, 1, 3, 0, 0, 3, 4};  // payload bytes, 0x81 .. 0x89
  table("KC_CLEN", [](int t) { return kCmdLen[t]; }, 9);
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
                            im.symbol("PKTDROP"), io | kIoAdcOvr,
                            io | kIoRxErr, io | kIoFrameOvr, im.symbol("SPKDROP"), io | kIoCmdOvf};
  table("KC_STAT", [&stat](int f) { return stat[f]; }, 14);
  kc("KC_BIT15", 0x8000), kc("KC_BIT14", 0x4000), kc("KC_LOW15", 0x3FFF);
  sym("SINE", int64_t(im.krom.size()));
  if (demix)
    for (int e = 0; e <= kQ; e += 2)
      put(uint32_t(p.demix.qsin[size_t(e)] & 0xFFFF) |
          (e + 1 <= kQ ? uint32_t(p.demix.qsin[size_t(e + 1)] & 0xFFFF) << 16 : 0u));

  // ---- sizes, flags, arithmetic ----
  sym("K", K), sym("KS", ks), sym("R", R), sym("C", C), sym("T", T), sym("DIM", dim);
  sym("STEP", p.step), sym("MAXSPK", p.max_spikes), sym("LK", lk), sym("NCS", kNeuronBlock);
  sym("DEMIX", demix), sym("GHOST", p.spec.ghost), sym("NEURONS", p.spec.spikes);
  sym("NEURON_UNIT", p.spec.neuron_unit), sym("EV_IZ_DONE", kEvIzDone);
  sym("NEURON_LANES", p.spec.neuron_lanes);
  // Layer 0's spike flags for synapse_weights: S0 in DMEM (SZ, zeros, the
  // row above it; S1 below), or the lanes' columns of three at FLAGS + n.
  if (p.spec.neuron_lanes) sym("FLAGS", kIoIzFlag + C);
  sym("CF", 14), sym("TW", 10), sym("QUART", kQ);
  sym("SHL_Q", p.mag_shift == 0 ? 2 : 0), sym("SHR_Q", p.mag_shift == 0 ? 0 : 2 * p.mag_shift - 2);
  sym("GRND", p.taxel.recip_shift + 14);
  for (auto [n, v] : std::initializer_list<std::pair<const char*, int>>{
           {"IO_FRAME", kIoFrame},     {"IO_FRAME_T", kIoFrameT},   {"IO_STATUS", kIoStatus},
           {"IO_CMD", kIoCmd},         {"IO_OUT_FREE", kIoOutFree}, {"IO_ADC_T", kIoAdcT},
           {"IO_ADC_OVR", kIoAdcOvr},  {"IO_RX_ERR", kIoRxErr},     {"IO_CRC_ERR", kIoCrcErr},
           {"IO_FRM_ERR", kIoFrmErr},  {"IO_FRAME_OVR", kIoFrameOvr},
           {"IO_SDFT_BUSY", kIoSdftBusy}, {"IO_CMD_OVF", kIoCmdOvf},
           {"IO_OUT_BYTE", kIoOutByte}, {"IO_OUT_WORD", kIoOutWord}, {"IO_FRAME_DONE", kIoFrameDone},
           {"IO_CMD_POP", kIoCmdPop},  {"IO_SDFT_K", kIoSdftK},     {"IO_SDFT_INC", kIoSdftInc},
           {"IO_CLEAR", kIoClear},     {"IO_IZ_X", kIoIzX},         {"IO_IZ_V", kIoIzV},
           {"IO_IZ_U", kIoIzU},        {"IO_IZ_GO", kIoIzGo},       {"IO_IZ_UGO", kIoIzUGo},
           {"IO_IZ_CFG", kIoIzCfg},    {"IO_IZ_SPIKE", kIoIzSpike}, {"IO_IZ_N", kIoIzN},
           {"IO_IZ_XGO", kIoIzXGo},    {"IO_IZ_SV", kIoIzSV},       {"IO_IZ_SU", kIoIzSU},
           {"IO_IZ_EVN", kIoIzEvN},    {"IO_IZ_EV", kIoIzEv}})
    sym(n, v);
  return im;
}

// dtmf_top's parameter overrides for a plan, its engine image and the
// $readmemh files of its microcode and constants (hls/dtmf_ucode.h writes
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
  if (p.spec.neuron_lanes)  // (without lanes dtmf_top's defaults, unused)
    v.insert(v.end() - 3, {{"NEURON_LANES", i(p.spec.neuron_lanes)},
                           {"NEURON_BITS", i(std::max(1, clog2(2L * p.T)))},
                           {"COLS", i(p.C)}});
  return v;
}

}  // namespace eskin::hls
