// Golden seed-000 contact localisation.
//
// Calibration scan: presses of known force F_cal at the nodes of a regular
// grid (pitch p) over the skin, each giving the baseline-subtracted field of
// all sensors (one 3*S vector). Field table: the scan is refined s times in
// each direction by universal Kriging with a linear drift (the seed's linear
// universal Kriging) and the generalised covariance |h|^3 (an intrinsic random
// function of order 1: the exact interpolator that is also the natural cubic
// thin-plate spline), applied per block of `region` x `region` scan nodes
// (the seed's 10 x 10 per region) with one ring of neighbour nodes so blocks
// join smoothly.
//
// Search: a frame's field d is matched against table entries T(x) by the
// force-scaled distance min_s |d - s T(x)|^2 = |d|^2 - (d.T)^2/|T|^2 (the
// seed's Euclidean nearest neighbour, with the press force as a free scale
// since field changes grow linearly with force): first over the coarse scan
// nodes (the rough region), then over the fine table within one scan pitch of
// the best node. The force is s * F_cal. Several contacts: the found
// contact's s T(x) is subtracted and the search repeats while the remaining
// energy is above `residual` of the frame's.
#pragma once

#include <Eigen/Dense>

#include <array>
#include <vector>

namespace eskin::golden {

struct ScanGrid {
  double x0 = 0, y0 = 0;  // the first node's position (mm)
  double pitch_mm = 1;
  int nx = 0, ny = 0;
  double force_n = 1;     // F_cal of every scan press
};

struct Contact {
  double x_mm = 0, y_mm = 0, force_n = 0;
};

class ContactLocator {
 public:
  // scan[j * nx + i]: the field vector of the press at node (i, j).
  ContactLocator(const ScanGrid& grid, const std::vector<Eigen::VectorXd>& scan, int subdivision,
                 int region = 10);
  // Up to max_contacts contacts in the frame (strongest first).
  std::vector<Contact> locate(const Eigen::VectorXd& d, int max_contacts = 1,
                              double residual = 0.05) const;
  int table_nx() const { return fnx_; }
  int table_ny() const { return fny_; }
  double table_pitch_mm() const { return grid_.pitch_mm / sub_; }
  // The table entry at fine node (i, j) and its position.
  const Eigen::VectorXd& entry(int i, int j) const { return table_[size_t(j) * size_t(fnx_) + size_t(i)]; }
  std::array<double, 2> position(int i, int j) const;

 private:
  void build(const std::vector<Eigen::VectorXd>& scan, int region);
  Contact best(const Eigen::VectorXd& d, double& score) const;

  ScanGrid grid_;
  int sub_;
  int fnx_, fny_;
  std::vector<Eigen::VectorXd> scan_, table_;
};

}  // namespace eskin::golden
