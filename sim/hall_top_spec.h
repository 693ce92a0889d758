// rtl/hall_top.v's parameters for a Hall scene: buses, sensors per bus,
// addresses, TCA9548A channels, MLX90393 register words and the waits the
// sequencer needs (computed from the datasheet timing formula), as
// Verilator/Yosys -G overrides. Sensor s of the FPGA is sensor k of bus b at
// s = b * NSB + k; `slot` maps the scene's sensor index to it.
#pragma once

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "eskin/hall_config.h"
#include "eskin/mlx90393_config.h"

namespace eskin::sim {

struct HallTopSpec {
  int nb = 0, nsb = 0;
  std::vector<int> addr, mux_addr, mux_ch;  // per FPGA sensor slot
  std::vector<int> slot;                    // scene sensor -> FPGA slot
  uint16_t reg0 = 0, reg1 = 0, reg2 = 0;
  long conv_cyc = 0, stale_cyc = 0;
  // Decoding inside hall_top: hall_baseline and the command path whenever
  // the scene decodes anything, ft_calibrate (on slots ft_id..ft_id+2) for
  // `wrench`, hall_decouple (on slot dec_id) for `decouple`, force_curve (one
  // cell per slot curve_id..curve_id+nc-1) for `force_curve`; `locate` is
  // host-side by design.
  bool deltas = false, ft = false, decouple = false, curve = false;
  int ft_id = 0, dec_id = 0, curve_id = 0, nc = 1, curve_nb = 0;
  uint32_t dec_gain[3] = {0, 0, 0};    // UQ16.16 uT/LSB (hls/hall_decouple.h)
  uint32_t curve_gain[3] = {0, 0, 0};  // UQ4.12 uT/LSB (hls/force_curve.h)
  std::vector<int> lock_mn;            // the cells' range ends, mN
  // Breakpoints per range of the force curves eskin's calibration fits
  // (host/hall/hall_chain.h calibrate_force_curves' default): NB = 4 NR + 1.
  static constexpr int kCurvePerRange = 4;

  // Packs one field per slot, slot 0 in the low bits, as a Verilog literal.
  static std::string packed(const std::vector<int>& v, int bits) {
    const int n = int(v.size()) * bits;
    std::string hex((n + 3) / 4, '0');
    for (int i = 0; i < n; ++i) {
      const int bit = (v[i / bits] >> (i % bits)) & 1;
      if (!bit) continue;
      char& c = hex[hex.size() - 1 - i / 4];
      const int d = (c <= '9' ? c - '0' : c - 'a' + 10) | (1 << (i % 4));
      c = char(d < 10 ? '0' + d : 'a' + d - 10);
    }
    return std::to_string(n) + "'h" + hex;
  }
  std::vector<std::string> verilog_params() const {
    char r[64];
    std::vector<std::string> p = {"-GNB=" + std::to_string(nb), "-GNSB=" + std::to_string(nsb),
                                  "-GADDR=" + packed(addr, 7),
                                  "-GMUX_ADDR=" + packed(mux_addr, 7),
                                  "-GMUX_CH=" + packed(mux_ch, 3)};
    std::snprintf(r, sizeof r, "-GREG0=16'h%04x", reg0);
    p.push_back(r);
    std::snprintf(r, sizeof r, "-GREG1=16'h%04x", reg1);
    p.push_back(r);
    std::snprintf(r, sizeof r, "-GREG2=16'h%04x", reg2);
    p.push_back(r);
    p.push_back("-GCONV_CYC=" + std::to_string(conv_cyc));
    p.push_back("-GSTALE_CYC=" + std::to_string(stale_cyc));
    return p;
  }
  // The decoding's overrides (none for a scene that decodes nothing).
  std::vector<std::string> decode_params() const {
    std::vector<std::string> p;
    if (deltas) p.push_back("-GDELTAS=1");
    if (ft) p.push_back("-GFT=1"), p.push_back("-GFT_ID=" + std::to_string(ft_id));
    if (decouple) {
      p.push_back("-GDECOUPLE=1"), p.push_back("-GDEC_ID=" + std::to_string(dec_id));
      for (int a = 0; a < 3; ++a)
        p.push_back(std::string("-GDEC_GAIN_") + "XYZ"[a] + "=32'd" + std::to_string(dec_gain[a]));
    }
    if (curve) {
      p.push_back("-GCURVE=1"), p.push_back("-GCURVE_ID=" + std::to_string(curve_id));
      p.push_back("-GNC=" + std::to_string(nc));
      p.push_back("-GCURVE_NB=" + std::to_string(curve_nb));
      p.push_back("-GCURVE_NR=" + std::to_string(lock_mn.size()));
      for (int a = 0; a < 3; ++a)
        p.push_back(std::string("-GCURVE_GAIN_") + "XYZ"[a] + "=16'd" + std::to_string(curve_gain[a]));
      std::vector<int> rev(lock_mn.rbegin(), lock_mn.rend());  // range 0 in the low bits
      std::string hex;
      char w[16];
      for (int v : rev) std::snprintf(w, sizeof w, "%08x", unsigned(v)), hex += w;
      p.push_back("-GLOCK_MN=" + std::to_string(32 * lock_mn.size()) + "'h" + hex);
    }
    return p;
  }
};

// Throws ConfigError (naming the field) when the scene's buses cannot be
// built: hall_top gives every bus the same number of sensors.
inline HallTopSpec hall_top_spec(const HallConfig& h, double clk_hz = 12e6) {
  HallTopSpec s;
  s.nb = h.bus_count();
  std::vector<std::vector<int>> on_bus(s.nb);
  for (size_t i = 0; i < h.sensors.size(); ++i) on_bus[h.sensors[i].bus].push_back(int(i));
  s.nsb = s.nb ? int(on_bus[0].size()) : 0;
  for (int b = 0; b < s.nb; ++b)
    if (int(on_bus[b].size()) != s.nsb)
      throw ConfigError("hall.sensors", "bus " + std::to_string(b) + " has " +
                                            std::to_string(on_bus[b].size()) +
                                            " sensors, bus 0 has " + std::to_string(s.nsb) +
                                            ": hall_top needs the same number on every bus");
  s.slot.assign(h.sensors.size(), 0);
  for (int b = 0; b < s.nb; ++b)
    for (int k = 0; k < s.nsb; ++k) {
      const HallSensor& hs = h.sensors[on_bus[b][k]];
      s.slot[on_bus[b][k]] = b * s.nsb + k;
      s.addr.push_back(hs.i2c_address);
      s.mux_addr.push_back(hs.mux_address < 0 ? 0 : hs.mux_address);
      s.mux_ch.push_back(hs.mux_address < 0 ? 0 : hs.mux_channel);
    }
  mlx90393::Config c = h.mlx;
  c.trig_int_sel = true;  // INT pin = DRDY
  c.comm_mode = 3;        // I2C only
  s.reg0 = c.reg0();
  s.reg1 = c.reg1();
  s.reg2 = c.reg2();
  // Single mode waits the conversion with 20 % for the oscillator's spread;
  // burst mode reads a sensor anyway 1.5 periods into a round.
  s.conv_cyc = long(std::ceil(mlx90393::conversion_us(c, mlx90393::kXYZ) * 1.2 * clk_hz / 1e6));
  s.stale_cyc =
      long(std::ceil(mlx90393::burst_period_us(c, mlx90393::kXYZ) * 1.5 * clk_hz / 1e6));
  s.deltas = !h.decode.empty();
  s.ft = h.wants(HallDecode::Wrench);
  if (s.ft) {
    // The wrench reads the scene's first three sensors: consecutive slots.
    s.ft_id = s.slot.size() >= 3 ? s.slot[0] : -1;
    for (int i = 0; i < 3; ++i)
      if (s.ft_id < 0 || s.slot[size_t(i)] != s.ft_id + i)
        throw ConfigError("hall.sensors", "the wrench's sensors 0, 1, 2 must be consecutive "
                                          "on one bus for hall_top's ft_calibrate");
  }
  s.decouple = h.wants(HallDecode::Decouple);
  if (s.decouple) {
    // The decoupling reads the scene's first sensor (the split cell's).
    if (s.slot.empty()) throw ConfigError("hall.sensors", "decouple needs a sensor");
    s.dec_id = s.slot[0];
    for (int a = 0; a < 3; ++a)
      s.dec_gain[a] = uint32_t(std::lround(mlx90393::sensitivity_uT(h.mlx, a) * 65536));
  }
  s.curve = h.wants(HallDecode::ForceCurve);
  if (s.curve) {
    // One curve per stack cell, read by the scene's sensors 0 .. nc-1.
    std::vector<const HallCell*> stacks;
    for (const auto& c : h.cells)
      if (c.kind == CellKind::Stack) stacks.push_back(&c);
    s.nc = int(stacks.size());
    if (s.nc < 1 || s.nc > int(s.slot.size()))
      throw ConfigError("hall.cells", "force_curve needs 1 to " + std::to_string(s.slot.size()) +
                                          " stack cells (one sensor each), got " +
                                          std::to_string(s.nc));
    s.curve_id = s.slot[0];
    for (int i = 0; i < s.nc; ++i)
      if (s.slot[size_t(i)] != s.curve_id + i)
        throw ConfigError("hall.sensors", "the force curves' sensors 0 .. " +
                                              std::to_string(s.nc - 1) +
                                              " must be consecutive slots for hall_top's force_curve");
    const auto lock = stacks[0]->stack_lock_forces_n();
    for (const HallCell* c : stacks)
      if (c->stack_lock_forces_n() != lock)
        throw ConfigError("hall.cells", "hall_top's force_curve needs the same range ends in every "
                                        "stack cell (cell " + c->name + " differs)");
    for (double f : lock) s.lock_mn.push_back(int(std::lround(f * 1000)));
    s.curve_nb = int(lock.size()) * HallTopSpec::kCurvePerRange + 1;
    for (int a = 0; a < 3; ++a)
      s.curve_gain[a] = uint32_t(std::lround(mlx90393::sensitivity_uT(h.mlx, a) * 4096));
  }
  return s;
}

}  // namespace eskin::sim
