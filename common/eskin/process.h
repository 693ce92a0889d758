// Runs a program from an argument vector, never through a shell: each
// argument reaches it as it is, whatever quotes or spaces it holds.
#pragma once

#include <chrono>
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

// A program run from an argument vector beside the caller, its stdout and
// stderr into files: started at construction, polled or waited for, and
// killed (SIGKILL) when destroyed while still running.
class ChildProcess {
 public:
  ChildProcess(const std::vector<std::string>& argv, const std::string& out,
               const std::string& err);
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  bool started() const { return pid_ > 0; }
  int start_error() const { return start_error_; }  // posix_spawn's error when not started
  int pid() const { return pid_; }
  void signal(int sig);
  // Exit code (128 + signal when killed) once it has ended, else -1.
  int poll_exit();
  // poll_exit() until it ends or `timeout` passes (then -1).
  int wait_exit(std::chrono::milliseconds timeout);

 private:
  int pid_ = -1;
  int start_error_ = 0;
  int status_ = -1;
};

// The path of `tool` found on PATH ("" if none is executable there).
std::string find_on_path(const std::string& tool);

// `argv` as one line a user can read or paste into a POSIX shell (each
// argument single-quoted); for messages only, never to run.
std::string printable_command(const std::vector<std::string>& argv);

}  // namespace eskin
