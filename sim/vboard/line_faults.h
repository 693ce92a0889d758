// The serial line between the FPGA's UART pins and the USB-serial bridge,
// with faults (docs/vboard.md, "Line faults"), both directions:
//   bit errors   each wire bit of a character (start, 8 data, stop) flipped
//                with probability `ber`, independently: a flipped start or
//                stop bit misframes the receiver as on a real line;
//   dropped      a character lost whole (probability per character);
//   inserted     a random character added before one (probability per
//                character): noise the receiver took for a byte;
//   pulled cable for [at, at + for) of simulated time nothing passes either
//                way: both lines idle high.
// Bit errors and pulls act on the line's level (wire()), once per FPGA
// clock, so the receivers (the bridge's, the FPGA's uart_rx) see what they
// would see on hardware. Drops and inserts act on characters where the
// bridge takes or gives them (fate()): FPGA -> host as the bridge's
// receiver delivers a byte, host -> FPGA as its transmitter takes one.
// Every fault comes from one seed (each direction and kind its own
// stream derived from it, so one direction's traffic does not move the
// other's faults): the same seed and the same traffic give the same faults.
// Every injected fault is counted, per direction and kind.
#pragma once

#include <cstdint>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sim/vboard/uart_rx_model.h"

namespace eskin::vboard {

enum class LineDir { to_host = 0, to_fpga = 1 };

struct DirectionFaults {
  double ber = 0;          // per wire bit
  double drop_rate = 0;    // per character
  double insert_rate = 0;  // per character
  bool any() const { return ber > 0 || drop_rate > 0 || insert_rate > 0; }
};

struct CablePull {
  double at_ms = 0, for_ms = 0;  // simulated time
};

struct LineFaultOptions {
  DirectionFaults to_host, to_fpga;
  std::vector<CablePull> pulls;
  uint64_t seed = 1;
  bool any() const { return to_host.any() || to_fpga.any() || !pulls.empty(); }
};

// The command-line form, shared by eskin-vboard and eskin simulate
// (`direction`: both, to-host, to-fpga; `pulls`: AT_MS:FOR_MS each).
// Throws std::invalid_argument naming the option and what it expects; an
// option that would not act (a seed or a direction with no fault on) is
// refused too. An empty string is an option not given.
struct LineFaultArgs {
  std::string ber, drop_rate, insert_rate, direction, seed;
  std::vector<std::string> pulls;
};
LineFaultOptions parse_line_faults(const LineFaultArgs& a);
// The same options back as arguments of eskin-vboard (`--ber 1e-05 ...`).
std::vector<std::string> line_fault_args(const LineFaultOptions& o);

struct DirectionCounts {
  uint64_t chars = 0;  // characters that started on the wire
  uint64_t start_flips = 0, data_flips = 0, stop_flips = 0;
  uint64_t dropped = 0, inserted = 0;
  uint64_t pulled_chars = 0;  // characters on the wire (in part) while the cable was out
  uint64_t flips() const { return start_flips + data_flips + stop_flips; }
  // Faults that can damage a character the receiver takes: flips, drops,
  // inserts (a pull is counted apart).
  uint64_t faults() const { return flips() + dropped + inserted; }
};

// An 8N1 receiver on the FPGA's uart_txd pin: the bytes it read.
struct UartTap {
  void sample(double t, bool level) {
    if (const int b = rx.sample(t, level); b >= 0) bytes.push_back(uint8_t(b));
  }
  UartRxModel rx;
  std::vector<uint8_t> bytes;
};

struct LineCounts {
  DirectionCounts to_host, to_fpga;
  uint64_t pulls = 0;  // pulls begun
};

nlohmann::json to_json(const DirectionCounts& c);
nlohmann::json to_json(const LineCounts& c);
LineCounts line_counts_from_json(const nlohmann::json& j);

class LineFaults {
 public:
  explicit LineFaults(const LineFaultOptions& o = {});
  ~LineFaults();
  LineFaults(const LineFaults&) = delete;
  LineFaults& operator=(const LineFaults&) = delete;

  bool active() const { return active_; }
  // The bit time of the transmitter on each side (ns): the FPGA's UART for
  // to_host, the host's rate for to_fpga.
  void set_bit_ns(LineDir d, double bit_ns) { dir(d).bit_ns = bit_ns; }

  // The level the far end sees at time t (ns, non-decreasing) when the
  // near end drives `level`.
  bool wire(LineDir d, double t, bool level) {
    if (d == LineDir::to_host && tap_) tap_rx_.sample(t, level);
    if (!active_) return level;
    return wire_slow(d, t, level);
  }

  // What happens to the next character crossing the bridge in direction d:
  // drop it, and/or put a random byte (`inserted`, >= 0) before it.
  struct Fate {
    bool drop = false;
    int inserted = -1;
  };
  Fate fate(LineDir d);

  // Writes the FPGA's own bytes on uart_txd, before any fault, to `path`
  // (a tap on the FPGA's pin): what a fault-free line would have delivered.
  void tap_to(const std::string& path, double fpga_bit_ns);
  void flush_tap();

  const LineCounts& counts() const { return counts_; }

 private:
  struct Dir {
    DirectionFaults f;
    double bit_ns = 0;
    bool in_char = false, pulled_counted = false;
    double t0 = 0;
    uint16_t mask = 0;               // bits of the current character to flip
    uint64_t bit_index = 0;          // wire bits begun so far
    uint64_t next_flip = UINT64_MAX; // index of the next bit to flip
    std::mt19937_64 bits, chars;
    DirectionCounts* n = nullptr;
  };
  Dir& dir(LineDir d) { return dirs_[int(d)]; }
  bool wire_slow(LineDir d, double t, bool level);
  uint64_t gap(Dir& s);
  bool pulled(double t);

  bool active_ = false;
  Dir dirs_[2];
  std::vector<CablePull> pulls_;  // sorted
  size_t pull_ = 0;               // first pull not yet over
  bool in_pull_ = false;
  LineCounts counts_;
  std::FILE* tap_ = nullptr;
  UartTap tap_rx_;
};

}  // namespace eskin::vboard
