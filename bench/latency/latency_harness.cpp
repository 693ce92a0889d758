// Cycle-exact stage latencies of one build of rtl/dtmf_top.v. Not built by
// CMake: `eskin bench latency` (bench/suite/latency.cpp) verilates the top
// with the build's parameters and compiles this harness against it, one
// build per parameter set, cached.
//
//   latency_harness CODES.u16 SAMPLE RUN_TO
// CODES.u16: the 12-bit ADC codes (little-endian u16); SAMPLE: the sample
// whose frame is measured (a packet step with the link idle); RUN_TO: the
// sample to simulate up to. Prints "stage cycles" lines: cycles at the top's
// clock from the 16th SCLK falling edge of SAMPLE (the ADC's last data
// edge) to the handshake of each stage (tests/rtl/dtmf_top_board.h probes).
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "Vdtmf_top.h"
#include "Vdtmf_top___024root.h"
#include "dtmf_top_board.h"

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: latency_harness CODES.u16 SAMPLE RUN_TO\n");
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
  dtmf_bench::Board<Vdtmf_top> b(codes);
  b.run_until_sample(run_to);
  const auto it = b.events.find(n);
  if (it == b.events.end() || b.tag_error) {
    std::fprintf(stderr, "latency_harness: no events for sample %u (tag error %d)\n", n,
                 int(b.tag_error));
    return 1;
  }
  const auto& e = it->second;
  const int64_t ref = int64_t(b.sample_edge(n));
  const auto out = [ref](const char* name, uint64_t cycle) {
    if (cycle) std::printf("%s %lld\n", name, (long long)(int64_t(cycle) - ref));
  };
  out("adc_ad7476", e.adc);
  out("sdft_bank.first", e.sd_first);
  out("sdft_bank.last", e.sd_last);
  out("carrier_magnitude.first", e.mg_first);
  out("carrier_magnitude.last", e.mg_last);
  out("taxel_reconstruct.first", e.tx_first);
  out("taxel_reconstruct.last", e.tx_last);
  out("izhikevich_layer.first", e.nr_first);
  out("izhikevich_layer.last", e.nr_last);
  for (const auto& [type, cycle] : e.hdr)
    out(type == 1 ? "link_framer.amplitudes" : type == 2 ? "link_framer.taxels" : "link_framer.other",
        cycle);
  for (const auto& r : b.received())
    if (r.p.t == n && (r.p.type == 1 || r.p.type == 2))
      out(r.p.type == 1 ? "uart.amplitudes" : "uart.taxels", r.start_cycle);
  std::printf("overruns %d\ndropped %d\n", int(b.root().dtmf_top__DOT__p_overruns),
              int(b.root().dtmf_top__DOT__p_dropped));
  return 0;
}
