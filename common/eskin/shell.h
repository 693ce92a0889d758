// Shell command lines built from arguments: the one quoting helper, for the
// latency bench's Verilator builds (their command line sets OBJCACHE from
// the shell's `command -v ccache`) and harness runs, and for printing an
// argument vector as a command a user can paste. Tools that need no shell run from an argument
// vector (eskin/process.h).
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
