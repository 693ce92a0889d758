// hls/spike_encoder.h: address-event words round-trip. The test decodes each
// word itself from the documented format (bit fields written out here, not
// taken from the kernel), for the default and a non-default width pair.
#include "hls/spike_encoder.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>

namespace {

using eskin::hls::SpikeEncoderIn;

struct Decoded {
  uint32_t t;
  unsigned layer, neuron;
};

// Documented layout: [t:32][layer:LW][neuron:AW], LSB-aligned in 64 bits.
Decoded decode(uint64_t w, int lw, int aw) {
  Decoded d;
  d.neuron = unsigned(w % (uint64_t(1) << aw));
  d.layer = unsigned((w / (uint64_t(1) << aw)) % (uint64_t(1) << lw));
  d.t = uint32_t(w / (uint64_t(1) << (aw + lw)));
  return d;
}

template <int LW, int AW>
void round_trip(uint64_t seed) {
  eskin::hls::SpikeEncoder<LW, AW> enc;
  std::mt19937_64 rng(seed);
  int words = 0;
  for (int k = 0; k < 100000; ++k) {
    SpikeEncoderIn in;
    in.layer = uint8_t(rng() % (1u << LW));
    in.neuron = uint16_t(rng() % (1u << AW));
    in.t = k < 4 ? uint32_t(k < 2 ? 0 : 0xffffffffu) : uint32_t(rng());
    in.spike = k < 4 || (rng() & 1);
    uint64_t w = ~uint64_t(0);
    const bool got = enc.push(in, w);
    ASSERT_EQ(got, in.spike);
    if (!got) continue;
    ++words;
    ASSERT_LT(w, uint64_t(1) << (32 + LW + AW));  // nothing above the word
    const Decoded d = decode(w, LW, AW);
    EXPECT_EQ(d.t, in.t);
    EXPECT_EQ(d.layer, in.layer);
    EXPECT_EQ(d.neuron, in.neuron);
  }
  EXPECT_GT(words, 40000);
}

// Bound: exact round trip of every field (pure bit packing, no arithmetic),
// including t = 0 and t = 2^32 - 1 and the largest layer/neuron values.
TEST(SpikeEncoderHls, WordsRoundTrip) {
  round_trip<4, 12>(1);
  round_trip<2, 8>(2);
  round_trip<8, 16>(3);
}

// Bound: the documented default layout, one literal word checked by hand:
// t = 0x12345678, layer 3, neuron 0xabc -> 0x12345678_3abc.
TEST(SpikeEncoderHls, DefaultLayoutLiteral) {
  eskin::hls::SpikeEncoder<> enc;
  uint64_t w = 0;
  ASSERT_TRUE(enc.push(SpikeEncoderIn{3, 0xabc, 0x12345678u, true}, w));
  EXPECT_EQ(w, 0x123456783abcull);
  EXPECT_EQ(enc.kWordBits, 48);
}

}  // namespace
