// Sliding rectangular-window sums behind the golden SdftBank variants (see
// sdft_bank.h for the definitions and the phase convention):
//
//   R_t(n) = sum_{i=0}^{N-1} x[n-N+1+i] * exp(-j*2*pi*f_t/fs * i)
//
// for a list of "tap" frequencies f_t (the carriers, their Hann neighbours
// f_t -/+ fs/N, and 0 Hz for DC). IEEE double throughout.
#pragma once

#include <complex>
#include <cstdint>
#include <vector>

namespace eskin::golden {

// The last N samples, oldest first via at(i); zeros before they are seen.
class SampleWindow {
 public:
  explicit SampleWindow(int n) : n_(n), buf_(2 * size_t(n), 0.0) {}
  void push(double x) {
    pos_ = pos_ + 1 == n_ ? 0 : pos_ + 1;
    buf_[pos_] = buf_[pos_ + n_] = x;  // doubled: the window is contiguous
    ++count_;
  }
  // Sample i of the window (0 = oldest, N-1 = newest).
  double at(int i) const { return buf_[pos_ + 1 + i]; }
  const double* oldest() const { return &buf_[pos_ + 1]; }
  int size() const { return n_; }
  uint64_t count() const { return count_; }  // samples pushed so far

 private:
  int n_;
  int pos_ = 0;  // slot of the newest sample
  std::vector<double> buf_;
  uint64_t count_ = 0;
};

class SlidingSums {
 public:
  virtual ~SlidingSums() = default;
  virtual void push(double x) = 0;
  virtual std::complex<double> sum(int tap) const = 0;
  virtual const SampleWindow& window() const = 0;
};

// Modulated exact form: 64-bit phase accumulators, terms re-derived when they
// leave; see sdft_bank.h (Exact).
class ExactSums : public SlidingSums {
 public:
  ExactSums(const std::vector<double>& taps_hz, double fs_hz, int n);
  void push(double x) override;
  std::complex<double> sum(int tap) const override;
  const SampleWindow& window() const override { return win_; }

 private:
  SampleWindow win_;
  std::vector<uint64_t> inc_;
  std::vector<std::complex<double>> acc_;     // sum of x[m]*exp(-j*theta_t(m))
  std::vector<std::complex<double>> oldest_;  // exp(j*theta_t(s)), s = oldest sample
};

// Recursive form y <- (r*z)*y + x_new - (r*z)^N * x_old (z = e^{jw}, both
// factors rounded to double); r = 1 is the naive sliding DFT. The output is
// sum_i r^(N-1-i) x[s+i] e^{-jwi}: exp(-jw(N-1)) * y.
class RecursiveSums : public SlidingSums {
 public:
  RecursiveSums(const std::vector<double>& taps_hz, double fs_hz, int n, double r);
  void push(double x) override;
  std::complex<double> sum(int tap) const override;
  const SampleWindow& window() const override { return win_; }

 private:
  SampleWindow win_;
  std::vector<std::complex<double>> pole_, leave_, rotate_, y_;
};

}  // namespace eskin::golden
