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

// `packets` packets through `eskin stream` (recording HDF5 when `hdf5`),
// VmRSS sampled every tenth of them; every packet taken once, and RSS from
// the sample at `warm` packets to the end grows by at most 256 KiB.
void expect_flat(bool hdf5, uint64_t packets, uint64_t warm) {
  MemoryOptions o;
  o.eskin_bin = ESKIN_BIN;
  o.packets = packets;
  o.sample_every = packets / 10;
  o.hdf5 = hdf5;
  const MemoryResult r = eskin::stream::measure_stream_memory(o);
  SCOPED_TRACE(eskin::stream::memory_text(r) + r.child_stderr);
  // Every packet taken once: the count is the stream's own, at the end of a
  // run ended by the pty hanging up, not capped by --count.
  EXPECT_EQ(r.error, "");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_TRUE(r.counted);
  EXPECT_EQ(r.packets_counted, packets);
  EXPECT_EQ(r.frames_ok, packets);
  EXPECT_EQ(r.lost_packets, 0u);
  EXPECT_EQ(r.corrupt_frames, 0u);
  if (hdf5) {
    EXPECT_GT(r.hdf5_bytes, 0u);
  }
  ASSERT_EQ(r.samples.size(), 11u);  // at 0, every tenth up to nine tenths, and at the end
  EXPECT_EQ(r.last().packets, packets);
  const eskin::stream::MemorySample* from = nullptr;
  for (const auto& s : r.samples)
    if (s.packets == warm) from = &s;
  ASSERT_NE(from, nullptr) << "no sample at " << warm << " packets";
  // Anything kept per packet costs far more than a byte (a decoded Packet
  // is over 100 bytes with its vectors; its wire frame alone is 15..50; a
  // recorded row 50..150), so even one byte per packet would be 879 KiB
  // over 9 * 10^5 packets; 256 KiB is under 0.3 bytes per packet over the
  // shortest span here and well above the allocator's page-level jitter (a
  // few pages).
  EXPECT_LE(int64_t(r.last().rss_kib) - int64_t(from->rss_kib), 256)
      << "RSS grew with the packet count from " << warm << " packets to " << packets;
}

// 10^6 packets; from 10^5 on, the decoder's, the allocator's and the
// kernel's buffers are in use.
TEST(StreamMemory, RssStaysFlatOverAMillionPackets) { expect_flat(false, 1000000, 100000); }

// Recording: the recorder holds each dataset's chunk cache to two chunks
// and HDF5's metadata cache to 256 KiB, evicting only inside a flush
// (host/stream/record_hdf5.h); both fill in the first million packets or
// so, and the chunk index nodes must not pile up as the file grows (they
// did: RSS grew ~2 bytes per recorded packet before). From 1.5 * 10^6
// packets on, RSS is flat over 1.5 * 10^6 more.
TEST(StreamMemory, RssStaysFlatWhileRecordingHdf5) { expect_flat(true, 3000000, 1500000); }

}  // namespace
