#include "sim/vboard/vboard_process.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace eskin::vboard {

VboardProcess::VboardProcess(const std::string& exe, const std::vector<std::string>& args) {
  int p[2];
  if (pipe(p) != 0) throw std::runtime_error(std::string("pipe: ") + std::strerror(errno));
  std::vector<std::string> all{exe};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_ = fork();
  if (pid_ < 0) throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
  if (pid_ == 0) {
    dup2(p[1], 1);
    close(p[0]);
    close(p[1]);
    setenv("SYSTEMC_DISABLE_COPYRIGHT_MESSAGE", "1", 1);
    execv(exe.c_str(), argv.data());
    std::fprintf(stderr, "cannot run %s: %s\n", exe.c_str(), std::strerror(errno));
    _exit(127);
  }
  close(p[1]);
  out_ = p[0];
  fcntl(out_, F_SETFL, O_NONBLOCK);
  while (ready_.is_null())
    if (!read_lines(-1))
      throw std::runtime_error("the virtual board " + exe + " exited before it was ready (status " +
                               std::to_string(wait()) + ")");
}

VboardProcess::~VboardProcess() {
  if (!exited_ && pid_ > 0) {
    kill(pid_, SIGTERM);
    wait();
  }
  if (out_ >= 0) close(out_);
}

// Reads what the child printed; false at end of file.
bool VboardProcess::read_lines(int timeout_ms) {
  pollfd pf{out_, POLLIN, 0};
  if (poll(&pf, 1, timeout_ms) <= 0) return true;
  char b[65536];
  const ssize_t n = read(out_, b, sizeof b);
  if (n == 0) return false;
  if (n < 0) return errno == EAGAIN || errno == EINTR;
  buf_.append(b, size_t(n));
  for (size_t nl; (nl = buf_.find('\n')) != std::string::npos;) {
    const std::string line = buf_.substr(0, nl);
    buf_.erase(0, nl + 1);
    if (line.empty() || line[0] != '{') continue;
    nlohmann::json j = nlohmann::json::parse(line);
    const std::string ev = j.value("event", "");
    if (ev == "ready") ready_ = std::move(j);
    if (ev == "done") done_ = std::move(j);
  }
  return true;
}

bool VboardProcess::poll_done() {
  if (done_.is_null() && !read_lines(0) && done_.is_null())
    throw std::runtime_error("the virtual board exited without finishing (status " +
                             std::to_string(wait()) + ")");
  return !done_.is_null();
}

int VboardProcess::wait() {
  if (!exited_) {
    // Its last lines first: a done line longer than the pipe holds would
    // keep the child from exiting, and done() must hold it afterwards.
    while (out_ >= 0 && read_lines(100)) {
    }
    int st = 0;
    while (waitpid(pid_, &st, 0) < 0 && errno == EINTR) {
    }
    exited_ = true;
    status_ = WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
  }
  return status_;
}

}  // namespace eskin::vboard
