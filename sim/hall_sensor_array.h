// A Hall skin's devices at the FPGA's pins: one simulated I2C bus per bus
// the FPGA top masters (sim/i2c_pin_bus.h), the MLX90393 models on them
// (TCA9548A muxes where the scene puts sensors behind one) and their DRDY
// lines, the field coming from a HallFieldSource (the scene's world). Each
// FPGA clock: before() gives the FPGA the line levels and DRDYs just before
// the edge, after() applies its pull-downs from the edge on. Sensor s of the
// FPGA is its slot s (sim/hall_top_spec.h: bus b, k-th on it, s = b*NSB+k).
// Shared by the virtual board (sim/vboard) and the RTL test bench
// (tests/rtl/hall_top_board.h).
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "eskin/hall_config.h"
#include "sim/hall_field_source.h"
#include "sim/hall_top_spec.h"
#include "sim/i2c_pin_bus.h"
#include "sim/mlx90393_model.h"
#include "sim/tca9548a_model.h"

namespace eskin::sim {

class HallSensorArray {
 public:
  // A scene's sensors (their addresses, muxes, register settings and noise)
  // in the FPGA slots of its hall_top spec.
  HallSensorArray(const HallFieldSource& field, const HallConfig& h, const HallTopSpec& spec);
  // nb buses of nsb default sensors: directly at 0x0C + k, or all at 0x0C
  // behind TCA9548A channel k (one mux per bus at 0x70).
  HallSensorArray(const HallFieldSource& field, int nb, int nsb, bool mux);

  // Pin levels just before the clock edge at t_ns, one bit per bus / slot.
  void before(double t_ns, uint64_t& scl, uint64_t& sda, uint64_t& drdy);
  // The FPGA's pull-downs (scl_oe, sda_oe: one bit per bus) after that edge.
  void after(double t_ns, uint64_t scl_oe, uint64_t sda_oe);

  size_t bus_count() const { return buses_.size(); }
  I2cPinBus& bus(size_t b) { return *buses_[b]; }
  size_t size() const { return dev_.size(); }
  Mlx90393Model& device(size_t slot) { return *dev_[slot]; }
  const Mlx90393Model& device(size_t slot) const { return *dev_[slot]; }
  // The bus-timing violations' messages so far, "bus B: ..." (empty:
  // none; each bus keeps its first ones), and their count on all buses.
  std::vector<std::string> violations() const;
  size_t violation_count() const;

 private:
  int segment(int bus, int mux_address, int ch);

  std::vector<std::unique_ptr<I2cPinBus>> buses_;
  std::vector<std::unique_ptr<Tca9548aModel>> muxes_;
  std::map<std::pair<int, int>, Tca9548aModel*> mux_of_;  // (bus, address)
  std::vector<std::unique_ptr<Mlx90393Model>> dev_;
};

}  // namespace eskin::sim
