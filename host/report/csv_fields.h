// Comma-separated number lists shared by the NDJSON and CSV writers of the
// CLI and the reports, so every command prints amplitudes and taxels the
// same way (%.6g).
#pragma once

#include <fmt/format.h>

#include <Eigen/Dense>
#include <string>

namespace eskin::report {

inline std::string join(const Eigen::VectorXd& v) {
  std::string s;
  for (int i = 0; i < v.size(); ++i) s += fmt::format("{}{:.6g}", i ? "," : "", v[i]);
  return s;
}

// Row-major, the taxel order used everywhere (index = row * cols + col).
inline std::string join(const Eigen::MatrixXd& m) {
  std::string s;
  for (int i = 0; i < m.rows(); ++i)
    for (int j = 0; j < m.cols(); ++j) s += fmt::format("{}{:.6g}", (i || j) ? "," : "", m(i, j));
  return s;
}

}  // namespace eskin::report
