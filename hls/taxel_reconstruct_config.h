// Host-side, NOT synthesised: builds the fixed-point constants of
// hls/taxel_reconstruct.h (reciprocal of the full carrier, PWL pressure
// table) from physical values in double. The kernel itself uses no float.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "hls/taxel_reconstruct.h"

namespace eskin::hls {

// recip / recip_shift so that g = r * recip >> recip_shift is UQ1.15 with
// 1.0 = full_carrier_mag (the magnitude, in input units, of one carrier whose
// line passes conductance fraction 1). Picks the largest shift that keeps
// recip in 16 bits (most precision). Throws std::invalid_argument naming
// `full_carrier_mag` when no shift 0..31 gives 1 <= recip < 2^16.
inline void set_full_carrier(double full_carrier_mag, TaxelReconstructConfig& c) {
  if (!(full_carrier_mag > 0.0))
    throw std::invalid_argument("full_carrier_mag: expected > 0, got " +
                                std::to_string(full_carrier_mag));
  for (int s = 31; s >= 0; --s) {
    const double r = std::round(std::ldexp(1.0, 15 + s) / full_carrier_mag);
    if (r < 65536.0 && r >= 1.0) {
      c.recip = uint16_t(r);
      c.recip_shift = uint8_t(s);
      return;
    }
  }
  throw std::invalid_argument("full_carrier_mag: expected 2^-16 .. 2^46 input units, got " +
                              std::to_string(full_carrier_mag));
}

// PWL pressure table from n (2..16) points (g ascending from 0, p
// non-decreasing), p in units of p_lsb (e.g. p_lsb = 1/256 kPa gives UQ8.8
// kPa values). Breakpoints are quantised first (g to UQ1.15, p to p_lsb) and
// slopes computed from the quantised ends, so the table passes within half an
// LSB of each quantised breakpoint. Points that quantise to the same g as
// their predecessor are dropped. Above the last point the value is clamped
// (slope 0). Throws std::invalid_argument naming the offending field.
inline void set_pwl(const double* g, const double* p, int n, double p_lsb,
                    TaxelReconstructConfig& c, int tax_w = 16) {
  if (n < 2 || n > kTaxelPwlN)
    throw std::invalid_argument("pwl points: expected 2..16, got " + std::to_string(n));
  if (g[0] != 0.0) throw std::invalid_argument("pwl g[0]: expected 0");
  const double pmax = std::ldexp(1.0, tax_w) - 1.0;
  uint16_t gq[kTaxelPwlN];
  uint32_t pq[kTaxelPwlN];
  int m = 0;
  for (int i = 0; i < n; ++i) {
    if (i > 0 && (g[i] < g[i - 1] || p[i] < p[i - 1]))
      throw std::invalid_argument("pwl point " + std::to_string(i) +
                                  ": expected g ascending and p non-decreasing");
    const double gi = std::min(65535.0, std::round(g[i] * 32768.0));
    const double pi = std::min(pmax, std::round(p[i] / p_lsb));
    if (m > 0 && gi <= gq[m - 1]) continue;
    gq[m] = uint16_t(gi);
    pq[m] = uint32_t(pi);
    ++m;
  }
  double max_slope = 0.0;
  for (int s = 0; s + 1 < m; ++s)
    max_slope = std::max(max_slope, double(pq[s + 1] - pq[s]) / double(gq[s + 1] - gq[s]));
  int ss = 31;  // largest slope_shift that keeps every slope in 16 bits
  while (ss > 0 && std::round(std::ldexp(max_slope, ss)) > 65535.0) --ss;
  if (std::round(max_slope) > 65535.0)
    throw std::invalid_argument("pwl slope: expected <= 65535 value LSB per g LSB");
  c.slope_shift = uint8_t(ss);
  for (int s = 0; s < kTaxelPwlN; ++s) {
    if (s < m) {
      c.g_tab[s] = gq[s];
      c.p_tab[s] = pq[s];
      c.slope[s] = s + 1 < m ? uint16_t(std::round(std::ldexp(
                                   double(pq[s + 1] - pq[s]) / double(gq[s + 1] - gq[s]), ss)))
                             : 0;
    } else {  // padding: never selected below 0xFFFF, gives the last value
      c.g_tab[s] = 0xFFFF;
      c.p_tab[s] = pq[m - 1];
      c.slope[s] = 0;
    }
  }
}

}  // namespace eskin::hls
