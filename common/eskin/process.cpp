#include "eskin/process.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <thread>

extern char** environ;

namespace eskin {

int run_logged(const std::vector<std::string>& argv, const std::string& log, LogMode mode) {
  return run_logged(argv, log, mode, RunContext{});
}

int run_logged(const std::vector<std::string>& argv, const std::string& log, LogMode mode,
               const RunContext& ctx) {
  if (argv.empty()) {
    errno = EINVAL;
    return -1;
  }
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  // The caller's environment with ctx.env's names replaced.
  std::vector<std::string> env_text;
  for (char** e = environ; *e; ++e) {
    const char* eq = std::strchr(*e, '=');
    const std::string name(*e, eq ? size_t(eq - *e) : std::strlen(*e));
    bool replaced = false;
    for (const auto& kv : ctx.env) replaced = replaced || kv.first == name;
    if (!replaced) env_text.emplace_back(*e);
  }
  for (const auto& kv : ctx.env) env_text.push_back(kv.first + "=" + kv.second);
  std::vector<char*> envp;
  for (auto& e : env_text) envp.push_back(e.data());
  envp.push_back(nullptr);

  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  // The log opens before the change of directory: a relative log is the
  // caller's.
  const int flags = O_WRONLY | O_CREAT | (mode == LogMode::Append ? O_APPEND : O_TRUNC);
  posix_spawn_file_actions_addopen(&fa, STDOUT_FILENO, log.c_str(), flags, 0644);
  posix_spawn_file_actions_adddup2(&fa, STDOUT_FILENO, STDERR_FILENO);
  if (!ctx.cwd.empty()) posix_spawn_file_actions_addchdir_np(&fa, ctx.cwd.c_str());
  pid_t pid = -1;
  const int e = posix_spawnp(&pid, args[0], &fa, nullptr, args.data(), envp.data());
  posix_spawn_file_actions_destroy(&fa);
  if (e != 0) {
    errno = e;
    return -1;
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return -1;
  return status;
}

std::string find_on_path(const std::string& tool) {
  const char* path = std::getenv("PATH");
  std::stringstream ss(path ? path : "");
  for (std::string dir; std::getline(ss, dir, ':');) {
    if (dir.empty()) continue;
    const std::string p = dir + "/" + tool;
    if (::access(p.c_str(), X_OK) == 0) return p;
  }
  return "";
}

std::string printable_command(const std::vector<std::string>& argv) {
  std::string line;
  for (const auto& a : argv) {
    line += line.empty() ? "'" : " '";
    for (char c : a) line += c == '\'' ? std::string("'\\''") : std::string(1, c);
    line += "'";
  }
  return line;
}

ChildProcess::ChildProcess(const std::vector<std::string>& argv, const std::string& out,
                           const std::string& err) {
  if (argv.empty()) {
    start_error_ = EINVAL;
    return;
  }
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&fa, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = -1;
  start_error_ = posix_spawn(&pid, args[0], &fa, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  if (start_error_ == 0) pid_ = pid;
}

ChildProcess::~ChildProcess() {
  if (started() && status_ < 0) {
    ::kill(pid_, SIGKILL);
    wait_exit(std::chrono::seconds(10));
  }
}

void ChildProcess::signal(int sig) {
  if (started() && status_ < 0) ::kill(pid_, sig);
}

int ChildProcess::poll_exit() {
  int st = 0;
  if (started() && status_ < 0 && ::waitpid(pid_, &st, WNOHANG) == pid_)
    status_ = WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
  return status_;
}

int ChildProcess::wait_exit(std::chrono::milliseconds timeout) {
  const auto end = std::chrono::steady_clock::now() + timeout;
  while (poll_exit() < 0 && std::chrono::steady_clock::now() < end)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  return status_;
}

}  // namespace eskin
