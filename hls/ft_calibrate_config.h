// Host-side, NOT synthesised: the fixed-point C of hls/ft_calibrate.h from
// a golden 6x9 matrix in N (rows 0..2) and N*mm (rows 3..5) per uT.
#pragma once

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace eskin::hls {

// entry = round(c_n_per_ut * sens_ut_per_lsb * 1000 * 2^c_frac): output in mN
// (mN*mm) per input LSB. Throws std::invalid_argument naming the entry when it
// does not fit int32.
inline int32_t ft_entry(double c_per_ut, double sens_ut_per_lsb, int c_frac, int i, int j) {
  const double v = std::round(c_per_ut * sens_ut_per_lsb * 1000.0 * std::ldexp(1.0, c_frac));
  if (!(std::fabs(v) < 2147483647.0))
    throw std::invalid_argument("C[" + std::to_string(i) + "][" + std::to_string(j) +
                                "]: expected |C * sens * 1000 * 2^C_FRAC| < 2^31, got " + std::to_string(v));
  return int32_t(v);
}

}  // namespace eskin::hls
