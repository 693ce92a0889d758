#include "host/golden/sdft_bank.h"

#include <cmath>
#include <sstream>

#include "host/golden/carrier_demix.h"
#include "host/golden/sdft_sums.h"

namespace eskin::golden {

uint64_t phase_increment(double f_hz, double fs_hz) {
  double cycles = f_hz / fs_hz;
  cycles -= std::floor(cycles + 0.5);  // [-0.5, 0.5): * 2^64 fits int64
  return uint64_t(int64_t(std::llround(std::ldexp(cycles, 64))));
}

double phase_angle(uint64_t phase) {
  return 2.0 * M_PI * (double(int64_t(phase)) * 0x1p-64);  // exact power-of-two scaling
}

std::vector<double> window_weights(int n, bool hann) {
  std::vector<double> h(size_t(n), 1.0);
  if (hann)
    for (int i = 0; i < n; ++i) h[size_t(i)] = 0.5 - 0.5 * std::cos(2.0 * M_PI * i / n);
  return h;
}

namespace {

double window_mean(const SampleWindow& w) {
  double s = 0.0;
  for (int i = 0; i < w.size(); ++i) s += w.at(i);
  return s / w.size();
}

// Reference: the windowed sum with a precomputed table scale*h(i)*e^{-jw i}.
class DirectBank : public SdftBank {
 public:
  DirectBank(const std::vector<double>& freqs, double fs, int n, bool hann) : win_(n) {
    std::vector<double> h = window_weights(n, hann);
    double sum_h = 0.0;
    for (double v : h) sum_h += v;
    for (double f : freqs) {
      const double w = 2.0 * M_PI * f / fs;
      for (int i = 0; i < n; ++i)
        coef_.push_back(std::polar(2.0 * h[size_t(i)] / sum_h, -w * i));
    }
  }
  void push(double x) override { win_.push(x); }
  std::complex<double> amplitude(int k) const override {
    const int n = win_.size();
    const std::complex<double>* c = &coef_[size_t(k) * size_t(n)];
    const double* x = win_.oldest();
    std::complex<double> acc = 0.0;
    for (int i = 0; i < n; ++i) acc += c[i] * x[i];
    return acc;
  }
  int carriers() const override { return int(coef_.size()) / win_.size(); }
  bool full() const override { return win_.count() >= uint64_t(win_.size()); }
  double dc() const override { return window_mean(win_); }

 private:
  SampleWindow win_;
  std::vector<std::complex<double>> coef_;  // K x N, row k = carrier k
};

// Taps for `lines` frequencies: [f] each, or [f - fs/N, f, f + fs/N] for Hann.
std::vector<double> make_taps(const std::vector<double>& lines, double fs, int n, bool hann) {
  std::vector<double> taps;
  for (double f : lines) {
    if (hann) taps.push_back(f - fs / n);
    taps.push_back(f);
    if (hann) taps.push_back(f + fs / n);
  }
  return taps;
}

// Unnormalised windowed sum sum_i h(i) x[s+i] e^{-jw i} of line l.
std::complex<double> windowed_sum(const SlidingSums& s, int line, bool hann) {
  if (!hann) return s.sum(line);
  return 0.5 * s.sum(3 * line + 1) - 0.25 * (s.sum(3 * line) + s.sum(3 * line + 2));
}

// Recursive, Damped and Exact: rectangular sliding sums combined per window.
class SlidingBank : public SdftBank {
 public:
  SlidingBank(std::unique_ptr<SlidingSums> sums, int carriers, int n, bool hann)
      : sums_(std::move(sums)), k_(carriers), hann_(hann), scale_(hann ? 4.0 / n : 2.0 / n) {}
  void push(double x) override { sums_->push(x); }
  std::complex<double> amplitude(int k) const override {
    return scale_ * windowed_sum(*sums_, k, hann_);
  }
  int carriers() const override { return k_; }
  bool full() const override {
    return sums_->window().count() >= uint64_t(sums_->window().size());
  }
  double dc() const override { return window_mean(sums_->window()); }

 private:
  std::unique_ptr<SlidingSums> sums_;
  int k_;
  bool hann_;
  double scale_;
};

// Exact sums at the carriers and at DC (last line), demixed jointly. The
// solve runs at most once per sample, on the first query.
class LsDemixBank : public SdftBank {
 public:
  LsDemixBank(const std::vector<double>& freqs, double fs, int n, bool hann)
      : demix_(freqs, fs, n, hann), hann_(hann), amp_(freqs.size()), sums_at_(freqs.size() + 1) {
    std::vector<double> lines = freqs;
    lines.push_back(0.0);
    sums_ = std::make_unique<ExactSums>(make_taps(lines, fs, n, hann), fs, n);
  }
  void push(double x) override {
    sums_->push(x);
    stale_ = true;
  }
  std::complex<double> amplitude(int k) const override {
    update();
    return amp_[size_t(k)];
  }
  int carriers() const override { return demix_.carriers(); }
  bool full() const override {
    return sums_->window().count() >= uint64_t(sums_->window().size());
  }
  double dc() const override {
    update();
    return dc_;
  }

 private:
  void update() const {
    if (!stale_) return;
    const int k = carriers();
    for (int l = 0; l <= k; ++l) sums_at_[size_t(l)] = windowed_sum(*sums_, l, hann_);
    demix_.solve(sums_at_.data(), sums_at_[size_t(k)].real(), amp_.data(), &dc_);
    stale_ = false;
  }
  CarrierDemix demix_;
  bool hann_;
  std::unique_ptr<ExactSums> sums_;
  mutable std::vector<std::complex<double>> amp_, sums_at_;
  mutable double dc_ = 0.0;
  mutable bool stale_ = false;
};

std::string num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

}  // namespace

DftVariant resolve_variant(DftVariant variant, const std::vector<double>& freqs_hz, double fs_hz,
                           const DecoderConfig& cfg) {
  if (variant != DftVariant::Auto) return variant;
  bool on_bins = !cfg.hann;
  for (double f : freqs_hz) {
    const double bin = f * cfg.window / fs_hz;
    on_bins = on_bins && std::fabs(bin - std::round(bin)) < 1e-9;
  }
  if (on_bins) return DftVariant::Exact;
  try {
    CarrierDemix probe(freqs_hz, fs_hz, cfg.window, cfg.hann);
    return DftVariant::LsDemix;
  } catch (const ConfigError&) {
    return DftVariant::Exact;  // carriers too close / too many for the window
  }
}

std::unique_ptr<SdftBank> make_sdft_bank(DftVariant variant, const std::vector<double>& freqs_hz,
                                         double fs_hz, const DecoderConfig& cfg) {
  const int n = cfg.window;
  if (!(fs_hz > 0.0)) throw ConfigError("adc.rate_hz", "expected > 0, got " + num(fs_hz));
  if (n < 2) throw ConfigError("decoder.window", "expected >= 2 samples, got " + std::to_string(n));
  if (freqs_hz.empty()) throw ConfigError("carriers", "expected at least one carrier");
  for (size_t k = 0; k < freqs_hz.size(); ++k)
    if (!(freqs_hz[k] > 0.0 && freqs_hz[k] < fs_hz / 2))
      throw ConfigError("carriers[" + std::to_string(k) + "]",
                        "expected 0 < f < fs/2 = " + num(fs_hz / 2) + " Hz, got " +
                            num(freqs_hz[k]));
  const int k = int(freqs_hz.size());
  const std::vector<double> taps = make_taps(freqs_hz, fs_hz, n, cfg.hann);
  switch (resolve_variant(variant, freqs_hz, fs_hz, cfg)) {
    case DftVariant::Auto:
      break;  // resolved above
    case DftVariant::Direct:
      return std::make_unique<DirectBank>(freqs_hz, fs_hz, n, cfg.hann);
    case DftVariant::Recursive:
      return std::make_unique<SlidingBank>(
          std::make_unique<RecursiveSums>(taps, fs_hz, n, 1.0), k, n, cfg.hann);
    case DftVariant::Damped:
      if (!(cfg.damping > 0.0 && cfg.damping < 1.0))
        throw ConfigError("decoder.damping", "expected 0 < r < 1 for the damped sliding DFT, got " +
                                                 num(cfg.damping));
      return std::make_unique<SlidingBank>(
          std::make_unique<RecursiveSums>(taps, fs_hz, n, cfg.damping), k, n, cfg.hann);
    case DftVariant::Exact:
      return std::make_unique<SlidingBank>(std::make_unique<ExactSums>(taps, fs_hz, n), k, n,
                                           cfg.hann);
    case DftVariant::LsDemix:
      return std::make_unique<LsDemixBank>(freqs_hz, fs_hz, n, cfg.hann);
  }
  throw ConfigError("decoder.variant", "unknown DFT variant");
}

}  // namespace eskin::golden
