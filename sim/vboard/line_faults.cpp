#include "sim/vboard/line_faults.h"

#include "eskin/number_text.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

namespace eskin::vboard {
namespace {

// A character lasts 10 bit times; it is taken as over a quarter bit early,
// so that a transmitter a little faster than its nominal rate (CPB rounded)
// starts its next character on a fresh one. The receivers sample in the
// middle of each bit, so the stop bit's flip still covers their sample.
constexpr double kCharBits = 9.75;

// One stream per direction and kind, from the one seed (splitmix64).
uint64_t derive(uint64_t seed, uint64_t k) {
  uint64_t z = seed + 0x9E3779B97F4A7C15ull * (k + 1);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

double number(const std::string& opt, const std::string& v, const char* expected) {
  const char* s = v.c_str();
  char* end = nullptr;
  errno = 0;
  const double x = std::strtod(s, &end);
  if (v.empty() || end == s || *end != '\0' || errno == ERANGE || !std::isfinite(x))
    throw std::invalid_argument(opt + ": expected " + expected + ", got '" + v + "'");
  return x;
}

double rate(const std::string& opt, const std::string& v, const char* per) {
  const std::string what = std::string("a probability per ") + per + " in [0, 1), e.g. 1e-5";
  const double x = number(opt, v, what.c_str());
  if (x < 0 || x >= 1)
    throw std::invalid_argument(opt + ": expected " + what + ", got '" + v + "'");
  return x;
}


}  // namespace

nlohmann::json to_json(const DirectionCounts& c) {
  return {{"chars", c.chars},         {"start_flips", c.start_flips}, {"data_flips", c.data_flips},
          {"stop_flips", c.stop_flips}, {"dropped", c.dropped},       {"inserted", c.inserted},
          {"pulled_chars", c.pulled_chars}};
}

namespace {

DirectionCounts dir_from(const nlohmann::json& j) {
  DirectionCounts c;
  c.chars = j.at("chars");
  c.start_flips = j.at("start_flips");
  c.data_flips = j.at("data_flips");
  c.stop_flips = j.at("stop_flips");
  c.dropped = j.at("dropped");
  c.inserted = j.at("inserted");
  c.pulled_chars = j.at("pulled_chars");
  return c;
}

}  // namespace

LineFaultOptions parse_line_faults(const LineFaultArgs& a) {
  LineFaultOptions o;
  DirectionFaults f;
  if (!a.ber.empty()) f.ber = rate("--ber", a.ber, "wire bit");
  if (!a.drop_rate.empty()) f.drop_rate = rate("--drop-rate", a.drop_rate, "character");
  if (!a.insert_rate.empty()) f.insert_rate = rate("--insert-rate", a.insert_rate, "character");
  const std::string dir = a.direction.empty() ? "both" : a.direction;
  if (dir != "both" && dir != "to-host" && dir != "to-fpga")
    throw std::invalid_argument("--fault-direction: expected both, to-host or to-fpga, got '" +
                                a.direction + "'");
  if (!a.direction.empty() && !f.any())
    throw std::invalid_argument(
        "--fault-direction: it directs --ber, --drop-rate and --insert-rate, and none of them is "
        "above 0");
  if (dir != "to-fpga") o.to_host = f;
  if (dir != "to-host") o.to_fpga = f;
  for (const std::string& p : a.pulls) {
    const size_t colon = p.find(':');
    const char* expected = "AT_MS:FOR_MS (simulated ms, AT_MS >= 0, FOR_MS > 0), e.g. 100:20";
    if (colon == std::string::npos)
      throw std::invalid_argument(std::string("--pull-cable: expected ") + expected + ", got '" +
                                  p + "'");
    CablePull c;
    c.at_ms = number("--pull-cable", p.substr(0, colon), expected);
    c.for_ms = number("--pull-cable", p.substr(colon + 1), expected);
    if (c.at_ms < 0 || c.for_ms <= 0)
      throw std::invalid_argument(std::string("--pull-cable: expected ") + expected + ", got '" +
                                  p + "'");
    o.pulls.push_back(c);
  }
  if (!a.seed.empty()) {
    const char* s = a.seed.c_str();
    char* end = nullptr;
    errno = 0;
    const unsigned long long v = std::strtoull(s, &end, 10);
    if (end == s || *end != '\0' || errno == ERANGE || a.seed[0] == '-')
      throw std::invalid_argument("--fault-seed: expected an unsigned 64-bit integer, got '" +
                                  a.seed + "'");
    if (!o.to_host.any() && !o.to_fpga.any())
      throw std::invalid_argument(
          "--fault-seed: it seeds --ber, --drop-rate and --insert-rate, and none of them is above "
          "0");
    o.seed = v;
  }
  return o;
}

std::vector<std::string> line_fault_args(const LineFaultOptions& o) {
  std::vector<std::string> a;
  const DirectionFaults& h = o.to_host;
  const DirectionFaults& f = o.to_fpga;
  const bool same = h.ber == f.ber && h.drop_rate == f.drop_rate && h.insert_rate == f.insert_rate;
  const DirectionFaults& on = h.any() ? h : f;
  if (on.any()) {
    if (!same && h.any() && f.any())
      throw std::logic_error("line_fault_args: different faults each way have no command line");
    if (on.ber > 0) a.insert(a.end(), {"--ber", shortest_text(on.ber)});
    if (on.drop_rate > 0) a.insert(a.end(), {"--drop-rate", shortest_text(on.drop_rate)});
    if (on.insert_rate > 0) a.insert(a.end(), {"--insert-rate", shortest_text(on.insert_rate)});
    if (!same) a.insert(a.end(), {"--fault-direction", h.any() ? "to-host" : "to-fpga"});
    a.insert(a.end(), {"--fault-seed", std::to_string(o.seed)});
  }
  for (const CablePull& p : o.pulls)
    a.insert(a.end(), {"--pull-cable", shortest_text(p.at_ms) + ":" + shortest_text(p.for_ms)});
  return a;
}

nlohmann::json to_json(const LineCounts& c) {
  return {{"to_host", to_json(c.to_host)}, {"to_fpga", to_json(c.to_fpga)}, {"pulls", c.pulls}};
}

LineCounts line_counts_from_json(const nlohmann::json& j) {
  LineCounts c;
  c.to_host = dir_from(j.at("to_host"));
  c.to_fpga = dir_from(j.at("to_fpga"));
  c.pulls = j.at("pulls");
  return c;
}

LineFaults::LineFaults(const LineFaultOptions& o) : active_(o.any()), pulls_(o.pulls) {
  std::sort(pulls_.begin(), pulls_.end(),
            [](const CablePull& a, const CablePull& b) { return a.at_ms < b.at_ms; });
  DirectionCounts* n[2] = {&counts_.to_host, &counts_.to_fpga};
  const DirectionFaults* f[2] = {&o.to_host, &o.to_fpga};
  for (int d = 0; d < 2; ++d) {
    Dir& s = dirs_[d];
    s.f = *f[d];
    s.n = n[d];
    s.bits.seed(derive(o.seed, 2 * uint64_t(d)));
    s.chars.seed(derive(o.seed, 2 * uint64_t(d) + 1));
    s.next_flip = s.f.ber > 0 ? gap(s) : UINT64_MAX;
  }
}

LineFaults::~LineFaults() {
  if (tap_) {
    flush_tap();
    std::fclose(tap_);
  }
}

// Bits until the next flipped one: each bit flips with probability ber,
// independently (geometric gaps), so a character's flips cost nothing to
// draw when there are none.
uint64_t LineFaults::gap(Dir& s) {
  std::geometric_distribution<uint64_t> g(s.f.ber);
  return g(s.bits);
}

bool LineFaults::pulled(double t) {
  while (pull_ < pulls_.size() && t >= 1e6 * (pulls_[pull_].at_ms + pulls_[pull_].for_ms)) {
    ++pull_;
    in_pull_ = false;
  }
  if (pull_ >= pulls_.size() || t < 1e6 * pulls_[pull_].at_ms) return false;
  if (!in_pull_) {
    in_pull_ = true;
    ++counts_.pulls;
  }
  return true;
}

bool LineFaults::wire_slow(LineDir d, double t, bool level) {
  Dir& s = dir(d);
  if (s.in_char && t >= s.t0 + kCharBits * s.bit_ns) s.in_char = false;
  if (!s.in_char && !level && s.bit_ns > 0) {
    s.in_char = true;
    s.pulled_counted = false;
    s.t0 = t;
    s.mask = 0;
    ++s.n->chars;
    while (s.next_flip < s.bit_index + 10) {
      const int k = int(s.next_flip - s.bit_index);
      s.mask |= uint16_t(1u << k);
      ++(k == 0 ? s.n->start_flips : k == 9 ? s.n->stop_flips : s.n->data_flips);
      s.next_flip += 1 + gap(s);
    }
    s.bit_index += 10;
  }
  bool out = level;
  if (s.in_char && s.mask) {
    const int k = int((t - s.t0) / s.bit_ns);
    if (k < 10 && ((s.mask >> k) & 1)) out = !out;
  }
  if (!pulls_.empty() && pulled(t)) {
    if (s.in_char && !s.pulled_counted) {
      ++s.n->pulled_chars;
      s.pulled_counted = true;
    }
    return true;
  }
  return out;
}

LineFaults::Fate LineFaults::fate(LineDir d) {
  Fate r;
  Dir& s = dir(d);
  if (!active_ || (s.f.drop_rate == 0 && s.f.insert_rate == 0)) return r;
  std::uniform_real_distribution<double> u(0.0, 1.0);
  if (s.f.insert_rate > 0 && u(s.chars) < s.f.insert_rate) {
    r.inserted = int(s.chars() & 0xFF);
    ++s.n->inserted;
  }
  if (s.f.drop_rate > 0 && u(s.chars) < s.f.drop_rate) {
    r.drop = true;
    ++s.n->dropped;
  }
  return r;
}

void LineFaults::tap_to(const std::string& path, double fpga_bit_ns) {
  tap_ = std::fopen(path.c_str(), "wb");
  if (!tap_)
    throw std::runtime_error("--tap-to-host: cannot write '" + path + "': " + std::strerror(errno));
  tap_rx_.rx.set_bit_ns(fpga_bit_ns);
}

void LineFaults::flush_tap() {
  if (!tap_ || tap_rx_.bytes.empty()) return;
  // Flushed each time: the host reads the file once the done line is out,
  // before the board exits.
  if (std::fwrite(tap_rx_.bytes.data(), 1, tap_rx_.bytes.size(), tap_) != tap_rx_.bytes.size() ||
      std::fflush(tap_) != 0)
    throw std::runtime_error("--tap-to-host: write failed: " + std::string(std::strerror(errno)));
  tap_rx_.bytes.clear();
}

}  // namespace eskin::vboard
