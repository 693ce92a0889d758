#include "host/golden/decode_score.h"

#include <algorithm>
#include <cmath>

namespace eskin::golden {

double DecodeScore::worst_rms_error_kpa() const {
  double w = 0;
  for (const auto& t : taxel) w = std::max(w, t.rms_error_kpa);
  return w;
}

double DecodeScore::worst_max_error_kpa() const {
  double w = 0;
  for (const auto& t : taxel) w = std::max(w, t.max_error_kpa);
  return w;
}

DecodeScorer::DecodeScorer(const SkinConfig& skin, const DecoderConfig& dec, TruthFn truth)
    : skin_(skin), dec_(dec), truth_(std::move(truth)) {
  const size_t n = size_t(skin_.rows * skin_.cols);
  s_.taxel.resize(n);
  sq_sum_.assign(n, 0.0);
  err_n_.assign(n, 0);
}

bool DecodeScorer::lit(double kpa) const {
  return skin_.conductance.g(kpa) > dec_.ghost_threshold;
}

void DecodeScorer::add(const Frame& f) {
  ++s_.frames;
  if (f.pressure.size() == 0) return;
  // Steady: truth equal at the window's first, middle and last sample. The
  // stimuli are piecewise linear with ramps longer than a window, so equal
  // ends and middle mean constant truth over the window.
  const size_t last = f.sample, first = last + 1 - size_t(dec_.window);
  truth_(first, a_);
  truth_((first + last) / 2, b_);
  truth_(last, c_);
  for (size_t t = 0; t < c_.size(); ++t)
    if (std::fabs(a_[t] - c_[t]) > 1e-9 || std::fabs(b_[t] - c_[t]) > 1e-9) return;
  ++s_.steady_frames;
  bool ghost_raw = false, ghost = false;
  for (int i = 0; i < skin_.rows; ++i)
    for (int j = 0; j < skin_.cols; ++j) {
      const size_t t = size_t(i * skin_.cols + j);
      const double truth = c_[t], dec = f.pressure(i, j);
      ++s_.taxel[t].steady_frames;
      const bool truth_lit = lit(truth);
      if (truth_lit || lit(dec)) {
        const double e = std::fabs(dec - truth);
        sq_sum_[t] += e * e;
        ++err_n_[t];
        s_.taxel[t].max_error_kpa = std::max(s_.taxel[t].max_error_kpa, e);
      }
      if (!truth_lit && lit(f.pressure_raw(i, j))) {
        ++s_.ghost_taxel_frames_raw;
        ghost_raw = true;
      }
      if (!truth_lit && lit(dec)) {
        ++s_.ghost_taxel_frames;
        ghost = true;
      }
      if (truth_lit && !lit(dec)) ++s_.missed_taxel_frames;
    }
  s_.ghost_frames_raw += ghost_raw;
  s_.ghost_frames += ghost;
}

DecodeScore DecodeScorer::score() const {
  DecodeScore out = s_;
  for (size_t t = 0; t < out.taxel.size(); ++t)
    out.taxel[t].rms_error_kpa = err_n_[t] ? std::sqrt(sq_sum_[t] / double(err_n_[t])) : 0.0;
  return out;
}

}  // namespace eskin::golden
