// Golden seed-003 multi-range force curve. A metamaterial block's layers lock
// one after the other, so force against the field change is piecewise: one
// sensitivity per range. The curve is piecewise linear in d = |B - B0| (uT,
// the magnitude of the baseline-removed field; the magnet moves along its
// axis, so this is the seed's |B| - |B0| up to the small off-axis part):
// breakpoints (d_k, F_k), linear between them, clamped to the last
// segment's slope beyond the ends.
#pragma once

#include <vector>

#include "eskin/hall_config.h"

namespace eskin::golden {

double force_curve_apply(const ForceCurve& c, double db_ut);

// Fits the breakpoints from a calibration sweep (pairs of field change and
// force, force ascending): each range [lock_{i-1}, lock_i] (N) is split into
// `per_range` equal force steps and d at each step is read off the sweep by
// linear interpolation.
ForceCurve fit_force_curve(const std::vector<double>& db_ut, const std::vector<double>& force_n,
                           const std::vector<double>& lock_forces_n, int per_range);

}  // namespace eskin::golden
