// crc16: rtl/crc16.v in C++, one byte of CRC-16/CCITT-FALSE (polynomial
// 0x1021, MSB first, not reflected) onto the register `crc`: the cycle
// models' framer (link_framer.h) and command decoder (cmd_decoder.h) use
// it as their RTL uses rtl/crc16.v.
#pragma once

#include <cstdint>

namespace eskin::cycle {

inline uint16_t crc16(uint16_t crc, uint8_t data) {
  crc = uint16_t(crc ^ (uint16_t(data) << 8));
  for (int i = 0; i < 8; ++i) crc = uint16_t((crc & 0x8000) ? (crc << 1) ^ 0x1021 : crc << 1);
  return crc;
}

}  // namespace eskin::cycle
