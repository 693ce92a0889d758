// A whole file as a string ("" when it cannot be read): for the benchmarks'
// logs, reports and CSV parts, and their tests.
#pragma once

#include <fstream>
#include <sstream>
#include <string>

namespace eskin::bench {

inline std::string read_text(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

}  // namespace eskin::bench
