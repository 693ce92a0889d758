// Starts an eskin-vboard executable as a child process and follows its
// JSON status lines (vboard_main.cpp): `ready` (the pty exists) and `done`
// (every byte for the host is in the pty, with the run's figures). The
// host talks to the board only through the pty, as to a real board.
#pragma once

#include <sys/types.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace eskin::vboard {

class VboardProcess {
 public:
  // Runs `exe args...`; throws std::runtime_error if it cannot start or
  // exits before its ready line (with what it printed on stderr, which
  // it is left to print: the board's messages are the user's).
  VboardProcess(const std::string& exe, const std::vector<std::string>& args);
  ~VboardProcess();  // ends the child if it still runs
  VboardProcess(const VboardProcess&) = delete;
  VboardProcess& operator=(const VboardProcess&) = delete;

  const nlohmann::json& ready() const { return ready_; }
  std::string pty() const { return ready_.at("pty").get<std::string>(); }
  // Non-blocking: true once the done line has arrived (then done() holds it).
  bool poll_done();
  const nlohmann::json& done() const { return done_; }
  // Reads the child's remaining status lines (done() then holds its done
  // line, if it printed one) and waits for it to exit; returns its exit
  // status (128 + signal).
  int wait();

 private:
  bool read_lines(int timeout_ms);
  pid_t pid_ = -1;
  int out_ = -1;
  std::string buf_;
  nlohmann::json ready_, done_;
  bool exited_ = false;
  int status_ = 0;
};

}  // namespace eskin::vboard
