// hls/taxel_packetizer.h against docs/protocol.md section 4, by hand: the
// expected bytes below are written out from the layouts (TAXELS_DENSE:
// rows, cols, g u16 LE row-major; TAXELS_SPARSE: {row, col, g u16 LE} for
// g >= max(1, threshold)), not computed by the kernel.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "hls/taxel_packetizer.h"

namespace {

using P = eskin::hls::TaxelPacketizer<2, 3>;

struct Packet {
  uint8_t type = 0;
  uint32_t t = 0;
  uint16_t len = 0;
  uint8_t payload[P::kSparseMaxLen] = {};
};

std::vector<uint8_t> bytes(const Packet& p) {
  std::vector<uint8_t> b(size_t(P::kHeaderBytes + p.len));
  EXPECT_EQ(P::fifo_bytes(p, b.data()), int(b.size()));
  return b;
}

// A 2 x 3 frame: g = 0, 1, 0x0102, 5, 0xFFFF, 4.
const uint16_t kG[6] = {0, 1, 0x0102, 5, 0xFFFF, 4};

TEST(TaxelPacketizer, DenseThenSparseAsTheProtocolLaysThemOut) {
  Packet p[2];
  ASSERT_EQ(P::frame(kG, 0x11223344u, true, true, 5, p), 2);
  EXPECT_EQ(bytes(p[0]), (std::vector<uint8_t>{
                             0x02, 0x44, 0x33, 0x22, 0x11, 14, 0,  // type, t, len 2 + 2 x 6
                             2, 3,                                 // rows, cols
                             0, 0, 1, 0, 2, 1, 5, 0, 0xFF, 0xFF, 4, 0}));
  // Threshold 5: taxels (0, 2) = 0x0102, (1, 0) = 5 and (1, 1) = 0xFFFF.
  EXPECT_EQ(bytes(p[1]), (std::vector<uint8_t>{0x03, 0x44, 0x33, 0x22, 0x11, 12, 0,  //
                                               0, 2, 2, 1, 1, 0, 5, 0, 1, 1, 0xFF, 0xFF}));
}

TEST(TaxelPacketizer, SparseThresholdIsAtLeastOneAndAnEmptyListIsSent) {
  Packet p[2];
  // sparse_min 0 and 1 both list every taxel with g >= 1 (never g = 0).
  for (uint16_t min : {0, 1}) {
    ASSERT_EQ(P::frame(kG, 7, false, true, min, p), 1);
    EXPECT_EQ(bytes(p[0]), (std::vector<uint8_t>{0x03, 7, 0, 0, 0, 20, 0,  //
                                                 0, 1, 1, 0, 0, 2, 2, 1, 1, 0, 5, 0,
                                                 1, 1, 0xFF, 0xFF, 1, 2, 4, 0}))
        << "sparse_min " << min;
  }
  // Threshold 0xFFFF: only the 0xFFFF taxel.
  ASSERT_EQ(P::frame(kG, 7, false, true, 0xFFFF, p), 1);
  EXPECT_EQ(p[0].len, 4);
  const uint16_t dark[6] = {};
  ASSERT_EQ(P::frame(dark, 9, false, true, 0, p), 1);
  EXPECT_EQ(bytes(p[0]), (std::vector<uint8_t>{0x03, 9, 0, 0, 0, 0, 0}));
  EXPECT_EQ(P::frame(kG, 9, false, false, 0, p), 0);
}

}  // namespace
