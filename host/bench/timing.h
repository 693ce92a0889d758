// Timing helpers shared by the benchmarks: per-thread CPU time (a shared
// machine deschedules us; CPU time of the measuring thread is far less noisy
// than wall-clock) and a best-of-passes rate. Figures are compared only as
// ratios measured side by side in one run.
#pragma once

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <functional>

namespace eskin::bench {

inline double cpu_seconds() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}
inline double wall_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

struct Rate {
  double samples_per_s = 0;
  double checksum = 0;  // of the last pass: keeps the work alive, compares rows
};

// Repeats pass() (one run over `samples`, returning its checksum) until at
// least min_s seconds of the chosen clock have elapsed; the best pass wins.
inline Rate timed(size_t samples, double min_s, const std::function<double()>& pass,
                  bool wall = false) {
  const auto now = wall ? wall_seconds : cpu_seconds;
  Rate r;
  double total = 0;
  do {
    const double t0 = now();
    r.checksum = pass();
    const double dt = now() - t0;
    total += dt;
    r.samples_per_s = std::max(r.samples_per_s, double(samples) / dt);
  } while (total < min_s);
  return r;
}

}  // namespace eskin::bench
