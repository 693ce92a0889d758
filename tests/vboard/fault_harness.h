// What the fault tests (line_faults_test.cpp, board_faults_test.cpp) share:
// a command train whose every command the FPGA answers, and running the
// binaries with their output in a log.
#pragma once

#include <sys/wait.h>

#include <cstdint>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "eskin/process.h"
#include "host/link/link_encoder.h"

namespace fault_harness {

// n SET_THRESHOLDs for taxel id 9, which the default build does not have:
// each is rejected (bad index) with a STATUS reply naming its seq (0, 1,
// ...). 64 zero bytes after each space them 76 characters apart, 253.3
// us at 3 Mbaud, so that a fault lands in one command.
inline std::vector<std::vector<uint8_t>> rejected_commands(int n) {
  eskin::link::LinkEncoder enc;
  std::vector<std::vector<uint8_t>> cmds;
  for (int i = 0; i < n; ++i) {
    std::vector<uint8_t> c = enc.set_threshold(9, uint16_t(i));
    c.insert(c.end(), 64, 0);
    cmds.push_back(c);
  }
  return cmds;
}

inline int exit_of(const std::vector<std::string>& argv, const std::string& log) {
  const int st = eskin::run_logged(argv, log);
  return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

inline std::string slurp(const std::string& p) {
  std::ifstream in(p);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace fault_harness
