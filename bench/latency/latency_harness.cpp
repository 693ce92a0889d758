// Cycle-exact stage latencies of one build of rtl/dtmf_top.v. Not built by
// CMake: `eskin bench latency` (host/bench/latency.cpp) verilates the top
// with the build's parameters (its microcode and constants written by
// hls::write_dtmf_top_build) and compiles this harness against it, one
// build per parameter set, cached.
//
//   latency_harness CODES.u16 SAMPLE RUN_TO CLK_HZ CLOCKS_PER_BIT
// CODES.u16: the 12-bit ADC codes (little-endian u16); SAMPLE: the frame
// sample whose latency is measured (a packet frame with the link idle);
// RUN_TO: the sample to simulate up to. Prints "stage cycles" lines: cycles
// at the top's clock from the 16th SCLK falling edge of SAMPLE (the ADC's
// last data edge) to each stage's event (tests/rtl/dtmf_top_board.h reads
// the top's p_* probes), then the counters that must be 0.
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "Vdtmf_top.h"
#include "Vdtmf_top___024root.h"
#include "dtmf_top_board.h"
#include "host/link/link_encoder.h"

int main(int argc, char** argv) {
  if (argc != 6) {
    std::fprintf(stderr, "usage: latency_harness CODES.u16 SAMPLE RUN_TO CLK_HZ CLOCKS_PER_BIT\n");
    return 2;
  }
  std::ifstream f(argv[1], std::ios::binary);
  const std::vector<char> raw{std::istreambuf_iterator<char>(f), {}};
  std::vector<uint16_t> codes(raw.size() / 2);
  for (size_t i = 0; i < codes.size(); ++i)
    codes[i] = uint16_t(uint8_t(raw[2 * i]) | uint8_t(raw[2 * i + 1]) << 8);
  const uint32_t n = uint32_t(std::stoul(argv[2]));
  const size_t run_to = std::stoul(argv[3]);
  if (codes.size() <= run_to) {
    std::fprintf(stderr, "latency_harness: %zu codes, need more than %zu\n", codes.size(), run_to);
    return 2;
  }
  dtmf_bench::Board<Vdtmf_top> b(codes, std::stod(argv[4]), std::stoi(argv[5]));
  b.run_until_sample(run_to);
  const auto it = b.events.find(n);
  if (it == b.events.end() || !it->second.frame) {
    std::fprintf(stderr, "latency_harness: sample %u made no frame\n", n);
    return 1;
  }
  const auto& e = it->second;
  const int64_t ref = int64_t(b.sample_edge(n));
  const auto out = [ref](const char* name, uint64_t cycle) {
    if (cycle) std::printf("%s %lld\n", name, (long long)(int64_t(cycle) - ref));
  };
  // The frame's packets (AMPLITUDES .. SPIKES carry its t) on the wire.
  uint64_t first = 0, last = 0;
  int packets = 0;
  for (const auto& r : b.received())
    if (r.p.t == n && r.p.type >= 1 && r.p.type <= 4) {
      first = first ? std::min(first, r.start_cycle) : r.start_cycle;
      last = std::max(last, r.end_cycle);
      ++packets;
    }
  out("adc_ad7476", e.adc);
  out("sdft_bank.last", e.sd_last);
  out("frame_capture", e.frame);
  out("frame_engine.first_byte", e.first_out);
  out("frame_engine.done", e.done);
  out("uart.first_start_bit", first);
  out("uart.last_stop_bit", last);
  std::printf("engine_clocks %lld\nengine_first_byte_clocks %lld\npackets %d\n",
              (long long)(e.done - e.frame), (long long)(e.first_out - e.frame), packets);
  // The top's own counters, from a STATUS packet asked for now.
  eskin::link::LinkEncoder enc;
  b.send(enc.request_status());
  const eskin::link::StatusBlock* st = nullptr;
  for (int i = 0; i < 2000000 && !st; ++i) {
    b.tick();
    for (const auto& r : b.received())
      if (r.p.type == eskin::link::kStatus) st = &r.p.status;
  }
  if (!st) {
    std::fprintf(stderr, "latency_harness: no STATUS packet\n");
    return 1;
  }
  std::printf("adc_overruns %d\nframe_overruns %d\ndropped_frames %d\nout_overflows %d\n"
              "link_errors %d\n",
              int(st->adc_overruns), int(st->frame_overruns), int(st->dropped_frames),
              int(b.out_overflows),
              int(b.link_stats().crc_errors + b.link_stats().framing_errors +
                  b.link_stats().payload_errors + b.link_stats().lost_packets +
                  uint64_t(b.uart_framing_errors())));
  return 0;
}
