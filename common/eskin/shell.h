// Shell command lines built from arguments: the one quoting helper of the
// code that runs the project's tools through std::system (the bitstream
// flow, the latency bench's Verilator builds, the virtual boards' builds).
#pragma once

#include <string>

namespace eskin {

// `s` as one POSIX shell word: single-quoted, each ' written as '\''.
inline std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

}  // namespace eskin
