#include "sim/hall_sampler.h"

#include <cmath>

namespace eskin::sim {

HallSampler::HallSampler(const HallConfig& cfg, uint64_t seed)
    : cfg_(cfg), rng_(seed ^ 0xA5A5F00DC0FFEEULL) {}

double HallSampler::period_s() const {
  return mlx90393::conversion_us(cfg_.mlx, mlx90393::kXYZ) * 1e-6;
}

HallFrame HallSampler::sample(const std::vector<Vec3>& field, double t_s) {
  HallFrame f(field.size());
  for (size_t s = 0; s < field.size(); ++s) {
    HallSample& x = f[s];
    x.sensor = uint8_t(s);
    x.t_us = uint32_t(std::llround(t_s * 1e6));
    for (int a = 0; a < 3; ++a) {
      const double b = field[s][size_t(a)] + cfg_.noise_rms_ut[size_t(a)] * noise_(rng_);
      const mlx90393::Code c = mlx90393::encode_uT(cfg_.mlx, a, b);
      x.lsb[size_t(a)] = int16_t(mlx90393::code_to_lsb(cfg_.mlx, a, c.code));
      if (c.saturated) x.flags |= uint8_t(kHallSatX << a);
    }
  }
  return f;
}

HallFrame HallSampler::sample(const HallWorld& world, double t_s) {
  std::vector<Vec3> field;
  for (size_t s = 0; s < world.config().sensors.size(); ++s)
    field.push_back(world.field_uT(int(s), t_s));
  return sample(field, t_s);
}

}  // namespace eskin::sim
