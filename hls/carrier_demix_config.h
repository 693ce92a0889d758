// Host-side, not synthesised: builds the tables of hls/carrier_demix.h (and
// of the RTL config port) from carrier frequencies in Hz, in double.
// Independent of the golden model: the Gram matrix is built here and
// inverted by Gauss-Jordan elimination with partial pivoting. Never throws:
// returns a status naming the field and what was expected.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "hls/carrier_demix.h"

namespace eskin::hls {

struct CarrierDemixStatus {
  bool ok = false;
  std::string message;     // "" when ok, else "FIELD: expected ..., got ..."
  double condition = 0;    // 2-norm condition number of the Gram matrix G
  double max_coef = 0;     // max |M_ij|, M = (N/2) G^{-1} / gains
  double row_norm = 0;     // ||M||_inf: output word growth over the inputs
};

// M = (N/2) G^{-1} / (sum_gain * rotation gain), quantised to Q(CW-CF).CF.
// sum_gain: gain of the incoming sums (sdft_bank: 1 - 2^-(CW_sdft-1)).
// Frames: the first frame's oldest sample is sample `first_oldest` after the
// bank's clear (frames on every sample from sample 0: 1 - N; frames every
// STEP samples from the first full window: 0), then one frame every
// `frame_step` samples.
// The tables of a demix with any sizes and formats (host side, vectors).
struct CarrierDemixTables {
  int carriers = 0;
  std::vector<uint32_t> inc, phase0;  // K each
  std::vector<int32_t> qsin;          // 2^(TW-2) + 1
  std::vector<int32_t> coef;          // (2K+1)^2, row-major
};

inline CarrierDemixStatus carrier_demix_tables(const std::vector<double>& freqs_hz, double fs_hz,
                                               double sum_gain, int N, int KMAX, int TW, int SW,
                                               int CW, int CF, int frame_step, int first_oldest,
                                               CarrierDemixTables& out) {
  CarrierDemixStatus st;
  const auto fail = [&](const std::string& m) { st.message = m; return st; };
  const int k = int(freqs_hz.size());
  if (k < 1 || k > KMAX)
    return fail("carriers: expected 1.." + std::to_string(KMAX) + " carriers, got " +
                std::to_string(k));
  if (!(fs_hz > 0) || !std::isfinite(fs_hz))
    return fail("adc.rate_hz: expected a finite rate > 0, got " + std::to_string(fs_hz));
  if (2 * k + 1 > N)
    return fail("decoder.window: expected >= 2K+1 = " + std::to_string(2 * k + 1) +
                " samples for K = " + std::to_string(k) + " carriers + DC, got " +
                std::to_string(N));
  for (int c = 0; c < k; ++c)
    if (!(freqs_hz[c] > 0 && freqs_hz[c] < fs_hz / 2))
      return fail("carriers[" + std::to_string(c) + "]: expected 0 < f < fs/2 = " +
                  std::to_string(fs_hz / 2) + " Hz, got " + std::to_string(freqs_hz[c]));
  if (frame_step < 1)
    return fail("frame_step: expected >= 1 sample per frame, got " + std::to_string(frame_step));
  if (!(sum_gain > 0.5 && sum_gain <= 2))
    return fail("sum_gain: expected 0.5 < gain <= 2, got " + std::to_string(sum_gain));

  CarrierDemixTables cfg;
  cfg.carriers = k;
  cfg.inc.assign(size_t(k), 0);
  cfg.phase0.assign(size_t(k), 0);
  const double two32 = std::ldexp(1.0, 32);
  std::vector<double> w(static_cast<size_t>(k), 0.0);
  for (int c = 0; c < k; ++c) {
    const uint64_t inc = uint64_t(std::llround(freqs_hz[c] / fs_hz * two32)) & 0xffffffffu;
    cfg.inc[c] = uint32_t(inc) * uint32_t(frame_step);        // mod 2^32
    cfg.phase0[c] = uint32_t(inc) * uint32_t(first_oldest);   // mod 2^32
    w[size_t(c)] = 2 * M_PI * double(inc) / two32;  // the frequency the phases realise
  }
  const int qn = (1 << (TW - 2)) + 1;
  cfg.qsin.assign(size_t(qn), 0);
  const double amp = std::ldexp(1.0, SW - 1) - 1;
  for (int i = 0; i < qn; ++i)
    cfg.qsin[i] = int32_t(std::lround(amp * std::sin(M_PI / 2 * i / (qn - 1))));

  // Gram matrix of the basis cos(w i), sin(w i) per carrier, then 1.
  const int dim = 2 * k + 1;
  cfg.coef.assign(size_t(dim * dim), 0);
  std::vector<double> g(size_t(dim * dim), 0.0), basis(static_cast<size_t>(dim));
  for (int i = 0; i < N; ++i) {
    for (int c = 0; c < k; ++c) {
      basis[size_t(2 * c)] = std::cos(w[size_t(c)] * i);
      basis[size_t(2 * c + 1)] = std::sin(w[size_t(c)] * i);
    }
    basis[size_t(2 * k)] = 1.0;
    for (int r = 0; r < dim; ++r)
      for (int s = 0; s < dim; ++s) g[size_t(r * dim + s)] += basis[size_t(r)] * basis[size_t(s)];
  }
  // Gauss-Jordan on [G | I].
  std::vector<double> a(g), inv(size_t(dim * dim), 0.0);
  for (int i = 0; i < dim; ++i) inv[size_t(i * dim + i)] = 1.0;
  for (int col = 0; col < dim; ++col) {
    int piv = col;
    for (int r = col + 1; r < dim; ++r)
      if (std::fabs(a[size_t(r * dim + col)]) > std::fabs(a[size_t(piv * dim + col)])) piv = r;
    if (std::fabs(a[size_t(piv * dim + col)]) < 1e-9)
      return fail("carriers: the carriers and DC are linearly dependent over the window "
                  "(expected distinct frequencies at least ~fs/N apart)");
    for (int s = 0; s < dim; ++s) {
      std::swap(a[size_t(col * dim + s)], a[size_t(piv * dim + s)]);
      std::swap(inv[size_t(col * dim + s)], inv[size_t(piv * dim + s)]);
    }
    const double d = a[size_t(col * dim + col)];
    for (int s = 0; s < dim; ++s) a[size_t(col * dim + s)] /= d, inv[size_t(col * dim + s)] /= d;
    for (int r = 0; r < dim; ++r) {
      if (r == col) continue;
      const double f = a[size_t(r * dim + col)];
      for (int s = 0; s < dim; ++s) {
        a[size_t(r * dim + s)] -= f * a[size_t(col * dim + s)];
        inv[size_t(r * dim + s)] -= f * inv[size_t(col * dim + s)];
      }
    }
  }
  // 2-norm condition of the symmetric positive definite G: lambda_max(G) *
  // lambda_max(G^{-1}), both by power iteration.
  const auto lambda_max = [dim](const std::vector<double>& m) {
    std::vector<double> v(size_t(dim), 1.0), u(static_cast<size_t>(dim));
    double lam = 0;
    for (int it = 0; it < 500; ++it) {
      double norm = 0;
      for (int r = 0; r < dim; ++r) {
        double s = 0;
        for (int c = 0; c < dim; ++c) s += m[size_t(r * dim + c)] * v[size_t(c)];
        u[size_t(r)] = s;
        norm += s * s;
      }
      norm = std::sqrt(norm);
      for (int r = 0; r < dim; ++r) v[size_t(r)] = u[size_t(r)] / norm;
      lam = norm;
    }
    return lam;
  };
  st.condition = lambda_max(g) * lambda_max(inv);

  const double rot_gain = amp / std::ldexp(1.0, SW - 1);
  const double scale = N / 2.0 / (sum_gain * rot_gain);
  const double lim = std::ldexp(1.0, CW - 1) - 1;
  for (int r = 0; r < dim; ++r) {
    double row = 0;
    for (int s = 0; s < dim; ++s) {
      const double m = inv[size_t(r * dim + s)] * scale;
      st.max_coef = std::max(st.max_coef, std::fabs(m));
      row += std::fabs(m);
      const double q = std::round(std::ldexp(m, CF));
      if (std::fabs(q) > lim)
        return fail("coef[" + std::to_string(r) + "][" + std::to_string(s) +
                    "]: expected |M| < 2^(CW-1-CF) = " + std::to_string(std::ldexp(1.0, CW - 1 - CF)) +
                    ", got " + std::to_string(m) + " (condition number " +
                    std::to_string(st.condition) + ": carriers too close for the window)");
      cfg.coef[r * dim + s] = int32_t(q);
    }
    st.row_norm = std::max(st.row_norm, row);
  }
  out = cfg;
  st.ok = true;
  return st;
}


template <class Demix>
CarrierDemixStatus make_carrier_demix_config(const std::vector<double>& freqs_hz, double fs_hz,
                                             double sum_gain, typename Demix::Config& out,
                                             int frame_step = 1,
                                             int first_oldest = 1 - Demix::kN) {
  CarrierDemixTables t;
  const CarrierDemixStatus st =
      carrier_demix_tables(freqs_hz, fs_hz, sum_gain, Demix::kN, Demix::kKMax, Demix::kTW,
                           Demix::kSW, Demix::kCW, Demix::kCF, frame_step, first_oldest, t);
  if (!st.ok) return st;
  typename Demix::Config cfg{};
  cfg.carriers = t.carriers;
  for (int k = 0; k < t.carriers; ++k) cfg.inc[k] = t.inc[size_t(k)], cfg.phase0[k] = t.phase0[size_t(k)];
  for (size_t i = 0; i < t.qsin.size(); ++i) cfg.qsin[i] = t.qsin[i];
  for (size_t i = 0; i < t.coef.size(); ++i) cfg.coef[i] = t.coef[i];
  out = cfg;
  return st;
}

}  // namespace eskin::hls
