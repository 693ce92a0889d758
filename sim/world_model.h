// World model of a DTMF (spatial-frequency) skin: stimuli -> taxel pressure
// -> carrier amplitudes -> summing amplifier -> ADC codes.
//
// Physics (docs/scenes.md):
//   p_ij(t)  ground-truth pressure of taxel (i, j): the sum of all stimuli
//            active at t = n / adc.rate_hz (kPa).
//   g_ij     = skin.conductance.g(p_ij), the fraction 0..1 of a carrier that
//            the taxel passes to the common conductor.
//   A_row[i] = osc_amplitude_v * amp_gain * sum_j g_ij   (V peak at the ADC)
//   A_col[j] = osc_amplitude_v * amp_gain * sum_i g_ij
//   Each oscillator free-runs at its actual frequency f_k = nominal_k *
//   (1 + freq_error_k) with a start phase phi_k drawn uniformly from the seed.
//   v(n)     = offset_v + sum_k A_k(n) sin(2 pi f_k n / fs + phi_k) + w(n),
//              w ~ N(0, noise_rms_v^2), white.
//   code(n)  = round(v / lsb), lsb = full_scale_v / 2^bits, clamped to
//              0 .. 2^bits - 1 (each clamped sample counts as clipped).
// Only touched taxels and the lines through them are computed: a line no
// stimulus ever touches passes no carrier (g = 0) and is skipped. With
// noise_rms_v = 0 no noise is drawn. Deterministic for a seed
// (std::mt19937_64; phases and noise come from separate streams, so the noise
// level does not change the phases). One WorldModel per thread: the const
// queries reuse internal scratch buffers.
#pragma once

#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

#include "sim/scene.h"

namespace eskin::sim {

class WorldModel {
 public:
  explicit WorldModel(const Scene& scene);

  size_t total_samples() const;   // round(duration_s * rate_hz)
  bool next(int& code);           // next ADC code (unsigned 0..2^bits-1); false after the last
  size_t position() const;        // index of the next sample
  // Ground truth at sample n: row-major rows*cols, kPa.
  void pressure_at(size_t n, std::vector<double>& kpa) const;
  std::vector<int> all_codes();   // the whole stream from the current position
  size_t clipped() const;         // samples clipped at 0 or max code so far

  // Row-major indices (i * cols + j) of every taxel some stimulus can touch.
  const std::vector<int>& touched_taxels() const { return touched_; }
  // Start phase (radians) of carrier k (rows then cols), as drawn from the seed.
  double start_phase(int k) const { return phase_[size_t(k)]; }
  // Analog input (V) at sample n before noise and quantisation.
  double clean_voltage(size_t n) const;
  // Carrier k (rows, then columns) absent from samples [from, to): its
  // oscillator or drive line failed (the virtual board's carrier-off).
  void carrier_off(int k, size_t from, size_t to) { off_.push_back({k, from, to}); }

 private:
  // One touched taxel and the stimuli that can reach it (with their weights:
  // 1 for a taxel press, the disk's cover fraction for a position press;
  // slides are recomputed per sample).
  struct Contrib { int stimulus; double weight; };
  struct Site { int taxel; std::vector<Contrib> presses; std::vector<int> slides; };

  double site_pressure(const Site& s, double t) const;

  Scene scene_;
  std::vector<Site> sites_;
  std::vector<int> touched_;
  std::vector<double> freq_, phase_;
  std::vector<char> row_used_, col_used_;
  size_t total_ = 0, pos_ = 0, clipped_ = 0;
  std::mt19937_64 noise_rng_;
  std::normal_distribution<double> noise_;
  mutable std::vector<double> row_g_, col_g_;
  struct Off { int k; size_t from, to; };
  std::vector<Off> off_;
  bool is_off(int k, size_t n) const {
    for (const Off& o : off_)
      if (o.k == k && n >= o.from && n < o.to) return true;
    return false;
  }
};

}  // namespace eskin::sim
