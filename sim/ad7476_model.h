// Cycle-accurate pin model of the AD7476A 12-bit, 1 MSPS serial ADC (two of
// them on a Digilent Pmod AD1) for Verilator testbenches. Header-only.
//
// Interface behaviour (AD7476A datasheet, serial interface section):
//  * CS falling samples the input (the next code of the supplied vector) and
//    starts the conversion; SDATA leaves three-state within t3 and shows the
//    first of 4 leading zeros.
//  * Each SCLK falling edge while CS is low shifts out the next bit: 3 more
//    zeros, then DB11..DB0 MSB first. The old bit is held for t7 after the
//    edge, the new one is valid t4 after it; in between SDATA is undefined.
//    The 16th falling edge ends the conversion, SDATA returns to three-state
//    (between t8 min and t8 max after it). DB0 is valid until t7 after the
//    16th edge, so a master may sample on falling edges (bit k at edge k).
//  * After the 13th falling edge the track-and-hold returns to track at the
//    next SCLK rising edge; it needs tACQ before the next CS falling edge.
// Wherever the datasheet leaves SDATA undefined (three-state, between hold
// and access time), sdata() returns a pseudo-random level, so a master that
// samples there reads garbage and its samples mismatch.
//
// The path between the master's flip-flops and the ADC (Ad7476Board): its
// clock edge reaches CS and SCLK at the ADC out_ns + trace_ns later (clock
// to out, output pad, board), and SDATA reaches its capture flip-flop
// trace_ns + in_ns after the ADC drives it (board, input pad, routing,
// setup). So at 20 MHz SCLK a bit is valid at the flip-flop from tSCLK -
// (t4 - round trip) before the edge that drives the next SCLK fall until
// t7 + round trip after it: the datasheet's 10 ns setup budget (tSCLK -
// t4) shrinks by the round trip, which the master must sample against.
// kRoundTripMinNs / kRoundTripMaxNs are the range rtl/adc_ad7476.v is
// built for (SDATA_RT_MIN_NS, SDATA_RT_MAX_NS); Ad7476Board::fastest() and
// slowest() are boards at its two ends, the default one in between.
//
// Timing checks (datasheet Table 4, VDD <= 3.3 V), each recorded as a
// violation message that names the parameter:
//   fSCLK <= 20 MHz (tSCLK >= 50 ns) and >= 10 kHz, SCLK low/high (t5, t6)
//   >= 0.4 tSCLK, t1 CS high >= 10 ns, t2 CS falling to first SCLK falling
//   >= 10 ns, exactly 16 SCLK falling edges per CS low (fewer aborts the
//   conversion), tQUIET >= 50 ns from bus relinquish (16th falling edge + t8
//   max) to the next CS falling, tACQ >= 250 ns, and running out of samples.
// Usage per clock edge at time t (ns, non-decreasing): first `sdata(t)`
// (the level the master's flip-flops see just before the edge), then, after
// the master has updated its outputs, `drive(t, cs_n, sclk)`; a master that
// samples on the falling clock edge asks `sdata(t + half period)` after
// drive(t). Times are the master's (its flip-flops' clock edges); the
// board's delays are added here.
#pragma once

#include <cstdint>
#include <cstdio>
#include <deque>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace eskin::sim {

struct Ad7476Timing {  // ns
  double tsclk_min = 50.0;     // 1 / fSCLK max (20 MHz)
  double tsclk_max = 100000.0; // 1 / fSCLK min (10 kHz)
  double t1_min = 10.0;        // minimum CS high pulse width
  double t2_min = 10.0;        // CS falling to SCLK falling setup
  double t3_max = 22.0;        // CS falling to SDATA out of three-state
  double t4_max = 40.0;        // SCLK falling to data valid (access time)
  double t56_frac = 0.4;       // SCLK low (t5) and high (t6) >= 0.4 tSCLK
  double t7_min = 10.0;        // data hold after SCLK falling
  double t8_min = 10.0;        // 16th SCLK falling to three-state, min (= t7)
  double t8_max = 36.0;        // ... max (bus relinquish)
  double tquiet_min = 50.0;    // bus relinquish to next CS falling
  double tacq_min = 250.0;     // track-and-hold acquisition
};

// The range of SCLK-out-to-SDATA-in round trips rtl/adc_ad7476.v is built
// for (its SDATA_RT_MIN_NS, SDATA_RT_MAX_NS defaults).
constexpr double kRoundTripMinNs = 5.0, kRoundTripMaxNs = 15.0;

struct Ad7476Board {  // ns, each >= 0
  double out_ns = 6.0;    // master's clock edge to CS / SCLK at its pins (clock to out, pad)
  double trace_ns = 0.5;  // board and cable, each way
  double in_ns = 3.0;     // SDATA pin to the capture flip-flop (pad, routing, setup)
  double round_trip() const { return out_ns + 2 * trace_ns + in_ns; }
  // Both ends of the range above: fast pads on a short cable, slow pads
  // (DRIVE=4 into the Pmod's load) on a longer one.
  static Ad7476Board fastest() { return {2.5, 0.25, 2.0}; }
  static Ad7476Board slowest() { return {9.0, 1.0, 4.0}; }
};

class Ad7476Model {
 public:
  explicit Ad7476Model(std::vector<uint16_t> codes, Ad7476Timing timing = {},
                       uint64_t seed = 1, Ad7476Board board = {})
      : codes_(std::move(codes)), tm_(timing), board_(board), rng_(seed) {}

  // SDATA at the master's capture flip-flop at time t: the level the ADC
  // drove trace_ns + in_ns earlier.
  int sdata(double t) {
    const double ta = t - board_.trace_ns - board_.in_ns;
    while (wave_.size() > 1 && wave_[1].from <= ta) wave_.pop_front();  // queries never go back
    if (wave_.empty() || wave_[0].from > ta || wave_[0].level < 0)
      return int(rng_() & 1);  // three-state or changing: undefined
    return wave_[0].level;
  }

  // Pin levels after the master's update at time t; the ADC sees them
  // out_ns + trace_ns later.
  void drive(double t, bool cs_n, bool sclk) {
    const double ta = t + board_.out_ns + board_.trace_ns;
    if (!cs_n_ && cs_n) cs_rise(ta);
    if (cs_n_ && !cs_n) cs_fall(ta);
    cs_n_ = cs_n;
    if (sclk_ && !sclk) sclk_fall(ta);
    if (!sclk_ && sclk) sclk_rise(ta);
    sclk_ = sclk;
  }

  const std::vector<std::string>& violations() const { return messages_; }
  size_t violation_count() const { return violation_count_; }
  size_t conversions() const { return conversions_; }  // completed (16 clocks)
  size_t samples_taken() const { return next_; }

 private:
  static constexpr double kNever = -std::numeric_limits<double>::infinity();

  void violate(double t, const char* param, double value, const char* rel, double limit) {
    ++violation_count_;
    if (messages_.size() >= 50) return;
    char buf[200];
    std::snprintf(buf, sizeof buf, "%s = %.2f ns %s %.2f ns (at t = %.1f ns)", param, value,
                  rel, limit, t);
    messages_.push_back(buf);
  }
  void note(const std::string& what) {
    ++violation_count_;
    if (messages_.size() < 50) messages_.push_back(what);
  }

  // SDATA at the ADC's pin from time `from` on: a bit, or -1 (undefined).
  // A new level replaces every later one already planned.
  void level_from(double from, int level) {
    while (!wave_.empty() && wave_.back().from >= from) wave_.pop_back();
    wave_.push_back({from, level});
  }
  int level_at(double ta) const {
    int v = -1;
    for (const Level& l : wave_)
      if (l.from <= ta) v = l.level;
    return v;
  }

  void cs_fall(double t) {
    if (last_cs_rise_ != kNever && t - last_cs_rise_ < tm_.t1_min)
      violate(t, "t1 (CS high pulse width)", t - last_cs_rise_, "<", tm_.t1_min);
    if (relinquish_ != kNever && t - relinquish_ < tm_.tquiet_min)
      violate(t, "tQUIET (bus relinquish to CS falling)", t - relinquish_, "<", tm_.tquiet_min);
    if (track_from_ != kNever && t - track_from_ < tm_.tacq_min)
      violate(t, "tACQ (track-and-hold acquisition)", t - track_from_, "<", tm_.tacq_min);
    uint16_t code = 0;
    if (next_ < codes_.size()) {
      code = codes_[next_] & 0x0FFF;
    } else {
      note("sample vector exhausted: more conversions than supplied codes");
    }
    ++next_;
    word_ = code;  // 16-bit frame: 4 leading zeros then DB11..DB0
    falls_ = 0;
    cs_fall_ = t;
    last_fall_ = last_rise_ = kNever;
    track_from_ = kNever;
    level_from(t, -1);              // leaving three-state
    level_from(t + tm_.t3_max, 0);  // the first leading zero
  }

  void cs_rise(double t) {
    last_cs_rise_ = t;
    if (falls_ < 16) {
      note("CS rose after " + std::to_string(falls_) +
           " SCLK falling edges: tCONVERT needs 16 SCLK cycles (conversion aborted)");
      relinquish_ = t + tm_.t8_max;
      track_from_ = t;
    }
    level_from(t, -1);  // three-state
  }

  void sclk_fall(double t) {
    if (cs_n_) return;
    ++falls_;
    if (falls_ == 1) {
      if (t - cs_fall_ < tm_.t2_min)
        violate(t, "t2 (CS to SCLK setup)", t - cs_fall_, "<", tm_.t2_min);
    } else {
      const double period = t - last_fall_;
      if (period < tm_.tsclk_min)
        violate(t, "tSCLK (fSCLK max 20 MHz)", period, "<", tm_.tsclk_min);
      if (period > tm_.tsclk_max)
        violate(t, "tSCLK (fSCLK min 10 kHz)", period, ">", tm_.tsclk_max);
      if (last_rise_ > last_fall_) {
        if (last_rise_ - last_fall_ < tm_.t56_frac * period)
          violate(t, "t5 (SCLK low pulse width, 0.4 tSCLK)", last_rise_ - last_fall_, "<",
                  tm_.t56_frac * period);
        if (t - last_rise_ < tm_.t56_frac * period)
          violate(t, "t6 (SCLK high pulse width, 0.4 tSCLK)", t - last_rise_, "<",
                  tm_.t56_frac * period);
      }
    }
    last_fall_ = t;
    if (falls_ > 16) {
      note("more than 16 SCLK falling edges while CS low (falling edge " +
           std::to_string(falls_) + ")");
      return;
    }
    // The current bit stays for t7 if it was valid by now (t8 min after
    // the 16th edge), then SDATA changes: the next bit from t4 on, or
    // three-state after the 16th edge.
    const int now = level_at(t);
    level_from(t, now);
    level_from(t + (falls_ == 16 ? tm_.t8_min : tm_.t7_min), -1);
    if (falls_ < 16) {
      level_from(t + tm_.t4_max, (word_ >> (15 - falls_)) & 1);
    } else {
      relinquish_ = t + tm_.t8_max;
      ++conversions_;
    }
  }

  void sclk_rise(double t) {
    if (cs_n_) return;
    last_rise_ = t;
    if (falls_ == 13) track_from_ = t;  // back to track (datasheet point B)
  }

  struct Level {
    double from;
    int level;  // 0, 1, or -1: undefined
  };

  std::vector<uint16_t> codes_;
  Ad7476Timing tm_;
  Ad7476Board board_;
  std::mt19937_64 rng_;
  std::deque<Level> wave_;  // SDATA at the ADC's pin, in time order
  size_t next_ = 0, conversions_ = 0, violation_count_ = 0;
  std::vector<std::string> messages_;

  bool cs_n_ = true, sclk_ = true;
  int falls_ = 0;
  uint16_t word_ = 0;
  double cs_fall_ = kNever, last_cs_rise_ = kNever, last_fall_ = kNever, last_rise_ = kNever;
  double relinquish_ = kNever, track_from_ = kNever;
};

}  // namespace eskin::sim
