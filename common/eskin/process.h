// Runs a program from an argument vector, never through a shell: each
// argument reaches it as it is, whatever quotes or spaces it holds.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace eskin {

enum class LogMode { Truncate, Append };

// Where a run starts and what it sees besides the caller's environment.
struct RunContext {
  std::string cwd;                                         // "" : the caller's
  std::vector<std::pair<std::string, std::string>> env;    // set (or replaced) for the child
};

// Runs argv[0] (a path, or a name looked up on PATH) with the arguments
// argv, its stdout and stderr into `log` (truncated or appended to); waits
// for it. Returns the wait status, or -1 if it could not be started (errno
// set).
int run_logged(const std::vector<std::string>& argv, const std::string& log,
               LogMode mode = LogMode::Truncate);
int run_logged(const std::vector<std::string>& argv, const std::string& log, LogMode mode,
               const RunContext& ctx);

// The path of `tool` found on PATH ("" if none is executable there).
std::string find_on_path(const std::string& tool);

// `argv` as one line a user can read or paste into a POSIX shell (each
// argument single-quoted); for messages only, never to run.
std::string printable_command(const std::vector<std::string>& argv);

}  // namespace eskin
