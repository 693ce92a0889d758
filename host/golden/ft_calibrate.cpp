#include "host/golden/ft_calibrate.h"

#include <stdexcept>
#include <string>

namespace eskin::golden {

FtMatrix ft_fit(const std::vector<Vec9>& db, const std::vector<Vec6>& w) {
  if (db.size() != w.size() || db.size() < 9)
    throw std::invalid_argument("ft_fit: expected at least 9 calibration presses with one wrench each, got " +
                                std::to_string(db.size()) + " fields and " + std::to_string(w.size()) + " wrenches");
  Eigen::MatrixXd b(9, Eigen::Index(db.size())), f(6, Eigen::Index(db.size()));
  for (size_t i = 0; i < db.size(); ++i) b.col(Eigen::Index(i)) = db[i], f.col(Eigen::Index(i)) = w[i];
  // C B = W  <=>  B^T C^T = W^T: least squares over the N presses.
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(b.transpose());
  if (cod.rank() < 9)
    throw std::invalid_argument("ft_fit: the calibration fields span only " + std::to_string(cod.rank()) +
                                " of 9 dimensions: press in more directions");
  return cod.solve(f.transpose()).transpose();
}

}  // namespace eskin::golden
