// The bench around a Verilated rtl/hall_top.v (any parameter set, class V):
// MLX90393 models (and TCA9548A muxes) on simulated I2C buses at the pins,
// DRDY lines, the UART line decoded by host/link, with the cycle of every
// packet's first start bit and of its closing stop bit. Shared by
// tests/rtl/hall_top_test.cpp and `eskin bench latency`'s Hall harness
// (bench/latency/hall_latency_harness.cpp).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <utility>
#include <stdexcept>
#include <vector>

#include "clocked_dut.h"
#include "eskin/hall_config.h"
#include "host/link/link_decoder.h"
#include "i2c_pin_bench.h"
#include "sim/hall_field_source.h"
#include "sim/hall_top_spec.h"
#include "sim/mlx90393_model.h"
#include "sim/tca9548a_model.h"
#include "uart_line.h"

namespace hall_bench {

constexpr double kClkNs = 1e9 / 12e6;  // hall_top's CLK_HZ: 12 MHz
constexpr uint64_t kConvCyc = 24636;   // 2053 us
constexpr int kCpb = 4;                // 12 MHz / 3 Mbaud

struct RampField : eskin::sim::HallFieldSource {
  std::array<double, 3> field_uT(int sensor, double t_s) const override {
    return {5.0 * sensor + 2000.0 * t_s, -30.0 + 2.0 * sensor, 80.0 - sensor};
  }
};

template <class V>
struct HallBoard {
  using HallSample = eskin::link::HallSample;
  using LinkDecoder = eskin::link::LinkDecoder;
  using Packet = eskin::link::Packet;
  using Mlx90393Model = eskin::sim::Mlx90393Model;
  using Mlx90393Options = eskin::sim::Mlx90393Options;
  using Tca9548aModel = eskin::sim::Tca9548aModel;

  ClockedDut<V> d;
  RampField ramp;
  const eskin::sim::HallFieldSource* field = &ramp;
  std::vector<std::unique_ptr<I2cPinBus>> buses;
  std::vector<std::unique_ptr<Tca9548aModel>> muxes;
  std::map<std::pair<int, int>, Tca9548aModel*> mux_of;  // scene builds: (bus, address)

  // The bus segment of a scene sensor: 0 directly on the bus, else its
  // TCA9548A channel's (one mux model per bus and address, 0x70 + A2 A1 A0).
  int segment(int bus, int mux_address, int ch) {
    if (mux_address < 0) return 0;
    const std::pair<int, int> key{bus, mux_address};
    if (!mux_of.count(key)) {
      const int a = mux_address - 0x70;
      muxes.push_back(std::make_unique<Tca9548aModel>(buses[size_t(bus)]->bus, (a >> 2) & 1,
                                                      (a >> 1) & 1, a & 1));
      mux_of[key] = muxes.back().get();
    }
    return mux_of[key]->channel_segment(ch);
  }
  std::vector<std::unique_ptr<Mlx90393Model>> dev;
  LinkDecoder dec;
  UartLine line{kCpb};
  std::vector<Packet> packets;
  std::vector<uint64_t> first_byte_cycle;  // start bit of each packet's first byte
  std::vector<uint64_t> packet_cycle;      // cycle each packet was decoded (its closing
                                           // delimiter's stop bit sampled)
  std::vector<uint64_t> packet_start_cycle;  // per packet: its first byte's start bit

  // A scene's sensors (their own field source, noise and addresses) in the
  // FPGA slots of its hall_top spec.
  HallBoard(const eskin::sim::HallFieldSource& src, const eskin::HallConfig& h,
            const eskin::sim::HallTopSpec& spec)
      : field(&src) {
    for (int b = 0; b < spec.nb; ++b) buses.push_back(std::make_unique<I2cPinBus>());
    dev.resize(h.sensors.size());
    for (size_t i = 0; i < h.sensors.size(); ++i) {
      const auto& hs = h.sensors[i];
      Mlx90393Options o;
      o.base_address = uint8_t(hs.i2c_address);
      o.config = h.mlx;
      o.noise_rms_uT = {h.noise_rms_ut[0], h.noise_rms_ut[1], h.noise_rms_ut[2]};
      o.seed = 1000 + i;
      dev[spec.slot[i]] = std::make_unique<Mlx90393Model>(
          buses[hs.bus]->bus, *field, int(i), o, segment(hs.bus, hs.mux_address, hs.mux_channel));
    }
    start();
  }
  // nb buses of nsb sensors: direct at 0x0C + k, or all 0x0C behind mux channel k.
  HallBoard(int nb, int nsb, bool mux) {
    for (int b = 0; b < nb; ++b) {
      buses.push_back(std::make_unique<I2cPinBus>());
      if (mux) muxes.push_back(std::make_unique<Tca9548aModel>(buses[b]->bus, 0, 0, 0));
      for (int k = 0; k < nsb; ++k) {
        Mlx90393Options o;
        if (!mux) {
          o.a1 = (k >> 1) & 1;
          o.a0 = k & 1;
        }
        const int seg = mux ? muxes[b]->channel_segment(k) : 0;
        dev.push_back(std::make_unique<Mlx90393Model>(buses[b]->bus, *field, b * nsb + k, o, seg));
      }
    }
    start();
  }
  void start() {
    dec.on_packet([this](const Packet& p) {
      packets.push_back(p);
      packet_cycle.push_back(d.cycle);
      packet_start_cycle.push_back(frame_start_);
    });
    d.m.rst = 1;
    d.m.uart_rxd = 1;
    d.m.scl_i = 0;
    step();
    step();
    d.m.rst = 0;
  }
  void step() {
    const double t = double(d.cycle) * kClkNs;
    uint64_t scl = 0, sda = 0, drdy = 0;
    for (size_t b = 0; b < buses.size(); ++b) {
      bool c, a;
      buses[b]->before(t, c, a);
      scl |= uint64_t(c) << b;
      sda |= uint64_t(a) << b;
    }
    for (size_t s = 0; s < dev.size(); ++s) drdy |= uint64_t(dev[s]->drdy()) << s;
    d.m.scl_i = scl;
    d.m.sda_i = sda;
    d.m.drdy = drdy;
    d.m.uart_rxd = uint8_t(line.tx_level());
    d.tick();
    for (size_t b = 0; b < buses.size(); ++b)
      buses[b]->after(t, (d.m.scl_oe >> b) & 1, (d.m.sda_oe >> b) & 1);
    uart(d.m.uart_txd);
  }
  void run(uint64_t n) {
    for (uint64_t i = 0; i < n; ++i) step();
  }
  std::vector<const Packet*> frames() const {
    std::vector<const Packet*> r;
    for (const auto& p : packets)
      if (p.type == eskin::link::kHallSamples) r.push_back(&p);
    return r;
  }
  // DRDY time (cycles) of the newest reading in frame f: the one that
  // completed it.
  double newest_drdy_cycle(size_t f) const {
    double newest = 0;
    for (size_t s = 0; s < dev.size(); ++s) {
      size_t k = 0;  // index among sensor s's data readings
      for (size_t g = 0; g < f; ++g) k += frames()[g]->hall_samples[s].has_data();
      if (!frames()[f]->hall_samples[s].has_data()) continue;
      newest = std::max(newest, dev[s]->delivered()[k].t_done_ns / kClkNs);
    }
    return newest;
  }
  // Frame f's latency in clocks from the DRDY of the reading that completed
  // it: to the start bit of its first byte on the UART, and to the stop bit
  // of its last byte (the closing delimiter of the last of its packets:
  // HALL_SAMPLES, then HALL_DELTAS and HALL_WRENCH6 when the build decodes).
  struct FrameLatency {
    uint64_t first_byte = 0, last_byte = 0;
  };
  FrameLatency frame_latency(size_t f) const {
    namespace L = eskin::link;
    const uint64_t drdy = uint64_t(std::ceil(newest_drdy_cycle(f)));
    size_t seen = 0, i = 0;
    for (; i < packets.size(); ++i)
      if (packets[i].type == L::kHallSamples && seen++ == f) break;
    if (i == packets.size()) throw std::out_of_range("HallBoard: no such frame");
    FrameLatency r{packet_start_cycle[i] - drdy, packet_cycle[i] - drdy};
    for (size_t j = i + 1; j < packets.size() && packets[j].type != L::kHallSamples; ++j)
      if (packets[j].type == L::kHallDeltas || packets[j].type == L::kHallWrench6)
        r.last_byte = packet_cycle[j] - drdy;
    return r;
  }

 private:
  void uart(int level) {
    if (!line.rx_sample(level, d.cycle)) return;
    const uint8_t byte = line.byte();
    if (!in_frame_ && byte != 0) {
      in_frame_ = true;
      first_byte_cycle.push_back(line.start_cycle());
      frame_start_ = line.start_cycle();
    }
    if (byte == 0) in_frame_ = false;
    dec.feed(&byte, 1);
  }
  bool in_frame_ = false;
  uint64_t frame_start_ = 0;
};

}  // namespace hall_bench
