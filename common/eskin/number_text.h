// The shortest text that reads back as a double (std::to_chars: "900",
// "0.01", "1e-05"), for option values written back onto a command line.
#pragma once

#include <charconv>
#include <string>

namespace eskin {

inline std::string shortest_text(double x) {
  char b[32];
  const auto r = std::to_chars(b, b + sizeof b, x);
  return std::string(b, r.ptr);
}

}  // namespace eskin
