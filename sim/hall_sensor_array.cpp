#include "sim/hall_sensor_array.h"

namespace eskin::sim {

HallSensorArray::HallSensorArray(const HallFieldSource& field, const HallConfig& h,
                                 const HallTopSpec& spec) {
  for (int b = 0; b < spec.nb; ++b) buses_.push_back(std::make_unique<I2cPinBus>());
  dev_.resize(h.sensors.size());
  for (size_t i = 0; i < h.sensors.size(); ++i) {
    const auto& hs = h.sensors[i];
    Mlx90393Options o;
    o.base_address = uint8_t(hs.i2c_address);
    o.config = h.mlx;
    o.noise_rms_uT = {h.noise_rms_ut[0], h.noise_rms_ut[1], h.noise_rms_ut[2]};
    o.seed = 1000 + i;  // one noise stream per scene sensor
    dev_[size_t(spec.slot[i])] = std::make_unique<Mlx90393Model>(
        buses_[size_t(hs.bus)]->bus, field, int(i), o,
        segment(hs.bus, hs.mux_address, hs.mux_channel));
  }
}

HallSensorArray::HallSensorArray(const HallFieldSource& field, int nb, int nsb, bool mux) {
  for (int b = 0; b < nb; ++b) {
    buses_.push_back(std::make_unique<I2cPinBus>());
    for (int k = 0; k < nsb; ++k) {
      Mlx90393Options o;
      if (!mux) {
        o.a1 = (k >> 1) & 1;
        o.a0 = k & 1;
      }
      const int seg = mux ? segment(b, 0x70, k) : 0;
      dev_.push_back(std::make_unique<Mlx90393Model>(buses_[size_t(b)]->bus, field, b * nsb + k, o, seg));
    }
  }
}

// The bus segment of a sensor: 0 directly on the bus, else its TCA9548A
// channel's (one mux model per bus and address, 0x70 + A2 A1 A0).
int HallSensorArray::segment(int bus, int mux_address, int ch) {
  if (mux_address < 0) return 0;
  const std::pair<int, int> key{bus, mux_address};
  if (!mux_of_.count(key)) {
    const int a = mux_address - 0x70;
    muxes_.push_back(std::make_unique<Tca9548aModel>(buses_[size_t(bus)]->bus, (a >> 2) & 1,
                                                     (a >> 1) & 1, a & 1));
    mux_of_[key] = muxes_.back().get();
  }
  return mux_of_[key]->channel_segment(ch);
}

void HallSensorArray::before(double t_ns, uint64_t& scl, uint64_t& sda, uint64_t& drdy) {
  scl = sda = drdy = 0;
  for (size_t b = 0; b < buses_.size(); ++b) {
    bool c, a;
    buses_[b]->before(t_ns, c, a);
    scl |= uint64_t(c) << b;
    sda |= uint64_t(a) << b;
  }
  for (size_t s = 0; s < dev_.size(); ++s) drdy |= uint64_t(dev_[s]->drdy()) << s;
}

void HallSensorArray::after(double t_ns, uint64_t scl_oe, uint64_t sda_oe) {
  for (size_t b = 0; b < buses_.size(); ++b)
    buses_[b]->after(t_ns, (scl_oe >> b) & 1, (sda_oe >> b) & 1);
}

std::vector<std::string> HallSensorArray::violations() const {
  std::vector<std::string> v;
  for (size_t b = 0; b < buses_.size(); ++b)
    for (const auto& m : buses_[b]->bus.violations()) v.push_back("bus " + std::to_string(b) + ": " + m);
  return v;
}

size_t HallSensorArray::violation_count() const {
  size_t n = 0;
  for (const auto& b : buses_) n += b->bus.violation_count();
  return n;
}

}  // namespace eskin::sim
