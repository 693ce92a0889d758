// adc_ad7476: the clock-exact C++ model of rtl/adc_ad7476.v (the SPI
// master of NCH AD7476A sharing CS and SCLK), at its pins: a part of the
// `cycle` fidelity level (docs/vboard.md). The sample point (LAG) and every
// count are derived from the parameters as the RTL derives them; the
// illegal sets the RTL refuses at elaboration are refused here. cs_n, sclk
// and the output port are registers. Held to the Verilated RTL clock by
// clock, at both sample points, in tests/rtl/adc_ad7476_test.cpp.
#pragma once

#include <cstdint>
#include <stdexcept>

namespace eskin::cycle {

class AdcAd7476 {
 public:
  AdcAd7476(int64_t clk_hz, int64_t sample_hz, int sclk_div, int nch = 1,
            int rt_min_ns = 5, int rt_max_ns = 15, int margin_ps = 1000)
      : h_(sclk_div), nch_(nch) {
    if (nch > kMaxCh) throw std::invalid_argument("AdcAd7476: at most 4 channels");
    period_ = (clk_hz + sample_hz / 2) / sample_hz;
    const int64_t clk_khz = clk_hz / 1000;
    const auto clamp = [](int64_t v) { return v > 2000 ? 2000 : v; };
    const int64_t quiet = clamp(period_ - 31 * h_), acq = clamp(period_ - 28 * h_),
                  t1 = clamp(period_ - 32 * h_);
    const int64_t t_ps = 1000000000 / (clk_khz < 1 ? 1 : clk_khz);
    const int64_t w_lo = int64_t(rt_max_ns) * 1000 + 40000 - 2 * h_ * t_ps;
    const int64_t w_hi = int64_t(rt_min_ns) * 1000 + 10000;
    const auto room = [&](int64_t d) { return d - w_lo < w_hi - d ? d - w_lo : w_hi - d; };
    lag_ = room(0) >= margin_ps                                              ? 0
           : room(t_ps / 2) >= margin_ps && room(t_ps / 2) >= room(t_ps) ? 1
           : room(t_ps) >= margin_ps                                      ? 2
                                                                          : 3;
    if (nch < 1 || h_ < 1 || sample_hz < 1 || clk_hz > 40000000LL * h_ || lag_ > 2 ||
        rt_min_ns < 0 || rt_max_ns < rt_min_ns || clk_hz < 20000LL * h_ ||
        int64_t(h_) * 100000 < clk_khz || quiet * 1000000 < clk_khz * 86 ||
        acq * 1000000 < clk_khz * 250 || t1 < 1 || t1 * 1000000 < clk_khz * 10)
      throw std::invalid_argument("AdcAd7476: a parameter set rtl/adc_ad7476.v refuses");
  }

  int lag() const { return lag_; }
  int64_t period() const { return period_; }
  bool cs_n() const { return cs_n_; }
  bool sclk() const { return sclk_; }
  bool m_valid() const { return m_valid_; }
  // Channel c's 12-bit code (m_data[12c +: 12]).
  uint16_t m_code(int c = 0) const { return codes_[c]; }
  uint32_t m_t() const { return m_t_; }
  uint16_t overruns() const { return overruns_; }

  void reset() {
    pcnt_ = 0;
    busy_ = false;
    cs_n_ = sclk_ = true;
    hcnt_ = 0;
    half_ = 0;
    for (auto& s : shreg_) s = 0;
    count_ = 0;
    m_valid_ = false;
    for (auto& c : codes_) c = 0;
    m_t_ = 0;
    overruns_ = 0;
    fall_q_ = last_q_ = false;
  }

  // LAG 1: SDATA at the falling clock edge before the next rising one.
  void falling_edge(uint32_t sdata) {
    for (int c = 0; c < nch_; ++c) sd_neg_[c] = (sdata >> c) & 1u;
  }
  // One rising edge; sdata: bit c is channel c's SDATA at this edge.
  void clock(bool en, uint32_t sdata, bool m_ready, bool clear) {
    // The registers before the edge.
    const int64_t pcnt = pcnt_;
    const bool busy = busy_, valid = m_valid_;
    const int hcnt = hcnt_, half = half_;
    const uint32_t count = count_;
    const bool fall_now = busy && hcnt == h_ - 1 && (half & 1) == 0;
    const bool last_now = fall_now && half == 30;
    const bool take = lag_ == 0 ? fall_now : fall_q_;
    const bool take16 = lag_ == 0 ? last_now : last_q_;

    if (clear) overruns_ = 0;
    if (valid && m_ready) m_valid_ = false;
    pcnt_ = pcnt == period_ - 1 ? 0 : pcnt + 1;
    fall_q_ = fall_now;
    last_q_ = last_now;
    const bool deliver = take16 && !(valid && !m_ready);
    if (take || deliver) {  // a bit taken: shifted = {shreg[14:0], the bit}
      for (int c = 0; c < nch_; ++c) {
        const bool bit = lag_ == 1 ? sd_neg_[c] : ((sdata >> c) & 1u) != 0;
        const uint16_t shifted = uint16_t((uint32_t(shreg_[c]) << 1) | (bit ? 1u : 0u));
        if (deliver) codes_[c] = uint16_t(shifted & 0x0FFF);
        if (take) shreg_[c] = shifted;
      }
    }
    if (take16) {  // the 16th bit is in
      count_ = count + 1;
      if (!deliver) {
        if (overruns_ != 0xFFFF && !clear) ++overruns_;
      } else {
        m_valid_ = true;
        m_t_ = count;
      }
    }
    if (!busy) {
      if (pcnt == 0 && en) {
        busy_ = true;
        cs_n_ = false;
        hcnt_ = 0;
        half_ = 0;
      }
    } else if (hcnt != h_ - 1) {
      hcnt_ = hcnt + 1;
    } else {
      hcnt_ = 0;
      half_ = (half + 1) & 31;
      if ((half & 1) == 0) {
        sclk_ = false;  // SCLK falling edge half / 2 + 1
      } else {
        sclk_ = true;
        if (half == 31) {  // the 16th rising edge: the conversion ends
          cs_n_ = true;
          busy_ = false;
        }
      }
    }
  }

 private:
  int64_t period_ = 0;
  int h_, nch_, lag_ = 0;
  int64_t pcnt_ = 0;
  bool busy_ = false, cs_n_ = true, sclk_ = true;
  int hcnt_ = 0, half_ = 0;
  static constexpr int kMaxCh = 4;
  uint16_t shreg_[kMaxCh] = {}, codes_[kMaxCh] = {};
  bool sd_neg_[kMaxCh] = {};
  uint32_t count_ = 0;
  bool m_valid_ = false;
  uint32_t m_t_ = 0;
  uint16_t overruns_ = 0;
  bool fall_q_ = false, last_q_ = false;
};

}  // namespace eskin::cycle
