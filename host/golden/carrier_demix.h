// Joint least-squares demixing of K carriers + DC over an N-sample window
// (golden, IEEE double, Eigen). Removes the cross-talk that off-bin carriers
// cause in each other's DFT (up to ~20% for the thesis carriers at N = 32).
//
// Model of the window (i = 0..N-1 oldest first, w_k = 2*pi*f_k/fs):
//   x[s+i] ~ d + sum_k a_k*cos(w_k*i) + b_k*sin(w_k*i)
// fitted by weighted least squares (weights h(i): ones or periodic Hann).
// Unknowns theta = (a_1, b_1, ..., a_K, b_K, d). The amplitude of carrier k is
// a_k - j*b_k: a tone A*cos(w_k*(s+i) + phi) gives A*exp(j*(w_k*s + phi)),
// the same oldest-sample phase convention and units as SdftBank (sdft_bank.h).
//
// Streaming form: the normal equations G*theta = B^T*H*x only need the
// windowed DFT sums the sliding banks already keep,
//   B^T H x = (Re P_1, -Im P_1, ..., Re P_K, -Im P_K, D),
//   P_k = sum_i h(i) x[s+i] exp(-j*w_k*i),  D = sum_i h(i) x[s+i],
// so each sample costs one (2K+1)^2 matrix-vector product with the
// precomputed G^{-1} = (B^T H B)^{-1}.
//
// Conditioning: kappa = condition number (2-norm) of the weighted basis
// sqrt(H)*B; G has kappa^2, so rounding in the sums is amplified by up to
// kappa^2 in theta, and noise in the window by up to ~kappa/sqrt(2) more
// than for orthogonal carriers. Orthogonal (bin-centred, rectangular) gives
// kappa = sqrt(2); the thesis carriers at N = 32: 1.85 (Hann 1.98); two
// carriers 0.18 bin apart: ~7, 0.09 bin: ~13.5 (kappa ~ 1.2/spacing in bins).
// Construction throws ConfigError("decoder.window") when 2K+1 exceeds the
// samples with nonzero weight or kappa > max_condition (default 10: carriers
// too close for the window), naming the closest carrier pair.
#pragma once

#include <Eigen/Dense>
#include <complex>
#include <vector>

namespace eskin::golden {

class CarrierDemix {
 public:
  static constexpr double kDefaultMaxCondition = 10.0;
  CarrierDemix(const std::vector<double>& freqs_hz, double fs_hz, int window, bool hann,
               double max_condition = kDefaultMaxCondition);

  int carriers() const { return int(freqs_.size()); }
  int window() const { return n_; }
  double condition_number() const { return kappa_; }

  // sums[k] = P_k, dc_sum = D (unnormalised windowed sums, as above) ->
  // amplitudes[k] (K of them) and the fitted DC level d.
  void solve(const std::complex<double>* sums, double dc_sum,
             std::complex<double>* amplitudes, double* dc) const;

  // Reference path: the same fit directly on the N window samples (oldest
  // first) through the precomputed weighted pseudo-inverse.
  void fit(const std::vector<double>& samples, std::vector<std::complex<double>>& amplitudes,
           double& dc) const;

  const Eigen::MatrixXd& basis() const { return basis_; }            // N x (2K+1)
  const Eigen::MatrixXd& normal_inverse() const { return g_inv_; }   // G^{-1}

 private:
  std::vector<double> freqs_;
  int n_;
  std::vector<double> weights_;
  Eigen::MatrixXd basis_, g_inv_, pinv_;  // pinv_: theta = pinv_ * (sqrt(h) .* x)
  double kappa_ = 0.0;
};

}  // namespace eskin::golden
