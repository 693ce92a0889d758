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
#include "sim/hall_field_source.h"
#include "sim/hall_top_spec.h"
#include "sim/hall_sensor_array.h"
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

  ClockedDut<V> d;
  RampField ramp;
  eskin::sim::HallSensorArray io;  // the buses, muxes and sensors at the pins
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
      : io(src, h, spec) {
    start();
  }
  // nb buses of nsb sensors: direct at 0x0C + k, or all 0x0C behind mux channel k.
  HallBoard(int nb, int nsb, bool mux) : io(ramp, nb, nsb, mux) { start(); }
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
    uint64_t scl, sda, drdy;
    io.before(t, scl, sda, drdy);
    d.m.scl_i = scl;
    d.m.sda_i = sda;
    d.m.drdy = drdy;
    d.m.uart_rxd = uint8_t(line.tx_level());
    d.tick();
    io.after(t, d.m.scl_oe, d.m.sda_oe);
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
    for (size_t s = 0; s < io.size(); ++s) {
      size_t k = 0;  // index among sensor s's data readings
      for (size_t g = 0; g < f; ++g) k += frames()[g]->hall_samples[s].has_data();
      if (!frames()[f]->hall_samples[s].has_data()) continue;
      newest = std::max(newest, io.device(s).delivered()[k].t_done_ns / kClkNs);
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
