// The streaming path's memory stays flat: 10^6 packets in a DTMF board's
// mix go through a real pty into the real `eskin stream` process
// (host/stream/stream_memory.h, the library behind `eskin bench memory`,
// which runs 10^7: docs/bench.md), and its VmRSS after warm-up does not
// follow the packet count.
#include <gtest/gtest.h>

#include "host/stream/stream_memory.h"

namespace {

using eskin::stream::MemoryOptions;
using eskin::stream::MemoryResult;

TEST(StreamMemory, RssStaysFlatOverAMillionPackets) {
  MemoryOptions o;
  o.eskin_bin = ESKIN_BIN;
  o.packets = 1000000;
  o.sample_every = 100000;
  const MemoryResult r = eskin::stream::measure_stream_memory(o);
  SCOPED_TRACE(eskin::stream::memory_text(r) + r.child_stderr);
  // Every packet taken once: the count is the stream's own, at the end of a
  // run ended by the pty hanging up, not capped by --count.
  EXPECT_EQ(r.error, "");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_TRUE(r.counted);
  EXPECT_EQ(r.packets_counted, o.packets);
  EXPECT_EQ(r.frames_ok, o.packets);
  EXPECT_EQ(r.lost_packets, 0u);
  EXPECT_EQ(r.corrupt_frames, 0u);
  ASSERT_EQ(r.samples.size(), 11u);  // at 0, every 10^5 packets up to 9 * 10^5, and at the end
  EXPECT_EQ(r.warm().packets, 100000u);
  EXPECT_EQ(r.last().packets, o.packets);
  // From 10^5 packets (the decoder's, the allocator's and the kernel's
  // buffers in use) to 10^6, 9 * 10^5 packets go through. Anything kept per
  // packet costs far more than a byte (a decoded Packet is over 100 bytes
  // with its vectors; its wire frame alone is 15..50), so one byte per
  // packet would already be 879 KiB; 256 KiB is under 0.3 bytes per packet
  // and well above the allocator's page-level jitter (a few pages).
  EXPECT_LE(r.growth_kib(), 256) << "RSS grew with the packet count";
}

}  // namespace
