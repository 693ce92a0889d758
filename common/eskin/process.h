// Runs a program from an argument vector, never through a shell: each
// argument reaches it as it is, whatever quotes or spaces it holds.
#pragma once

#include <string>
#include <vector>

namespace eskin {

enum class LogMode { Truncate, Append };

// Runs argv[0] (a path, or a name looked up on PATH) with the arguments
// argv, its stdout and stderr into `log` (truncated or appended to); waits
// for it. Returns the wait status, or -1 if it could not be started (errno
// set).
int run_logged(const std::vector<std::string>& argv, const std::string& log,
               LogMode mode = LogMode::Truncate);

}  // namespace eskin
