#include "eskin/skin_config.h"

#include <cstdio>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace eskin {
namespace {

std::string num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

std::string idx(const std::string& base, size_t i) {
  return base + "[" + std::to_string(i) + "]";
}

}  // namespace

double Conductance::g(double p) const {
  if (!(p > 0.0)) return 0.0;
  switch (kind) {
    case Kind::Linear:
      return std::min(1.0, p / p_max_kpa);
    case Kind::Saturating:
      return p / (p + p_half_kpa);
    case Kind::Table: {
      if (p >= table_p_kpa.back()) return table_g.back();
      size_t i = size_t(std::upper_bound(table_p_kpa.begin(), table_p_kpa.end(), p) -
                        table_p_kpa.begin());
      double t = (p - table_p_kpa[i - 1]) / (table_p_kpa[i] - table_p_kpa[i - 1]);
      return table_g[i - 1] + t * (table_g[i] - table_g[i - 1]);
    }
  }
  return 0.0;
}

double Conductance::inverse(double gv) const {
  if (!(gv > 0.0)) return 0.0;
  switch (kind) {
    case Kind::Linear:
      return std::min(gv, 1.0) * p_max_kpa;
    case Kind::Saturating: {
      // p = g * p_half / (1 - g); cap just below the asymptote.
      double gc = std::min(gv, 1.0 - 1e-9);
      return gc * p_half_kpa / (1.0 - gc);
    }
    case Kind::Table: {
      if (gv >= table_g.back()) return table_p_kpa.back();
      // First segment whose upper g reaches gv (g is non-decreasing).
      size_t i = 1;
      while (i < table_g.size() && table_g[i] < gv) ++i;
      double dg = table_g[i] - table_g[i - 1];
      double t = dg > 0.0 ? (gv - table_g[i - 1]) / dg : 0.0;
      return table_p_kpa[i - 1] + t * (table_p_kpa[i] - table_p_kpa[i - 1]);
    }
  }
  return 0.0;
}

std::vector<double> SkinConfig::carrier_freqs_hz() const {
  std::vector<double> f(row_freq_hz);
  f.insert(f.end(), col_freq_hz.begin(), col_freq_hz.end());
  return f;
}

std::vector<std::string> SkinConfig::carrier_labels() const {
  std::vector<std::string> l;
  const std::vector<double> f = carrier_freqs_hz();
  for (size_t k = 0; k < f.size(); ++k) {
    const bool row = int(k) < rows;
    char hz[32];
    std::snprintf(hz, sizeof hz, "%g", f[k]);
    l.push_back(std::string(row ? "row " : "col ") + std::to_string(row ? int(k) : int(k) - rows) +
                " \u00b7 " + hz + " Hz");
  }
  return l;
}

std::vector<double> SkinConfig::actual_freqs_hz() const {
  std::vector<double> f = carrier_freqs_hz();
  for (size_t i = 0; i < f.size() && i < freq_error.size(); ++i)
    f[i] *= 1.0 + freq_error[i];
  return f;
}

std::vector<double> plan_carriers(int n, double fs_hz, int window) {
  const int usable = window / 2 - 1;  // bins 1 .. N/2-1: no DC, no Nyquist
  if (n < 1 || n > usable)
    throw ConfigError("skin.carriers",
                      "automatic plan needs 1.." + std::to_string(usable) +
                          " carriers for a " + std::to_string(window) +
                          "-sample window, got " + std::to_string(n) +
                          " (use a longer decoder.window)");
  std::vector<double> f;
  for (int i = 0; i < n; ++i) {
    int k = n == 1 ? (usable + 1) / 2 : 1 + (i * (usable - 1)) / (n - 1);
    f.push_back(k * fs_hz / window);
  }
  return f;
}

void validate(const SkinConfig& s, const std::string& p) {
  if (s.rows < 1 || s.rows > 256)
    throw ConfigError(p + ".rows", "expected 1..256, got " + std::to_string(s.rows));
  if (s.cols < 1 || s.cols > 256)
    throw ConfigError(p + ".cols", "expected 1..256, got " + std::to_string(s.cols));
  const AdcConfig& a = s.adc;
  if (!(a.rate_hz > 0.0))
    throw ConfigError(p + ".adc.rate_hz", "expected > 0, got " + num(a.rate_hz));
  if (a.bits < 2 || a.bits > 24)
    throw ConfigError(p + ".adc.bits", "expected 2..24, got " + std::to_string(a.bits));
  if (!(a.full_scale_v > 0.0))
    throw ConfigError(p + ".adc.full_scale_v", "expected > 0, got " + num(a.full_scale_v));
  if (!(a.offset_v >= 0.0 && a.offset_v <= a.full_scale_v))
    throw ConfigError(p + ".adc.offset_v",
                      "expected within [0, full_scale_v=" + num(a.full_scale_v) +
                          "], got " + num(a.offset_v));
  if (!(a.noise_rms_v >= 0.0))
    throw ConfigError(p + ".adc.noise_rms_v", "expected >= 0, got " + num(a.noise_rms_v));
  if (!(s.osc_amplitude_v > 0.0))
    throw ConfigError(p + ".osc_amplitude_v", "expected > 0, got " + num(s.osc_amplitude_v));
  if (!(s.amp_gain > 0.0))
    throw ConfigError(p + ".amp_gain", "expected > 0, got " + num(s.amp_gain));

  const std::pair<const std::vector<double>*, std::string> lines[] = {
      {&s.row_freq_hz, "rows"}, {&s.col_freq_hz, "cols"}};
  const int counts[] = {s.rows, s.cols};
  for (int l = 0; l < 2; ++l) {
    const auto& v = *lines[l].first;
    const std::string field = p + ".carriers." + lines[l].second;
    if (int(v.size()) != counts[l])
      throw ConfigError(field, "expected " + std::to_string(counts[l]) +
                                   " frequencies, got " + std::to_string(v.size()));
    for (size_t i = 0; i < v.size(); ++i)
      if (!(v[i] > 0.0 && v[i] < a.rate_hz / 2))
        throw ConfigError(idx(field, i), "expected 0 < f < Nyquist (" +
                                             num(a.rate_hz / 2) + " Hz), got " + num(v[i]));
  }
  if (!s.freq_error.empty()) {
    if (int(s.freq_error.size()) != s.carriers())
      throw ConfigError(p + ".freq_error", "expected " + std::to_string(s.carriers()) +
                                               " values (rows then cols), got " +
                                               std::to_string(s.freq_error.size()));
    for (size_t i = 0; i < s.freq_error.size(); ++i)
      if (!(std::fabs(s.freq_error[i]) < 0.1))
        throw ConfigError(idx(p + ".freq_error", i),
                          "expected |error| < 0.1, got " + num(s.freq_error[i]));
  }
  std::vector<double> f = s.actual_freqs_hz();
  for (size_t i = 0; i < f.size(); ++i) {
    if (!(f[i] < a.rate_hz / 2))
      throw ConfigError(p + ".freq_error", "carrier " + std::to_string(i) + " drifts to " +
                                               num(f[i]) + " Hz, at or above Nyquist");
    for (size_t j = 0; j < i; ++j)
      if (f[i] == f[j])
        throw ConfigError(p + ".carriers", "carriers " + std::to_string(j) + " and " +
                                               std::to_string(i) + " share " + num(f[i]) +
                                               " Hz; every row and column needs its own");
  }

  const Conductance& c = s.conductance;
  const std::string cf = p + ".conductance";
  if (c.kind == Conductance::Kind::Linear && !(c.p_max_kpa > 0.0))
    throw ConfigError(cf + ".p_max_kpa", "expected > 0, got " + num(c.p_max_kpa));
  if (c.kind == Conductance::Kind::Saturating && !(c.p_half_kpa > 0.0))
    throw ConfigError(cf + ".p_half_kpa", "expected > 0, got " + num(c.p_half_kpa));
  if (c.kind == Conductance::Kind::Table) {
    if (c.table_p_kpa.size() < 2 || c.table_p_kpa.size() != c.table_g.size())
      throw ConfigError(cf + ".table", "expected >= 2 [p_kpa, g] points");
    if (c.table_p_kpa[0] != 0.0 || c.table_g[0] != 0.0)
      throw ConfigError(cf + ".table[0]", "expected the curve to start at [0, 0]");
    for (size_t i = 1; i < c.table_p_kpa.size(); ++i) {
      if (!(c.table_p_kpa[i] > c.table_p_kpa[i - 1]))
        throw ConfigError(idx(cf + ".table", i), "expected pressures strictly ascending");
      if (!(c.table_g[i] >= c.table_g[i - 1] && c.table_g[i] <= 1.0))
        throw ConfigError(idx(cf + ".table", i), "expected g non-decreasing and <= 1");
    }
  }
}

void validate(const DecoderConfig& d, const SkinConfig& s, const std::string& p) {
  if (d.window < 4 || d.window > 4096)
    throw ConfigError(p + ".window", "expected 4..4096 samples, got " + std::to_string(d.window));
  if (!(d.damping > 0.0 && d.damping <= 1.0))
    throw ConfigError(p + ".damping", "expected 0 < r <= 1, got " + num(d.damping));
  if (d.hop < 1)
    throw ConfigError(p + ".hop", "expected >= 1, got " + std::to_string(d.hop));
  if (!(d.ghost_threshold >= 0.0))
    throw ConfigError(p + ".ghost_threshold", "expected >= 0, got " + num(d.ghost_threshold));
  if (!(d.ghost_onset > 0.0))
    throw ConfigError(p + ".ghost_onset", "expected > 0, got " + num(d.ghost_onset));
  // One bin (fs/N) is the resolution of an N-sample window: a carrier needs a
  // full period in the window, must stay a bin away from Nyquist, and two
  // carriers closer than a bin cannot be told apart.
  const double fs = s.adc.rate_hz, bin = fs / d.window;
  std::vector<double> f = s.carrier_freqs_hz();
  for (size_t i = 0; i < f.size(); ++i) {
    if (f[i] < bin)
      throw ConfigError("skin.carriers", "carrier " + num(f[i]) +
                                             " Hz has less than one period in a " +
                                             std::to_string(d.window) +
                                             "-sample window (needs >= " + num(bin) + " Hz)");
    if (f[i] > fs / 2 - bin)
      throw ConfigError("skin.carriers", "carrier " + num(f[i]) +
                                             " Hz is within one bin of Nyquist (max " +
                                             num(fs / 2 - bin) + " Hz)");
  }
  std::sort(f.begin(), f.end());
  for (size_t i = 1; i < f.size(); ++i)
    if (f[i] - f[i - 1] < bin)
      throw ConfigError(p + ".window",
                        "window too short for the carrier spacing: " + num(f[i - 1]) +
                            " and " + num(f[i]) + " Hz are closer than fs/N = " + num(bin) +
                            " Hz; need N >= " +
                            std::to_string(int(std::ceil(fs / (f[i] - f[i - 1])))));
}

const char* to_string(DftVariant v) {
  switch (v) {
    case DftVariant::Auto: return "auto";
    case DftVariant::Direct: return "direct";
    case DftVariant::Recursive: return "recursive";
    case DftVariant::Damped: return "damped";
    case DftVariant::Exact: return "exact";
    case DftVariant::LsDemix: return "ls";
  }
  return "?";
}

DftVariant dft_variant_from_string(const std::string& s) {
  for (DftVariant v : {DftVariant::Auto, DftVariant::Direct, DftVariant::Recursive,
                       DftVariant::Damped, DftVariant::Exact, DftVariant::LsDemix})
    if (s == to_string(v)) return v;
  throw ConfigError("decoder.variant",
                    "expected one of auto, direct, recursive, damped, exact, ls; got '" + s + "'");
}

}  // namespace eskin
