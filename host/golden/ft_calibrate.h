// Golden seed-002 six-axis force/torque: W = C * dB, dB the nine baseline-
// subtracted field components of the three cells (B1x B1y B1z B2x ... B3z),
// W = (Fx, Fy, Fz, Tx, Ty, Tz). C (6x9) is fitted to calibration presses by
// linear least squares: C = W B^+ with B^+ = B^T (B B^T)^-1 the pseudo-inverse
// of the 9xN matrix of calibration fields (computed by an orthogonal
// decomposition, not by forming the normal equations).
#pragma once

#include <Eigen/Dense>

#include <vector>

namespace eskin::golden {

using Vec9 = Eigen::Matrix<double, 9, 1>;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using FtMatrix = Eigen::Matrix<double, 6, 9>;

// Needs at least 9 presses whose fields span the 9 dimensions.
FtMatrix ft_fit(const std::vector<Vec9>& db_ut, const std::vector<Vec6>& wrench);
inline Vec6 ft_apply(const FtMatrix& c, const Vec9& db_ut) { return c * db_ut; }

}  // namespace eskin::golden
