// rtl/link_framer.v against the host side (host/link/link_encoder and
// link_decoder, an independent implementation of CRC-16 and COBS).
//
// Input: one byte stream, each packet as type, t, len, payload (the frame
// engine's output FIFO); the framer adds seq, CRC and COBS.
//
// Bounds and why:
//  * Byte-exact: the framer's output equals link_encoder's
//    COBS(raw_frame(type, seq, t, payload)) + 0x00 for every packet, since
//    both implement the same documented encoding (docs/protocol.md)
//    including the closing-block rule; and LinkDecoder returns every packet
//    (type, seq = packet index mod 256, t, payload) with zero CRC, framing,
//    payload or sequence errors.
//  * Under random source gaps and random sink back-pressure (ready 30%) the
//    result is the same, and m_data/m_valid never change while stalled
//    (valid/ready rule).
//  * Payloads cover COBS corner cases: empty, all zeros, zero-free runs of
//    253/254/255/508 bytes (block splits), random bytes.
//  * The cycle level's C++ model (sim/cycle/link_framer.h) gives the same
//    s_ready, m_valid, m_data and seq as the RTL at every clock, at full
//    rate and under gaps and back-pressure (bound: exact).
//  * Through uart_tx on the serial line (12 MHz, 3 Mbaud, CPB = 4) the
//    decoded stream is the same; the line idles only while the COBS encoder
//    fills a block (never inside a byte).
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <memory>
#include <random>
#include <vector>

#include "Vlink_framer.h"
#include "Vlink_framer_uart_tb.h"
#include "host/link/link_decoder.h"
#include "host/link/link_encoder.h"
#include "sim/cycle/link_framer.h"

using namespace eskin::link;

namespace {

struct Pkt { uint8_t type; uint32_t t; std::vector<uint8_t> payload; };

std::vector<Pkt> make_packets(int n, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<Pkt> v;
  auto fill = [&](size_t len, int pattern) {
    std::vector<uint8_t> p(len);
    for (size_t i = 0; i < len; ++i) {
      switch (pattern) {
        case 0: p[i] = uint8_t(rng()); break;
        case 1: p[i] = 0; break;
        case 2: p[i] = uint8_t(1 + rng() % 255); break;  // zero-free
        default: p[i] = (i % 7 == 0) ? 0 : uint8_t(rng() | 1); break;
      }
    }
    return p;
  };
  const size_t special[] = {0, 2, 252, 254, 256, 508, 510};
  for (int i = 0; i < n; ++i) {
    Pkt p;
    p.t = uint32_t(rng());
    const int pattern = int(rng() % 4);
    switch (i < 7 ? 0 : rng() % 5) {
      case 0: {  // amplitudes: even length, sometimes a COBS corner size
        size_t len = (i < 7) ? special[i] : 2 * (rng() % 200);
        p.type = kAmplitudes; p.payload = fill(len, pattern); break;
      }
      case 1: {
        const uint8_t r = uint8_t(1 + rng() % 10), c = uint8_t(1 + rng() % 12);
        p.type = kTaxelsDense;
        p.payload = fill(2 + 2 * size_t(r) * c, pattern);
        p.payload[0] = r; p.payload[1] = c;
        break;
      }
      case 2: p.type = kTaxelsSparse; p.payload = fill(4 * (rng() % 70), pattern); break;
      case 3: p.type = kSpikes; p.payload = fill(5 * (rng() % 60), pattern); break;
      default: p.type = kStatus; p.payload = fill(kStatusBytes, pattern); break;
    }
    v.push_back(std::move(p));
  }
  return v;
}

std::vector<uint8_t> expected_stream(const std::vector<Pkt>& pk) {
  std::vector<uint8_t> s;
  for (size_t i = 0; i < pk.size(); ++i) {
    auto w = cobs_encode(raw_frame(pk[i].type, uint8_t(i), pk[i].t, pk[i].payload));
    s.insert(s.end(), w.begin(), w.end());
    s.push_back(0);
  }
  return s;
}

// The framer's input stream: every packet as type, t (LE), len (LE), then
// the payload (what the frame engine writes to the output FIFO), offered
// with random gaps. Sets the model's inputs for this cycle.
struct Source {
  std::vector<uint8_t> bytes;
  std::mt19937_64 rng;
  double p_valid;
  size_t i = 0;
  bool sv = false;
  Source(const std::vector<Pkt>& pk, uint64_t seed, double pv) : rng(seed), p_valid(pv) {
    for (const Pkt& p : pk) {
      const size_t n = p.payload.size();
      const uint8_t hdr[7] = {p.type, uint8_t(p.t), uint8_t(p.t >> 8), uint8_t(p.t >> 16),
                              uint8_t(p.t >> 24), uint8_t(n), uint8_t(n >> 8)};
      bytes.insert(bytes.end(), hdr, hdr + 7);
      bytes.insert(bytes.end(), p.payload.begin(), p.payload.end());
    }
  }
  template <class M> void offer(M& m) {
    std::bernoulli_distribution go(p_valid);
    sv = i < bytes.size() && go(rng);
    m.s_valid = sv;
    m.s_data = sv ? bytes[i] : 0xEE;
  }
  void after(bool s_ready) {
    if (sv && s_ready) ++i;
  }
};

void check_decoded(const std::vector<uint8_t>& out, const std::vector<Pkt>& pk) {
  LinkDecoder dec;
  dec.feed(out);
  const DecoderStats& s = dec.stats();
  EXPECT_EQ(s.crc_errors + s.framing_errors + s.payload_errors + s.seq_gaps, 0u);
  Packet p;
  size_t i = 0;
  while (dec.pop(p)) {
    ASSERT_LT(i, pk.size());
    EXPECT_EQ(p.type, pk[i].type);
    EXPECT_EQ(p.seq, uint8_t(i));
    EXPECT_EQ(p.t, pk[i].t);
    EXPECT_EQ(p.payload, pk[i].payload) << "packet " << i;
    ++i;
  }
  EXPECT_EQ(i, pk.size());
}

// Three clocks of reset with the input idle.
void reset(Vlink_framer& m) {
  m.clk = 0; m.rst = 1; m.s_valid = 0; m.m_ready = 0;
  for (int i = 0; i < 3; ++i) { m.clk = 1; m.eval(); m.clk = 0; m.eval(); }
  m.rst = 0;
}

void run_direct(double p_valid, double p_ready, uint64_t seed) {
  const auto pk = make_packets(300, seed);
  auto m = std::make_unique<Vlink_framer>();
  Source src(pk, seed + 1, p_valid);
  std::mt19937_64 rng(seed + 2);
  std::bernoulli_distribution ready(p_ready);
  reset(*m);
  const auto want = expected_stream(pk);
  std::vector<uint8_t> out;
  bool stalled = false;
  uint8_t held = 0;
  for (uint64_t cyc = 0; out.size() < want.size() && cyc < 50 * want.size() + 1000; ++cyc) {
    src.offer(*m);
    const bool rdy = ready(rng);
    m->m_ready = rdy;
    m->eval();
    const bool sr = m->s_ready;
    if (stalled) {
      ASSERT_TRUE(m->m_valid) << "valid dropped while stalled";
      ASSERT_EQ(m->m_data, held) << "data changed while stalled";
    }
    if (m->m_valid && rdy) out.push_back(m->m_data);
    stalled = m->m_valid && !rdy;
    held = m->m_data;
    m->clk = 1; m->eval(); m->clk = 0; m->eval();
    src.after(sr);
  }
  ASSERT_EQ(out.size(), want.size());
  EXPECT_TRUE(out == want) << "framer bytes differ from link_encoder";
  check_decoded(out, pk);
}

void same_as_model(double p_valid, double p_ready, uint64_t seed) {
  const auto pk = make_packets(200, seed);
  auto m = std::make_unique<Vlink_framer>();
  eskin::cycle::LinkFramer model;
  model.reset();
  Source src(pk, seed + 1, p_valid);
  std::mt19937_64 rng(seed + 2);
  std::bernoulli_distribution ready(p_ready);
  reset(*m);
  const size_t want = expected_stream(pk).size();
  size_t out = 0;
  for (uint64_t cyc = 0; out < want; ++cyc) {
    ASSERT_LT(cyc, 50 * want + 1000) << "the framer stopped";
    src.offer(*m);
    const bool rdy = ready(rng);
    m->m_ready = rdy;
    m->eval();
    ASSERT_EQ(bool(m->s_ready), model.s_ready()) << "cycle " << cyc;
    ASSERT_EQ(bool(m->m_valid), model.m_valid()) << "cycle " << cyc;
    ASSERT_EQ(m->m_data, model.m_data()) << "cycle " << cyc;
    ASSERT_EQ(m->seq, model.seq()) << "cycle " << cyc;
    out += model.m_valid() && rdy;
    model.clock(bool(m->s_valid), m->s_data, rdy);
    const bool sr = m->s_ready;
    m->clk = 1; m->eval(); m->clk = 0; m->eval();
    src.after(sr);
  }
}

}  // namespace

TEST(LinkFramer, CycleModelEqualsTheRtlEveryClock) {
  same_as_model(1.0, 1.0, 30);
  same_as_model(0.5, 0.3, 31);
  same_as_model(0.9, 0.05, 32);  // the UART's pace: blocks wait in both banks
}

TEST(LinkFramer, FullRateMatchesHostEncoder) { run_direct(1.0, 1.0, 10); }
TEST(LinkFramer, RandomGapsAndBackPressure) { run_direct(0.5, 0.3, 20); }

TEST(LinkFramer, ThroughUartTxOnTheLine) {
  const int cpb = 12000000 / 3000000;
  const auto pk = make_packets(60, 30);
  auto m = std::make_unique<Vlink_framer_uart_tb>();
  Source src(pk, 31, 1.0);
  m->clk = 0; m->rst = 1; m->s_valid = 0;
  for (int i = 0; i < 3; ++i) { m->clk = 1; m->eval(); m->clk = 0; m->eval(); }
  m->rst = 0;
  const auto want = expected_stream(pk);
  // Line decoder: start bit = first low sample while idle; bits read at the
  // middle of each CPB-cycle slot.
  std::vector<uint8_t> line;
  for (uint64_t cyc = 0; cyc < uint64_t(12 * cpb) * (want.size() + 50); ++cyc) {
    src.offer(*m);
    m->eval();
    const bool sr = m->s_ready;
    m->clk = 1; m->eval(); m->clk = 0; m->eval();
    src.after(sr);
    line.push_back(m->tx);
  }
  std::vector<uint8_t> out;
  for (size_t i = 0; i + 10 * cpb < line.size();) {
    if (line[i]) { ++i; continue; }
    uint8_t b = 0;
    for (int k = 0; k < 8; ++k) b |= uint8_t(line[i + (1 + k) * cpb + cpb / 2] << k);
    ASSERT_EQ(line[i + 9 * cpb + cpb / 2], 1) << "stop bit at " << i;
    out.push_back(b);
    i += 10 * cpb;
  }
  ASSERT_EQ(out.size(), want.size());
  EXPECT_TRUE(out == want);
  check_decoded(out, pk);
  // Figure (not a bound): share of line time carrying bytes while sending.
  size_t first = 0, last = line.size();
  while (first < line.size() && line[first]) ++first;
  while (last > 0 && line[last - 1]) --last;
  std::printf("line utilisation %.4f (%zu bytes in %zu cycles)\n",
              double(out.size() * 10 * cpb) / double(last - first), out.size(), last - first);
}
