#include "taxel_reconstruct.h"

#include <algorithm>
#include <cmath>

namespace eskin::golden {

Eigen::MatrixXd taxel_product(const Eigen::VectorXd& row_amp, const Eigen::VectorXd& col_amp) {
  return row_amp * col_amp.transpose();
}

Eigen::MatrixXd taxel_g(const Eigen::VectorXd& row_g, const Eigen::VectorXd& col_g) {
  // Negative amplitudes cannot come from a magnitude; clamping keeps sqrt real
  // if a caller feeds differences or demixed estimates.
  Eigen::VectorXd r = row_g.cwiseMax(0.0), c = col_g.cwiseMax(0.0);
  return (r * c.transpose()).cwiseSqrt();
}

Eigen::MatrixXd pressure_from_g(const Eigen::MatrixXd& g, const Conductance& c) {
  return g.unaryExpr([&c](double v) { return c.inverse(v); });
}

Eigen::MatrixXd taxel_pressure(const Eigen::VectorXd& row_g, const Eigen::VectorXd& col_g,
                               const Conductance& c) {
  return pressure_from_g(taxel_g(row_g, col_g), c);
}

}  // namespace eskin::golden
