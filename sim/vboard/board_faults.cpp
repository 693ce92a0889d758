#include "sim/vboard/board_faults.h"

#include "eskin/number_text.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

namespace eskin::vboard {
namespace {

struct Kind {
  const char* name;
  BoardFaultKind kind;
  bool indexed;       // KIND=N
  bool needs_for;     // :FOR_MS required
};
constexpr Kind kKinds[] = {
    {"reset", BoardFaultKind::reset, false, false},
    {"reset-in-frame", BoardFaultKind::reset_in_frame, false, false},
    {"reset-in-command", BoardFaultKind::reset_in_command, false, false},
    {"adc-stuck-low", BoardFaultKind::adc_stuck_low, false, true},
    {"adc-stuck-high", BoardFaultKind::adc_stuck_high, false, true},
    {"carrier-off", BoardFaultKind::carrier_off, true, true},
    {"sda-low", BoardFaultKind::sda_low, true, true},
};
constexpr double kResetMs = 0.01;  // a button press: hundreds of clocks at any board clock

const char* kExpected =
    "KIND@AT_MS[:FOR_MS] (simulated ms) with KIND reset, reset-in-frame, reset-in-command, "
    "adc-stuck-low, adc-stuck-high, carrier-off=K or sda-low=B, e.g. adc-stuck-high@20:5";

std::invalid_argument bad(const std::string& v, const std::string& why) {
  return std::invalid_argument("--fault '" + v + "': " + why + "; expected " + kExpected);
}

double number(const std::string& v, const std::string& s, const char* what) {
  char* end = nullptr;
  errno = 0;
  const double x = std::strtod(s.c_str(), &end);
  if (s.empty() || end == s.c_str() || *end != '\0' || errno == ERANGE || !std::isfinite(x))
    throw bad(v, std::string(what) + " '" + s + "' is not a number");
  return x;
}

const Kind& kind_of(BoardFaultKind k) {
  for (const Kind& d : kKinds)
    if (d.kind == k) return d;
  throw std::logic_error("board fault kind");
}

}  // namespace

std::vector<BoardFault> parse_board_faults(const std::vector<std::string>& values) {
  std::vector<BoardFault> out;
  for (const std::string& v : values) {
    const size_t at = v.find('@');
    if (at == std::string::npos) throw bad(v, "no '@AT_MS'");
    std::string name = v.substr(0, at), index;
    if (const size_t eq = name.find('='); eq != std::string::npos) {
      index = name.substr(eq + 1);
      name = name.substr(0, eq);
    }
    const Kind* k = nullptr;
    for (const Kind& d : kKinds)
      if (name == d.name) k = &d;
    if (!k) throw bad(v, "unknown kind '" + name + "'");
    BoardFault f;
    f.kind = k->kind;
    if (k->indexed) {
      char* end = nullptr;
      const long n = std::strtol(index.c_str(), &end, 10);
      if (index.empty() || *end != '\0' || n < 0 || n > 63)
        throw bad(v, std::string(name) + " needs =N with N in 0..63");
      f.index = int(n);
    } else if (!index.empty()) {
      throw bad(v, std::string(name) + " takes no =N");
    }
    const std::string when = v.substr(at + 1);
    const size_t colon = when.find(':');
    f.at_ms = number(v, when.substr(0, colon), "AT_MS");
    if (f.at_ms < 0) throw bad(v, "AT_MS is negative");
    if (colon == std::string::npos) {
      if (k->needs_for) throw bad(v, std::string(name) + " needs :FOR_MS");
      f.for_ms = kResetMs;
    } else {
      f.for_ms = number(v, when.substr(colon + 1), "FOR_MS");
      if (f.for_ms <= 0) throw bad(v, "FOR_MS must be above 0");
    }
    out.push_back(f);
  }
  return out;
}

std::string board_fault_text(const BoardFault& f) {
  const Kind& k = kind_of(f.kind);
  std::string s = k.name;
  if (k.indexed) s += "=" + std::to_string(f.index);
  return s + "@" + shortest_text(f.at_ms) + ":" + shortest_text(f.for_ms);
}

std::vector<std::string> board_fault_args(const std::vector<BoardFault>& faults) {
  std::vector<std::string> a;
  for (const BoardFault& f : faults) a.insert(a.end(), {"--fault", board_fault_text(f)});
  return a;
}

void check_board_faults(const std::vector<BoardFault>& faults, int carriers, int buses) {
  for (const BoardFault& f : faults) {
    const std::string v = "--fault '" + board_fault_text(f) + "': ";
    if (f.on_adc() && carriers == 0)
      throw std::invalid_argument(v + "this board has no ADC (a Hall board)");
    if (f.kind == BoardFaultKind::carrier_off && f.index >= carriers)
      throw std::invalid_argument(v + "the skin has " + std::to_string(carriers) +
                                  " carriers (rows, then columns: 0.." +
                                  std::to_string(carriers - 1) + ")");
    if (f.kind == BoardFaultKind::sda_low && f.index >= buses)
      throw std::invalid_argument(v + (buses == 0 ? std::string("this board has no I2C bus")
                                                  : "the sensors are on I2C buses 0.." +
                                                        std::to_string(buses - 1)));
  }
}

nlohmann::json to_json(const std::vector<BoardFaultRecord>& r) {
  nlohmann::json j = nlohmann::json::array();
  for (const BoardFaultRecord& x : r) {
    nlohmann::json e = {{"fault", board_fault_text(x.fault)}, {"begun", x.begun}};
    if (x.begun) {
      e["begin_ns"] = x.begin_ns;
      e["end_ns"] = x.end_ns;
    }
    j.push_back(e);
  }
  return j;
}

}  // namespace eskin::vboard
