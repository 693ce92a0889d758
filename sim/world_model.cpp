#include "sim/world_model.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace eskin::sim {
namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;

// Uniform in [0, 2 pi) from the top 53 bits: the same phases on every
// platform (std::uniform_real_distribution is implementation-defined).
double uniform_phase(std::mt19937_64& rng) {
  return double(rng() >> 11) * (1.0 / 9007199254740992.0) * kTwoPi;
}

// Cells whose unit square can meet a disk of radius r centred anywhere on the
// segment (x0, y0)-(x1, y1): centre distance to the segment <= r + sqrt(2)/2.
std::vector<int> cells_near_segment(double x0, double y0, double x1, double y1, double r,
                                    int rows, int cols) {
  std::vector<int> out;
  const double reach = r + 0.7072;
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j) {
      double dx = x1 - x0, dy = y1 - y0, len2 = dx * dx + dy * dy;
      double s = len2 > 0 ? std::clamp(((j - x0) * dx + (i - y0) * dy) / len2, 0.0, 1.0) : 0.0;
      double ex = x0 + s * dx - j, ey = y0 + s * dy - i;
      if (ex * ex + ey * ey <= reach * reach) out.push_back(i * cols + j);
    }
  return out;
}

}  // namespace

WorldModel::WorldModel(const Scene& scene)
    : scene_(scene), noise_rng_(scene.seed ^ 0x9E3779B97F4A7C15ULL), noise_(0.0, 1.0) {
  if (!scene_.has_skin)
    throw std::invalid_argument(scene_.file + ": the DTMF world model needs a skin: section (this scene has only hall:)");
  const SkinConfig& skin = scene_.skin;
  const int rows = skin.rows, cols = skin.cols;
  total_ = size_t(std::llround(scene_.duration_s * skin.adc.rate_hz));

  // Phases for every carrier in a fixed order, touched or not, so adding a
  // stimulus on one line never changes another line's phase.
  std::mt19937_64 phase_rng(scene_.seed);
  freq_ = skin.actual_freqs_hz();
  for (size_t k = 0; k < freq_.size(); ++k) phase_.push_back(uniform_phase(phase_rng));

  // Touched sites: a map from taxel to the stimuli that reach it.
  std::vector<int> site_of(size_t(rows) * cols, -1);
  auto site = [&](int taxel) -> Site& {
    if (site_of[size_t(taxel)] < 0) {
      site_of[size_t(taxel)] = int(sites_.size());
      sites_.push_back({taxel, {}, {}});
    }
    return sites_[size_t(site_of[size_t(taxel)])];
  };
  for (size_t s = 0; s < scene_.presses.size(); ++s) {
    const Press& p = scene_.presses[s];
    if (!p.at_position) {
      site(p.row * cols + p.col).presses.push_back({int(s), 1.0});
      continue;
    }
    for (int t : cells_near_segment(p.x, p.y, p.x, p.y, p.radius, rows, cols)) {
      double w = disk_cover_fraction(p.x, p.y, p.radius, t / cols, t % cols);
      if (w > 0) site(t).presses.push_back({int(s), w});
    }
  }
  for (size_t s = 0; s < scene_.slides.size(); ++s) {
    const Slide& sl = scene_.slides[s];
    for (int t : cells_near_segment(sl.x0, sl.y0, sl.x1, sl.y1, sl.radius, rows, cols))
      site(t).slides.push_back(int(s));
  }
  std::sort(sites_.begin(), sites_.end(),
            [](const Site& a, const Site& b) { return a.taxel < b.taxel; });
  row_used_.assign(size_t(rows), 0);
  col_used_.assign(size_t(cols), 0);
  for (const Site& s : sites_) {
    touched_.push_back(s.taxel);
    row_used_[size_t(s.taxel / cols)] = 1;
    col_used_[size_t(s.taxel % cols)] = 1;
  }
  row_g_.assign(size_t(rows), 0.0);
  col_g_.assign(size_t(cols), 0.0);
}

double WorldModel::site_pressure(const Site& s, double t) const {
  double p = 0;
  for (const Contrib& c : s.presses) {
    const Press& pr = scene_.presses[size_t(c.stimulus)];
    p += pr.pressure_kpa * c.weight * pr.envelope(t);
  }
  const int cols = scene_.skin.cols;
  for (int k : s.slides) {
    const Slide& sl = scene_.slides[size_t(k)];
    double env = sl.envelope(t);
    if (env <= 0) continue;
    double x, y;
    sl.centre(t, x, y);
    p += sl.pressure_kpa * env * disk_cover_fraction(x, y, sl.radius, s.taxel / cols, s.taxel % cols);
  }
  return p;
}

size_t WorldModel::total_samples() const { return total_; }
size_t WorldModel::position() const { return pos_; }
size_t WorldModel::clipped() const { return clipped_; }

void WorldModel::pressure_at(size_t n, std::vector<double>& kpa) const {
  kpa.assign(size_t(scene_.skin.rows) * scene_.skin.cols, 0.0);
  const double t = double(n) / scene_.skin.adc.rate_hz;
  for (const Site& s : sites_) kpa[size_t(s.taxel)] = site_pressure(s, t);
}

double WorldModel::clean_voltage(size_t n) const {
  const SkinConfig& skin = scene_.skin;
  const double t = double(n) / skin.adc.rate_hz;
  std::fill(row_g_.begin(), row_g_.end(), 0.0);
  std::fill(col_g_.begin(), col_g_.end(), 0.0);
  for (const Site& s : sites_) {
    double g = skin.conductance.g(site_pressure(s, t));
    row_g_[size_t(s.taxel / skin.cols)] += g;
    col_g_[size_t(s.taxel % skin.cols)] += g;
  }
  const double a = skin.osc_amplitude_v * skin.amp_gain;
  double v = skin.adc.offset_v;
  const double dn = double(n);
  for (int i = 0; i < skin.rows; ++i)
    if (row_used_[size_t(i)] && row_g_[size_t(i)] > 0 && !is_off(i, n))
      v += a * row_g_[size_t(i)] *
           std::sin(kTwoPi * freq_[size_t(i)] * dn / skin.adc.rate_hz + phase_[size_t(i)]);
  for (int j = 0; j < skin.cols; ++j) {
    size_t k = size_t(skin.rows + j);
    if (col_used_[size_t(j)] && col_g_[size_t(j)] > 0 && !is_off(skin.rows + j, n))
      v += a * col_g_[size_t(j)] * std::sin(kTwoPi * freq_[k] * dn / skin.adc.rate_hz + phase_[k]);
  }
  return v;
}

bool WorldModel::next(int& code) {
  if (pos_ >= total_) return false;
  const AdcConfig& adc = scene_.skin.adc;
  double v = clean_voltage(pos_);
  if (adc.noise_rms_v > 0) v += adc.noise_rms_v * noise_(noise_rng_);
  double c = std::nearbyint(v / adc.lsb_v());
  if (c < 0) {
    c = 0;
    ++clipped_;
  } else if (c > adc.max_code()) {
    c = adc.max_code();
    ++clipped_;
  }
  code = int(c);
  ++pos_;
  return true;
}

std::vector<int> WorldModel::all_codes() {
  std::vector<int> out;
  out.reserve(total_ - std::min(pos_, total_));
  int c;
  while (next(c)) out.push_back(c);
  return out;
}

}  // namespace eskin::sim
