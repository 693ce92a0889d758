#include "host/golden/contact_locate.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace eskin::golden {
namespace {

double cov(double h) { return h * h * h; }  // generalised covariance |h|^3

// Force-scaled match: returns the residual and the scale s (NaN-free; a
// table entry with no field or an opposite field does not match).
double match(const Eigen::VectorXd& d, const Eigen::VectorXd& t, double& s) {
  const double tt = t.squaredNorm(), dt = d.dot(t);
  if (!(tt > 0) || dt <= 0) {
    s = 0;
    return d.squaredNorm();
  }
  s = dt / tt;
  return d.squaredNorm() - dt * s;
}

}  // namespace

ContactLocator::ContactLocator(const ScanGrid& grid, const std::vector<Eigen::VectorXd>& scan,
                               int subdivision, int region)
    : grid_(grid), sub_(subdivision), fnx_(grid.nx * subdivision), fny_(grid.ny * subdivision),
      scan_(scan) {
  if (grid.nx < 2 || grid.ny < 2 || scan.size() != size_t(grid.nx) * size_t(grid.ny))
    throw std::invalid_argument("ContactLocator: expected an nx x ny scan (at least 2 x 2)");
  build(scan, region);
}

std::array<double, 2> ContactLocator::position(int i, int j) const {
  // Fine nodes split each scan cell [node - p/2, node + p/2] into sub_ parts.
  const double fp = grid_.pitch_mm / sub_;
  return {grid_.x0 - grid_.pitch_mm / 2 + (i + 0.5) * fp, grid_.y0 - grid_.pitch_mm / 2 + (j + 0.5) * fp};
}

void ContactLocator::build(const std::vector<Eigen::VectorXd>& scan, int region) {
  table_.assign(size_t(fnx_) * size_t(fny_), Eigen::VectorXd());
  const Eigen::Index dims = scan.front().size();
  for (int by = 0; by < grid_.ny; by += region)
    for (int bx = 0; bx < grid_.nx; bx += region) {
      // Nodes of the block plus one ring of neighbours.
      const int i0 = std::max(0, bx - 1), i1 = std::min(grid_.nx, bx + region + 1);
      const int j0 = std::max(0, by - 1), j1 = std::min(grid_.ny, by + region + 1);
      std::vector<std::array<double, 2>> pts;
      Eigen::MatrixXd vals(0, dims);
      std::vector<const Eigen::VectorXd*> v;
      for (int j = j0; j < j1; ++j)
        for (int i = i0; i < i1; ++i) {
          pts.push_back({grid_.x0 + i * grid_.pitch_mm, grid_.y0 + j * grid_.pitch_mm});
          v.push_back(&scan[size_t(j) * size_t(grid_.nx) + size_t(i)]);
        }
      const Eigen::Index n = Eigen::Index(pts.size());
      // Universal Kriging system [K P; P^T 0] [w; mu] = [k; p] with drift 1, x, y.
      Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n + 3, n + 3);
      for (Eigen::Index r = 0; r < n; ++r) {
        for (Eigen::Index c = 0; c < n; ++c)
          a(r, c) = cov(std::hypot(pts[size_t(r)][0] - pts[size_t(c)][0], pts[size_t(r)][1] - pts[size_t(c)][1]) /
                        grid_.pitch_mm);
        a(r, n) = a(n, r) = 1;
        a(r, n + 1) = a(n + 1, r) = (pts[size_t(r)][0] - pts[0][0]) / grid_.pitch_mm;
        a(r, n + 2) = a(n + 2, r) = (pts[size_t(r)][1] - pts[0][1]) / grid_.pitch_mm;
      }
      const Eigen::PartialPivLU<Eigen::MatrixXd> lu(a);
      Eigen::MatrixXd z(n, dims);
      for (Eigen::Index r = 0; r < n; ++r) z.row(r) = v[size_t(r)]->transpose();
      // Fine nodes inside this block.
      const int fi0 = bx * sub_, fi1 = std::min(grid_.nx, bx + region) * sub_;
      const int fj0 = by * sub_, fj1 = std::min(grid_.ny, by + region) * sub_;
      Eigen::VectorXd rhs(n + 3);
      for (int fj = fj0; fj < fj1; ++fj)
        for (int fi = fi0; fi < fi1; ++fi) {
          const auto p = position(fi, fj);
          for (Eigen::Index r = 0; r < n; ++r)
            rhs(r) = cov(std::hypot(p[0] - pts[size_t(r)][0], p[1] - pts[size_t(r)][1]) / grid_.pitch_mm);
          rhs(n) = 1;
          rhs(n + 1) = (p[0] - pts[0][0]) / grid_.pitch_mm;
          rhs(n + 2) = (p[1] - pts[0][1]) / grid_.pitch_mm;
          const Eigen::VectorXd w = lu.solve(rhs);
          table_[size_t(fj) * size_t(fnx_) + size_t(fi)] = z.transpose() * w.head(n);
        }
    }
}

Contact ContactLocator::best(const Eigen::VectorXd& d, double& score) const {
  // Rough: the best coarse scan node.
  double best = std::numeric_limits<double>::infinity(), s = 0;
  int bi = 0, bj = 0;
  for (int j = 0; j < grid_.ny; ++j)
    for (int i = 0; i < grid_.nx; ++i) {
      const double r = match(d, scan_[size_t(j) * size_t(grid_.nx) + size_t(i)], s);
      if (r < best) best = r, bi = i, bj = j;
    }
  // Fine: the table within one scan pitch of it.
  const int ci = bi * sub_ + sub_ / 2, cj = bj * sub_ + sub_ / 2, w = sub_ + sub_ / 2;
  best = std::numeric_limits<double>::infinity();
  Contact c;
  for (int j = std::max(0, cj - w); j < std::min(fny_, cj + w + 1); ++j)
    for (int i = std::max(0, ci - w); i < std::min(fnx_, ci + w + 1); ++i) {
      const double r = match(d, entry(i, j), s);
      if (r < best) {
        best = r;
        const auto p = position(i, j);
        c = {p[0], p[1], s * grid_.force_n};
      }
    }
  score = best;
  return c;
}

std::vector<Contact> ContactLocator::locate(const Eigen::VectorXd& d, int max_contacts,
                                            double residual) const {
  std::vector<Contact> out;
  Eigen::VectorXd rest = d;
  const double e0 = d.squaredNorm();
  for (int k = 0; k < max_contacts && rest.squaredNorm() > residual * e0; ++k) {
    double score;
    const Contact c = best(rest, score);
    if (c.force_n <= 0) break;
    out.push_back(c);
    // Remove this contact's field: the table entry at its position, scaled.
    const double fp = table_pitch_mm();
    const int i = std::clamp(int(std::floor((c.x_mm - (grid_.x0 - grid_.pitch_mm / 2)) / fp)), 0, fnx_ - 1);
    const int j = std::clamp(int(std::floor((c.y_mm - (grid_.y0 - grid_.pitch_mm / 2)) / fp)), 0, fny_ - 1);
    rest -= (c.force_n / grid_.force_n) * entry(i, j);
  }
  return out;
}

}  // namespace eskin::golden
