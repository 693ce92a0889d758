// rtl/crc16.v (one byte of CRC-16/CCITT-FALSE, combinational) against the
// host's table-driven CRC (host/link/link_encoder crc16_table, written
// independently): exhaustive over every register value and every byte
// (2^24 cases), plus the standard check value of "123456789" (0x29B1) and
// the receiver identity (the register over a frame and its big-endian CRC
// is 0). Bound: exact.
#include <gtest/gtest.h>

#include <cstdint>
#include <memory>

#include "Vcrc16.h"
#include "host/link/link_encoder.h"

TEST(Crc16, EveryRegisterAndByteEqualsTheHostTable) {
  auto m = std::make_unique<Vcrc16>();
  for (uint32_t crc = 0; crc < 65536; ++crc)
    for (uint32_t b = 0; b < 256; ++b) {
      m->crc_in = uint16_t(crc);
      m->data = uint8_t(b);
      m->eval();
      const uint8_t byte = uint8_t(b);
      ASSERT_EQ(m->crc_out, eskin::link::crc16_table(&byte, 1, uint16_t(crc)))
          << "crc " << crc << " byte " << b;
    }
}

TEST(Crc16, CheckValueAndReceiverIdentity) {
  auto m = std::make_unique<Vcrc16>();
  auto run = [&m](const uint8_t* p, size_t n) {
    uint16_t crc = 0xFFFF;
    for (size_t i = 0; i < n; ++i) {
      m->crc_in = crc;
      m->data = p[i];
      m->eval();
      crc = m->crc_out;
    }
    return crc;
  };
  const uint8_t check[] = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};
  EXPECT_EQ(run(check, 9), 0x29B1);
  uint8_t frame[11] = {'1', '2', '3', '4', '5', '6', '7', '8', '9', 0x29, 0xB1};
  EXPECT_EQ(run(frame, 11), 0);
}
