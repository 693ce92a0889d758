// A child process for CLI tests: the real eskin binary, stdout and stderr
// captured to files, waited for or killed by pid.
#pragma once

#include <signal.h>

#include <chrono>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "eskin/process.h"

namespace eskin::testing {

inline std::string slurp(const std::string& path) {
  std::ifstream f(path);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

// eskin::ChildProcess (common/eskin/process.h) with its output read back.
class Process : public eskin::ChildProcess {
 public:
  Process(const std::vector<std::string>& argv, const std::string& out, const std::string& err)
      : ChildProcess(argv, out, err), out_(out), err_(err) {}
  std::string out() const { return slurp(out_); }
  std::string err() const { return slurp(err_); }
  // Waits until `pred(text)` holds for stdout (or stderr).
  template <class Pred>
  bool wait_output(Pred pred, bool stderr_too, std::chrono::milliseconds timeout) const {
    const auto end = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < end) {
      if (pred(stderr_too ? err() : out())) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return false;
  }

 private:
  std::string out_, err_;
};

inline size_t count_of(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

}  // namespace eskin::testing
