// link_framer: the clock-exact C++ model of rtl/link_framer.v (seq, CRC
// and COBS framing of the output FIFO's packets, ping-pong block buffer),
// a part of the `cycle` fidelity level (docs/vboard.md). The same registers
// and RAM, updated as the RTL's nonblocking assignments update them at each
// rising edge; s_ready is combinational on the registers, m_valid / m_data
// are registers. Held to the Verilated RTL clock by clock in
// tests/rtl/link_framer_test.cpp.
#pragma once

#include <array>
#include <cstdint>

#include "sim/cycle/crc16.h"

namespace eskin::cycle {

class LinkFramer {
 public:
  bool s_ready() const { return from_input() && enc_ready(); }
  bool m_valid() const { return m_valid_; }
  uint8_t m_data() const { return m_data_; }
  uint8_t seq() const { return seq_; }

  void reset() {
    astate_ = kType;
    hidx_ = 0;
    seq_ = 0;
    crc_ = 0xFFFF;
    remaining_ = 0;
    wbank_ = 0;
    wcnt_ = 0;
    full_ = {false, false};
    last_ = {false, false};
    code_ = {0, 0};
    rstate_ = kIdle;
    kind_ = kCode;
    rbank_ = 0;
    ridx_ = 0;
    m_valid_ = false;
    m_data_ = 0;
  }

  void clock(bool s_valid, uint8_t s_data, bool m_ready) {
    if (!s_valid && from_input() && rstate_ == kIdle && !full_[size_t(rbank_)]) {
      rdata_ = mem_[size_t(rbank_) * 256 + ridx_];  // idle: only the RAM's read register moves
      return;
    }
    // This clock's combinational values, from the registers before the edge.
    const bool raw_valid = from_input() ? s_valid : true;
    const bool raw_eop = astate_ == kEop;
    const uint8_t raw_byte = astate_ == kSeq ? seq_
                             : astate_ == kCrc ? uint8_t((hidx_ & 1) ? crc_ & 0xFF : crc_ >> 8)
                                               : s_data;
    const bool raw_take = raw_valid && enc_ready();
    const bool wr_data = raw_take && !raw_eop && raw_byte != 0;
    const bool close = raw_take && (raw_eop || raw_byte == 0 || wcnt_ == 253);
    const uint8_t close_code = wr_data ? 0xFF : uint8_t(wcnt_ + 1);
    const uint8_t rcode = code_[size_t(rbank_)];
    const bool more = ridx_ != uint8_t(rcode - 1);
    const bool release_bank =
        rstate_ == kOut && m_ready && (kind_ == kDelim || (!more && !last_[rbank_]));
    const uint8_t rdata_next = mem_[size_t(rbank_) * 256 + ridx_];  // read before the write
    const int rb = rbank_;  // the read side's bank and its flags before the edge
    const bool rfull = full_[size_t(rb)], rlast = last_[size_t(rb)];

    // Assembler.
    if (raw_take) {
      if (astate_ != kCrc && !raw_eop) crc_ = crc16(crc_, raw_byte);
      switch (astate_) {
        case kType: astate_ = kSeq; break;
        case kSeq:
          hidx_ = 0;
          astate_ = kHdr;
          break;
        case kHdr: {
          const uint8_t h = hidx_;
          hidx_ = uint8_t((hidx_ + 1) & 7);
          if (h == 4) remaining_ = uint16_t((remaining_ & 0xFF00) | s_data);
          if (h == 5) {
            const uint16_t lo = remaining_ & 0xFF;
            remaining_ = uint16_t((uint16_t(s_data) << 8) | lo);
            hidx_ = 0;
            astate_ = remaining_ == 0 ? kCrc : kPay;
          }
          break;
        }
        case kPay:
          if (remaining_ == 1) astate_ = kCrc;
          --remaining_;
          break;
        case kCrc:
          if (hidx_ & 1) astate_ = kEop;
          hidx_ = uint8_t((hidx_ + 1) & 7);
          break;
        default:  // kEop
          ++seq_;
          crc_ = 0xFFFF;
          hidx_ = 0;
          astate_ = kType;
          break;
      }
    }

    // COBS encoder: block RAM and the write side.
    if (wr_data) mem_[size_t(wbank_) * 256 + wcnt_] = raw_byte;
    const uint8_t rdata_reg = rdata_;  // the register R_FETCH sends: last edge's read
    rdata_ = rdata_next;
    if (wr_data && !close) ++wcnt_;
    if (close) {
      full_[size_t(wbank_)] = true;
      last_[size_t(wbank_)] = raw_eop;
      code_[size_t(wbank_)] = close_code;
      wbank_ ^= 1;
      wcnt_ = 0;
    }
    if (release_bank) full_[size_t(rb)] = false;

    // The read side.
    switch (rstate_) {
      case kIdle:
        if (rfull) {
          m_data_ = rcode;
          m_valid_ = true;
          kind_ = kCode;
          ridx_ = 0;
          rstate_ = kOut;
        }
        break;
      case kOut:
        if (m_ready) {
          m_valid_ = false;
          if (kind_ != kDelim && more) {
            rstate_ = kFetch;
          } else if (kind_ != kDelim && rlast) {
            m_data_ = 0;
            m_valid_ = true;
            kind_ = kDelim;
          } else {
            rbank_ ^= 1;
            rstate_ = kIdle;
          }
        }
        break;
      default:  // kFetch
        m_data_ = rdata_reg;
        m_valid_ = true;
        kind_ = kData;
        ++ridx_;
        rstate_ = kOut;
        break;
    }
  }

 private:
  enum AState : uint8_t { kType, kSeq, kHdr, kPay, kCrc, kEop };
  enum RState : uint8_t { kIdle, kOut, kFetch };
  enum Kind : uint8_t { kCode, kData, kDelim };

  bool from_input() const { return astate_ == kType || astate_ == kHdr || astate_ == kPay; }
  bool enc_ready() const { return !full_[size_t(wbank_)]; }

  AState astate_ = kType;
  uint8_t hidx_ = 0, seq_ = 0;
  uint16_t crc_ = 0xFFFF, remaining_ = 0;
  std::array<uint8_t, 512> mem_{};
  uint8_t rdata_ = 0;
  int wbank_ = 0, rbank_ = 0;
  uint8_t wcnt_ = 0;
  std::array<bool, 2> full_{}, last_{};
  std::array<uint8_t, 2> code_{};
  RState rstate_ = kIdle;
  Kind kind_ = kCode;
  uint8_t ridx_ = 0;
  bool m_valid_ = false;
  uint8_t m_data_ = 0;
};

}  // namespace eskin::cycle
