#include "host/golden/hall_decouple.h"

#include <Eigen/Dense>

#include <cmath>
#include <functional>

namespace eskin::golden {

Decoupled hall_decouple(const Vec3& b, const DecoupleParams& p) {
  Decoupled d;
  const double bx = b[0], by = b[1];
  const double z1 = p.k1 * b[2] + p.c1_ut, z2 = p.k2 * b[2] + p.c2_ut;
  if (!(z1 > 0) || !(z2 > 0)) return d;
  const double den_x = z1 * z1 + by * by - bx * bx, den_y = z1 * z1 + bx * bx - by * by;
  if (!(den_x > 0) || !(den_y > 0)) return d;
  d.rx = std::atan(2 * bx * z1 / den_x);
  d.ry = std::atan(2 * by * z1 / den_y);
  const double u = (z2 * z2 - by * by + bx * bx) / (2 * z2);
  d.sz = 0.5 * std::log(u * u + by * by);
  d.valid = true;
  return d;
}

namespace {

double poly(const std::vector<double>& c, double x) {
  double y = 0, xp = x;
  for (double k : c) y += k * xp, xp *= x;
  return y;
}

// Least-squares F = sum_j c_j x^(j+1), j < 3 (zero force at zero change).
std::vector<double> fit_poly(const std::vector<double>& x, const std::vector<double>& f,
                             double& sse) {
  Eigen::MatrixXd a(x.size(), 3);
  Eigen::VectorXd y(x.size());
  for (size_t i = 0; i < x.size(); ++i) {
    a(Eigen::Index(i), 0) = x[i];
    a(Eigen::Index(i), 1) = x[i] * x[i];
    a(Eigen::Index(i), 2) = x[i] * x[i] * x[i];
    y(Eigen::Index(i)) = f[i];
  }
  const Eigen::VectorXd c = a.colPivHouseholderQr().solve(y);
  sse = (a * c - y).squaredNorm();
  return {c(0), c(1), c(2)};
}

// Minimum of f over [lo, hi] by golden-section search (f unimodal enough).
double golden_min(const std::function<double(double)>& f, double lo, double hi) {
  const double g = (std::sqrt(5.0) - 1) / 2;
  double a = lo, b = hi, c = b - g * (b - a), d = a + g * (b - a);
  double fc = f(c), fd = f(d);
  for (int i = 0; i < 60; ++i) {
    if (fc < fd)
      b = d, d = c, fd = fc, c = b - g * (b - a), fc = f(c);
    else
      a = c, c = d, fc = fd, d = a + g * (b - a), fd = f(d);
  }
  return (a + b) / 2;
}

}  // namespace

Vec3 decoupled_force(const Decoupled& d, const Decoupled& rest, const DecoupleParams& p) {
  return {poly(p.poly[0], d.rx - rest.rx), poly(p.poly[1], d.ry - rest.ry),
          poly(p.poly[2], d.sz - rest.sz)};
}

DecoupleParams fit_decouple(const std::vector<DecoupleSample>& cal, const Vec3& rest) {
  DecoupleParams p;
  // Bz' must be positive: follow the sign of the film's rest Bz.
  p.k1 = p.k2 = rest[2] >= 0 ? 1.0 : -1.0;
  const double scale = std::fabs(rest[2]);
  // Residual of the fits of one axis for a trial offset.
  auto fit_axis = [&](DecoupleParams q, int axis, double& sse) {
    const Decoupled r0 = hall_decouple(rest, q);
    std::vector<double> x, f;
    for (const auto& s : cal) {
      const Decoupled d = hall_decouple(s.b_ut, q);
      if (!d.valid || !r0.valid) continue;
      x.push_back(axis == 0 ? d.rx - r0.rx : axis == 1 ? d.ry - r0.ry : d.sz - r0.sz);
      f.push_back(s.force[size_t(axis)]);
    }
    if (x.size() < cal.size()) {
      sse = 1e300;
      return std::vector<double>{};
    }
    return fit_poly(x, f, sse);
  };
  auto cost_c1 = [&](double c1) {
    DecoupleParams q = p;
    q.c1_ut = c1;
    double a, b;
    fit_axis(q, 0, a);
    fit_axis(q, 1, b);
    return a + b;
  };
  p.c1_ut = golden_min(cost_c1, -0.5 * scale, 2.0 * scale);
  auto cost_c2 = [&](double c2) {
    DecoupleParams q = p;
    q.c2_ut = c2;
    double a;
    fit_axis(q, 2, a);
    return a;
  };
  p.c2_ut = golden_min(cost_c2, -0.5 * scale, 2.0 * scale);
  double sse;
  for (int a = 0; a < 3; ++a) p.poly[size_t(a)] = fit_axis(p, a, sse);
  return p;
}

}  // namespace eskin::golden
