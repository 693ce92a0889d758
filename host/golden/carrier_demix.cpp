#include "host/golden/carrier_demix.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "eskin/skin_config.h"
#include "host/golden/sdft_bank.h"

namespace eskin::golden {
namespace {

// "carriers 3300 and 5000 Hz" for the closest pair (the likely culprit).
std::string closest_pair(std::vector<double> f) {
  std::sort(f.begin(), f.end());
  std::ostringstream s;
  if (f.size() < 2) return "a single carrier";
  size_t best = 1;
  for (size_t i = 2; i < f.size(); ++i)
    if (f[i] - f[i - 1] < f[best] - f[best - 1]) best = i;
  s << "carriers " << f[best - 1] << " and " << f[best] << " Hz";
  return s.str();
}

}  // namespace

CarrierDemix::CarrierDemix(const std::vector<double>& freqs_hz, double fs_hz, int window,
                           bool hann, double max_condition)
    : freqs_(freqs_hz), n_(window), weights_(window_weights(window, hann)) {
  const int k = carriers(), unknowns = 2 * k + 1;
  const int used = int(std::count_if(weights_.begin(), weights_.end(),
                                     [](double h) { return h > 0.0; }));
  if (unknowns > used)
    throw ConfigError("decoder.window",
                      "least-squares demixing of " + std::to_string(k) +
                          " carriers + DC needs >= " + std::to_string(unknowns) +
                          " weighted samples, the window has " + std::to_string(used) +
                          " (use decoder.window >= " +
                          std::to_string(unknowns + (hann ? 1 : 0)) + ")");

  basis_.resize(n_, unknowns);
  for (int i = 0; i < n_; ++i) {
    for (int c = 0; c < k; ++c) {
      double w = 2.0 * M_PI * freqs_[c] / fs_hz;
      basis_(i, 2 * c) = std::cos(w * i);
      basis_(i, 2 * c + 1) = std::sin(w * i);
    }
    basis_(i, 2 * k) = 1.0;
  }
  Eigen::VectorXd sqrt_h(n_);
  for (int i = 0; i < n_; ++i) sqrt_h[i] = std::sqrt(weights_[i]);
  Eigen::MatrixXd weighted = sqrt_h.asDiagonal() * basis_;

  Eigen::JacobiSVD<Eigen::MatrixXd> svd(weighted, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::VectorXd& sv = svd.singularValues();
  kappa_ = sv[0] / sv[sv.size() - 1];
  if (!(kappa_ <= max_condition)) {
    std::ostringstream s;
    s << closest_pair(freqs_) << " are too close for a " << n_
      << "-sample window: least-squares condition number " << kappa_ << " > " << max_condition
      << " (lengthen decoder.window or move the carriers apart)";
    throw ConfigError("decoder.window", s.str());
  }
  Eigen::VectorXd inv_sv = sv.cwiseInverse();
  const Eigen::MatrixXd& v = svd.matrixV();
  g_inv_ = v * inv_sv.cwiseAbs2().asDiagonal() * v.transpose();
  pinv_ = v * inv_sv.asDiagonal() * svd.matrixU().transpose();
}

void CarrierDemix::solve(const std::complex<double>* sums, double dc_sum,
                         std::complex<double>* amplitudes, double* dc) const {
  const int k = carriers();
  Eigen::VectorXd rhs(2 * k + 1);
  for (int c = 0; c < k; ++c) {
    rhs[2 * c] = sums[c].real();       // sum h x cos(w i)
    rhs[2 * c + 1] = -sums[c].imag();  // sum h x sin(w i)
  }
  rhs[2 * k] = dc_sum;
  Eigen::VectorXd theta = g_inv_ * rhs;
  for (int c = 0; c < k; ++c) amplitudes[c] = {theta[2 * c], -theta[2 * c + 1]};
  if (dc) *dc = theta[2 * k];
}

void CarrierDemix::fit(const std::vector<double>& samples,
                       std::vector<std::complex<double>>& amplitudes, double& dc) const {
  if (int(samples.size()) != n_)
    throw std::invalid_argument("CarrierDemix::fit: expected " + std::to_string(n_) +
                                " samples, got " + std::to_string(samples.size()));
  Eigen::VectorXd xw(n_);
  for (int i = 0; i < n_; ++i) xw[i] = std::sqrt(weights_[i]) * samples[size_t(i)];
  Eigen::VectorXd theta = pinv_ * xw;
  const int k = carriers();
  amplitudes.resize(size_t(k));
  for (int c = 0; c < k; ++c) amplitudes[size_t(c)] = {theta[2 * c], -theta[2 * c + 1]};
  dc = theta[2 * k];
}

}  // namespace eskin::golden
