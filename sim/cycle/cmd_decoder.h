// cmd_decoder: the clock-exact C++ model of rtl/cmd_decoder.v (host
// command frames, COBS-decoded on the fly, judged at the delimiter, a FIFO
// with commit and rollback), a part of the `cycle` fidelity level
// (docs/vboard.md). avail is combinational on the registers; head and the
// counters are registers. Held to the Verilated RTL clock by clock, behind
// the cycle model of uart_rx, in tests/rtl/cmd_decoder_test.cpp.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <vector>

#include "sim/cycle/crc16.h"

namespace eskin::cycle {

class CmdDecoder {
 public:
  // DEPTH (a power of two, at least 16) and the routed type range, as the
  // RTL's parameters.
  explicit CmdDecoder(int depth = 512, uint8_t type_lo = 0x00, uint8_t type_hi = 0xFF,
                      bool type_in = true)
      : depth_(uint32_t(depth)), lo_(type_lo), hi_(type_hi), in_(type_in), mem_(size_t(depth)) {
    if (depth < 16 || (depth & (depth - 1)) != 0 || type_lo > type_hi)
      throw std::invalid_argument("CmdDecoder: DEPTH a power of two >= 16, TYPE_LO <= TYPE_HI");
  }

  bool avail() const { return rp_ != wc_ && !fresh_; }
  uint8_t head() const { return head_; }
  uint16_t crc_errors() const { return crc_errors_; }
  uint16_t frame_errors() const { return frame_errors_; }
  uint16_t overflows() const { return overflows_; }

  void reset() {
    code_rem_ = 0;
    pend_zero_ = in_frame_ = bad_ = ovf_ = false;
    count_ = 0;
    pos_ = 0;
    crc_ = 0xFFFF;
    len10_ = 0;
    typ_ = 0;
    wp_ = wc_ = rp_ = 0;
    fresh_ = true;
    crc_errors_ = frame_errors_ = overflows_ = 0;
  }

  void clock(bool s_valid, uint8_t s_data, bool rx_error, bool pop, bool clear) {
    if (!s_valid && !rx_error && !pop && !clear) {  // most clocks: only the head's read
      head_ = mem_[rp_ & (depth_ - 1)];
      fresh_ = false;
      return;
    }
    const uint32_t mask = 2 * depth_ - 1;
    // This clock's combinational values, from the registers before the edge.
    const bool delim = s_valid && s_data == 0;
    const bool is_code = s_valid && !delim && code_rem_ == 0;
    const bool raw_en = s_valid && !delim && (!is_code || pend_zero_);
    const uint8_t raw = is_code ? 0 : s_data;
    const bool struct_ok = !bad_ && code_rem_ == 0 && pos_ >= 10 && count_ == len10_;
    const bool do_frame = delim && in_frame_;
    const uint8_t typ_off = uint8_t(typ_ - lo_);
    const bool in_range = typ_off <= uint8_t(hi_ - lo_);
    const bool routed_here = in_ ? in_range : !in_range;
    const bool store = raw_en && (pos_ < 2 || pos_ > 5);
    const bool full = ((wp_ - rp_) & mask) == depth_;
    const bool was_avail = avail();
    const bool ovf_before = ovf_;
    const uint16_t crc_before = crc_;
    const uint32_t wp_before = wp_;

    head_ = mem_[rp_ & (depth_ - 1)];  // the block RAM's read, before this edge's write
    if (store && !full && !ovf_before) mem_[wp_ & (depth_ - 1)] = raw;

    fresh_ = pop;
    if (pop && was_avail) rp_ = (rp_ + 1) & mask;
    if (rx_error) bad_ = true;
    if (store) {
      if (full || ovf_before) ovf_ = true;
      else wp_ = (wp_ + 1) & mask;
    }
    if (delim) {
      code_rem_ = 0;
      pend_zero_ = false;
      in_frame_ = false;
      bad_ = false;
      ovf_ = false;
      count_ = 0;
      pos_ = 0;
      crc_ = 0xFFFF;
    } else if (s_valid) {
      in_frame_ = true;
      if (is_code) {
        code_rem_ = uint8_t(s_data - 1);
        pend_zero_ = s_data != 0xFF;
      } else {
        code_rem_ = uint8_t(code_rem_ - 1);
      }
      if (raw_en) {
        crc_ = crc16(crc_before, raw);
        if (count_ != 0x1FFFF) ++count_;
        const uint8_t p = pos_;
        if (pos_ != 15) ++pos_;
        if (p == 0) typ_ = raw;
        if (p == 6) len10_ = (len10_ & ~0xFFu) | raw;
        if (p == 7) len10_ = ((uint32_t(raw) << 8) | (len10_ & 0xFF)) + 10;
      }
    }
    if (do_frame) {
      if (!struct_ok || ovf_before || crc_before != 0 || !routed_here) {
        wp_ = wc_;
        if (!struct_ok) frame_errors_ = sat_inc(frame_errors_);
        else if (ovf_before) overflows_ = sat_inc(overflows_);
        else if (crc_before != 0) crc_errors_ = sat_inc(crc_errors_);
      } else {
        wc_ = (wp_before - 2) & mask;  // without the CRC bytes
        wp_ = wc_;
      }
    }
    if (clear) crc_errors_ = frame_errors_ = overflows_ = 0;
  }

 private:
  static uint16_t sat_inc(uint16_t x) { return x == 0xFFFF ? x : uint16_t(x + 1); }

  uint32_t depth_;
  uint8_t lo_, hi_;
  bool in_;
  std::vector<uint8_t> mem_;
  uint8_t code_rem_ = 0;
  bool pend_zero_ = false, in_frame_ = false, bad_ = false, ovf_ = false;
  uint32_t count_ = 0;  // 17 bits, saturating
  uint8_t pos_ = 0;     // saturating at 15
  uint16_t crc_ = 0xFFFF;
  uint32_t len10_ = 0;  // 17 bits
  uint8_t typ_ = 0;
  uint32_t wp_ = 0, wc_ = 0, rp_ = 0;  // AW + 1 bits
  bool fresh_ = true;
  uint8_t head_ = 0;
  uint16_t crc_errors_ = 0, frame_errors_ = 0, overflows_ = 0;
};

}  // namespace eskin::cycle
