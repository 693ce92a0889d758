// Host link decode throughput: the default scene's packets (what the FPGA
// sends; tests/stream/frames.h) repeated, decoded (1) by link::LinkDecoder
// from an in-memory buffer and (2) by stream::LinkStream reading a real pty
// that a writer thread fills, both in one run so the ratio is meaningful.
// Usage: build/bin/stream_bench [REPEATS]   (default 100: ~165k packets, 5 MB)
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <thread>

#include "host/link/link_decoder.h"
#include "host/stream/link_stream.h"
#include "tests/stream/frames.h"
#include "tests/stream/pty_pair.h"

namespace {

using clock_type = std::chrono::steady_clock;

void report(const char* what, size_t packets, size_t bytes, double s) {
  std::printf("%-28s %9zu packets %10zu bytes %8.3f s %12.0f packets/s %8.1f MB/s\n", what,
              packets, bytes, s, double(packets) / s, double(bytes) / s / 1e6);
}

}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::atoi(argv[1]) : 100;
  std::vector<eskin::testing::Sent> sent;
  const auto scene = eskin::testing::scene_frames(sent);
  // Re-encode with running seq numbers so repeats are not sequence gaps.
  eskin::link::LinkEncoder enc;
  std::vector<uint8_t> wire;
  for (int r = 0; r < repeats; ++r)
    for (const auto& s : sent) {
      const auto f = enc.frame(s.type, s.t, s.payload);
      wire.insert(wire.end(), f.begin(), f.end());
    }
  const size_t packets = sent.size() * size_t(repeats);
  std::printf("default scene: %zu packets per run, %d runs, mean frame %.1f wire bytes\n",
              sent.size(), repeats, double(wire.size()) / double(packets));

  {
    eskin::link::LinkDecoder dec;
    size_t n = 0;
    dec.on_packet([&](const eskin::link::Packet&) { ++n; });
    const auto t0 = clock_type::now();
    for (size_t i = 0; i < wire.size(); i += 4096)
      dec.feed(wire.data() + i, std::min<size_t>(4096, wire.size() - i));
    const double s = std::chrono::duration<double>(clock_type::now() - t0).count();
    if (n != packets || dec.stats().crc_errors + dec.stats().framing_errors) {
      std::fprintf(stderr, "in-memory decode lost packets: %zu of %zu\n", n, packets);
      return 1;
    }
    report("LinkDecoder, memory", packets, wire.size(), s);
  }
  {
    eskin::testing::PtyPair pty;
    eskin::stream::StreamOptions opt;
    opt.endpoint = eskin::stream::Endpoint::serial(pty.slave_path());
    opt.queue_capacity = 0;
    eskin::stream::LinkStream stream(opt);
    std::atomic<size_t> n{0};
    stream.on_packet([&](const eskin::link::Packet&) { ++n; });
    stream.start();
    while (!stream.connected()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    const auto t0 = clock_type::now();
    std::thread writer([&] { eskin::testing::write_fully(pty.master(), wire); });
    while (n < packets) {
      std::this_thread::sleep_for(std::chrono::microseconds(200));
      if (clock_type::now() - t0 > std::chrono::seconds(120)) break;
    }
    const double s = std::chrono::duration<double>(clock_type::now() - t0).count();
    writer.join();
    if (n != packets) {
      std::fprintf(stderr, "pty stream lost packets: %zu of %zu\n", n.load(), packets);
      return 1;
    }
    report("LinkStream, pty", packets, wire.size(), s);
  }
  std::printf("board link for comparison: 3 Mbaud = 0.3 MB/s\n");
  return 0;
}
