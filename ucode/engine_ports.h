// C++ models of rtl/dtmf_top.v's IO ports as the frame engine sees them:
// the output FIFO's write ports, the neuron unit and the neuron lanes.
// Each is the clock-exact spec of its port's timing and checks the
// contract the microcode must keep (a violation throws std::logic_error
// naming the clock). The one model of the whole IO bus that uses them is
// ucode/dtmf_top_bus.h.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "hls/izhikevich_layer.h"
#include "ucode/dtmf_io_map.h"

namespace eskin::hls {

// Clocks of one update of the neuron unit (rtl/izhikevich_layer.v): its
// results come kIzhikevichUnitClocks edges after the handshake edge, the
// end of the clock c of the write that starts it, so they show, and raise
// kEvIzDone, from clock c + kIzhikevichUnitClocks + 1 on; until then the
// ports show the previous update's results. The unit takes the next start
// from that clock on (back to back, one update per 14 clocks); before
// that a start is ignored (busy; the port model below throws on one).
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

}  // namespace eskin::hls
