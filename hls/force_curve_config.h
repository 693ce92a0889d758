// Host-side, NOT synthesised: hls/force_curve.h's gains and tables from the
// sensors' setting and a golden curve (uT -> N).
#pragma once

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "hls/force_curve.h"

namespace eskin::hls {

// UQ4.12 uT per LSB (the datasheet sensitivities 0.150 .. 9.68 uT/LSB fit).
inline uint16_t force_curve_gain(double ut_per_lsb) {
  const double g = std::round(ut_per_lsb * 4096.0);
  if (!(g >= 1 && g < 65536))
    throw std::invalid_argument("gain: expected 2^-12 .. 16 uT/LSB, got " + std::to_string(ut_per_lsb));
  return uint16_t(g);
}

// Breakpoints quantised first (db to 1/64 uT, force to mN), slopes from the
// quantised ends (Q15.16), so the table passes within rounding of each
// breakpoint. n must equal NB.
template <int NB>
ForceCurveTable<NB> force_curve_table(const double* db_ut, const double* force_n, int n) {
  if (n != NB) throw std::invalid_argument("force curve: expected " + std::to_string(NB) + " breakpoints, got " + std::to_string(n));
  ForceCurveTable<NB> t;
  for (int k = 0; k < NB; ++k) {
    t.db[k] = int32_t(std::lround(db_ut[k] * 64.0));
    t.f[k] = int32_t(std::lround(force_n[k] * 1000.0));
  }
  for (int k = 0; k + 1 < NB; ++k) {
    if (t.db[k + 1] <= t.db[k])
      throw std::invalid_argument("force curve: breakpoint " + std::to_string(k + 1) + " not above the previous one after quantisation");
    t.slope[k] = int32_t(std::lround(std::ldexp(double(t.f[k + 1] - t.f[k]) / double(t.db[k + 1] - t.db[k]), 16)));
  }
  t.slope[NB - 1] = t.slope[NB - 2];
  return t;
}

}  // namespace eskin::hls
