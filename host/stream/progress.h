// The progress of a long run on stderr: a bar on a terminal, otherwise a
// line per quarter once the run is longer than 2 s (eskin simulate).
#pragma once

#include <unistd.h>

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <string>

namespace eskin::stream {

class Progress {
 public:
  explicit Progress(size_t total) : total_(total), tty_(isatty(2)) {}
  void update(size_t done) {
    const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
    const double f = std::min(1.0, double(done) / double(total_));
    if (tty_) {
      if (el - last_ < 0.1 && f < 1) return;
      last_ = el;
      const int w = 30, n = int(f * w);
      fmt::print(stderr, "\rvirtual board [{}{}] {:3.0f}%  {:.1f} s", std::string(size_t(n), '#'),
                 std::string(size_t(w - n), ' '), 100 * f, el);
      if (f >= 1) fmt::print(stderr, "\n");
    } else if (el > 2 && int(f * 4) > quarter_) {
      quarter_ = int(f * 4);
      fmt::print(stderr, "virtual board: {:.0f}% after {:.1f} s\n", 100 * f, el);
    }
  }

 private:
  size_t total_;
  bool tty_;
  double last_ = -1;
  int quarter_ = 0;
  std::chrono::steady_clock::time_point t0_ = std::chrono::steady_clock::now();
};

}  // namespace eskin::stream
