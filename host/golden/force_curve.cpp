#include "host/golden/force_curve.h"

#include <algorithm>
#include <stdexcept>

namespace eskin::golden {

double force_curve_apply(const ForceCurve& c, double d) {
  const auto& x = c.db_ut;
  const auto& y = c.force_n;
  size_t i = size_t(std::upper_bound(x.begin(), x.end(), d) - x.begin());
  i = std::clamp<size_t>(i, 1, x.size() - 1);
  return y[i - 1] + (d - x[i - 1]) * (y[i] - y[i - 1]) / (x[i] - x[i - 1]);
}

ForceCurve fit_force_curve(const std::vector<double>& db, const std::vector<double>& f,
                           const std::vector<double>& lock, int per_range) {
  if (db.size() != f.size() || db.size() < 2)
    throw std::invalid_argument("fit_force_curve: expected a sweep of at least 2 (field, force) pairs");
  auto d_at = [&](double force) {
    size_t i = size_t(std::upper_bound(f.begin(), f.end(), force) - f.begin());
    i = std::clamp<size_t>(i, 1, f.size() - 1);
    return db[i - 1] + (force - f[i - 1]) * (db[i] - db[i - 1]) / (f[i] - f[i - 1]);
  };
  ForceCurve c;
  double lo = 0;
  c.db_ut.push_back(d_at(0));
  c.force_n.push_back(0);
  for (double hi : lock) {
    for (int k = 1; k <= per_range; ++k) {
      const double force = lo + (hi - lo) * k / per_range;
      c.force_n.push_back(force);
      c.db_ut.push_back(d_at(force));
    }
    lo = hi;
  }
  return c;
}

}  // namespace eskin::golden
