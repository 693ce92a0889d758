#include "host/golden/sdft_sums.h"

#include <cmath>

#include "host/golden/sdft_bank.h"

namespace eskin::golden {
namespace {

std::complex<double> unit(uint64_t phase) { return std::polar(1.0, phase_angle(phase)); }

}  // namespace

ExactSums::ExactSums(const std::vector<double>& taps_hz, double fs_hz, int n)
    : win_(n), acc_(taps_hz.size()) {
  for (double f : taps_hz) inc_.push_back(phase_increment(f, fs_hz));
  for (uint64_t inc : inc_) oldest_.push_back(unit(-uint64_t(n) * inc));  // sample -N
}

void ExactSums::push(double x) {
  const double x_old = win_.at(0);                        // leaves now (0 until full)
  const uint64_t m_new = win_.count();                    // stream index of x
  const uint64_t s = m_new - uint64_t(win_.size()) + 1;   // new oldest (wraps: harmless)
  win_.push(x);
  for (size_t t = 0; t < acc_.size(); ++t) {
    // oldest_[t] is unit(m_old * inc), evaluated by the same expression on
    // the same integer phase as when x_old entered as a new sample, so the
    // leaving term is bit-identical to the one added N samples ago: the
    // only error is the rounding of this addition.
    std::complex<double> t_new = x * std::conj(unit(m_new * inc_[t]));
    std::complex<double> t_old = x_old * std::conj(oldest_[t]);
    acc_[t] += t_new - t_old;
    oldest_[t] = unit(s * inc_[t]);  // leaves next; also rotates the output
  }
}

std::complex<double> ExactSums::sum(int tap) const {
  // Rotate from the stream-time reference to the window's oldest sample s.
  return oldest_[size_t(tap)] * acc_[size_t(tap)];
}

RecursiveSums::RecursiveSums(const std::vector<double>& taps_hz, double fs_hz, int n, double r)
    : win_(n), y_(taps_hz.size()) {
  const double r_n = std::pow(r, n);
  for (double f : taps_hz) {
    const uint64_t inc = phase_increment(f, fs_hz);
    pole_.push_back(std::polar(r, 2.0 * M_PI * f / fs_hz));   // r e^{jw}, rounded
    leave_.push_back(r_n * unit(uint64_t(n) * inc));           // r^N e^{jwN}
    rotate_.push_back(unit(-uint64_t(n - 1) * inc));           // e^{-jw(N-1)}
  }
}

void RecursiveSums::push(double x) {
  const double x_old = win_.at(0);
  win_.push(x);
  for (size_t t = 0; t < y_.size(); ++t) y_[t] = pole_[t] * y_[t] + x - leave_[t] * x_old;
}

std::complex<double> RecursiveSums::sum(int tap) const {
  return rotate_[size_t(tap)] * y_[size_t(tap)];
}

}  // namespace eskin::golden
