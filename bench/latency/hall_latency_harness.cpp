// Cycle-exact latency of one build of rtl/hall_top.v: from the DRDY of the
// reading that completes a frame to the frame's first and last byte on the
// host link. Not built by CMake: `eskin bench latency`
// (host/bench/latency.cpp) verilates hall_top with the parameters
// sim/hall_top_spec.h generates for the scene and compiles this harness
// against it (cached), on the bench tests/rtl/hall_top_test.cpp uses
// (tests/rtl/hall_top_board.h).
//
//   hall_latency_harness SCENE.yaml FRAMES
// Runs the scene's sensors (its HallWorld field, noise and addresses) until
// FRAMES + 1 frames are on the wire and measures frames 2 .. FRAMES-1 (the
// first two come from the configuration round and the first conversion).
// Prints "stage cycles" lines (the slowest of those frames; every frame's
// figure on a "# " line), then the counters that must be 0.
#include <algorithm>
#include <cstdio>
#include <string>

#include "Vhall_top.h"
#include "hall_top_board.h"
#include "sim/hall_top_spec.h"
#include "sim/hall_world.h"
#include "sim/scene.h"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: hall_latency_harness SCENE.yaml FRAMES\n");
    return 2;
  }
  const auto sc = eskin::sim::load_scene(argv[1]);
  if (!sc.has_hall) {
    std::fprintf(stderr, "hall_latency_harness: %s has no hall section\n", argv[1]);
    return 2;
  }
  const size_t frames = std::stoul(argv[2]);
  if (frames < 3) {
    std::fprintf(stderr, "hall_latency_harness: FRAMES must be at least 3\n");
    return 2;
  }
  const auto spec = eskin::sim::hall_top_spec(sc.hall.config);
  const eskin::sim::HallWorld world(sc.hall);
  hall_bench::HallBoard<Vhall_top> b(world, sc.hall.config, spec);
  const uint64_t limit = (frames + 4) * hall_bench::kConvCyc * 2;  // frames stopped coming
  while (b.frames().size() <= frames && b.d.cycle < limit) b.run(500);
  if (b.frames().size() <= frames) {
    std::fprintf(stderr, "hall_latency_harness: %zu frames after %llu clocks, expected %zu\n",
                 b.frames().size(), (unsigned long long)b.d.cycle, frames + 1);
    return 1;
  }
  hall_bench::HallBoard<Vhall_top>::FrameLatency worst;
  int incomplete = 0;
  for (size_t f = 2; f < frames; ++f) {
    const auto l = b.frame_latency(f);
    std::printf("# frame %zu (t %u us): DRDY -> first byte %llu, last byte %llu clocks\n", f,
                unsigned(b.frames()[f]->t), (unsigned long long)l.first_byte,
                (unsigned long long)l.last_byte);
    worst.first_byte = std::max(worst.first_byte, l.first_byte);
    worst.last_byte = std::max(worst.last_byte, l.last_byte);
    for (const auto& h : b.frames()[f]->hall_samples) incomplete += !h.has_data();
  }
  size_t violations = 0;
  violations += b.io.violations().size();
  std::printf("hall.drdy 0\nuart.first_start_bit %llu\nuart.last_stop_bit %llu\n",
              (unsigned long long)worst.first_byte, (unsigned long long)worst.last_byte);
  // A reading missing from a measured frame, an I2C timing violation or a
  // corrupt packet would make the figure meaningless.
  std::printf("missing_readings %d\ni2c_violations %zu\nlink_errors %llu\n", incomplete,
              violations,
              (unsigned long long)(b.dec.stats().crc_errors + b.dec.stats().framing_errors));
  return 0;
}
