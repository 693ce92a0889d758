// Host-side, not synthesised: builds the fixed-point IzhikevichConfig of
// hls/izhikevich_layer.h from model parameters in double (its own preset
// table: hls/ shares no code with host/golden or common/).
//
// Quantisation (formats in hls/izhikevich_layer.h): k = tau * dt_ms;
//   v_init = rnd(-65 * 2^22), v_reset = rnd(c 2^22), c_const =
//   rnd(-16.25 k 2^22); u_init = rnd(k b (-65) 2^FU), u_jump = rnd(k d 2^FU);
//   c2 = 0.04 k, c3 = k^2 a b, c4 = k a, gain: mantissa normalised into
//   [2^14, 2^15) (relative error <= 0.5 / 2^14 = 2^-15) with the matching shift.
// Input scaling: one unit of the kernel input x is `input_lsb` units of the
// golden model's input (so I = K * input_lsb * x); x_shift drops low bits of
// x before the 16-bit multiplier (receptor: taxel g in UQ1.15 -> x_shift 1).
#pragma once

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "hls/izhikevich_layer.h"

namespace eskin::hls {

struct IzhikevichModel {
  double a = 0.02, b = 0.2, c = -65.0, d = 8.0, tau = 1.0, gain = 1.0;
};

// RS IB CH FS LTS TC RZ (Izhikevich 2003) and RA (DTMF thesis Table 4.1).
// Throws std::invalid_argument naming neuron.preset for an unknown name.
inline IzhikevichModel izhikevich_fixed_preset(const std::string& name) {
  //                                      a     b      c      d    tau  gain
  if (name == "RS") return IzhikevichModel{0.02, 0.2, -65.0, 8.0, 1.0, 1.0};
  if (name == "IB") return IzhikevichModel{0.02, 0.2, -55.0, 4.0, 1.0, 1.0};
  if (name == "CH") return IzhikevichModel{0.02, 0.2, -50.0, 2.0, 1.0, 1.0};
  if (name == "FS") return IzhikevichModel{0.1, 0.2, -65.0, 2.0, 1.0, 1.0};
  if (name == "LTS") return IzhikevichModel{0.02, 0.25, -65.0, 2.0, 1.0, 1.0};
  if (name == "TC") return IzhikevichModel{0.02, 0.25, -65.0, 0.05, 1.0, 1.0};
  if (name == "RZ") return IzhikevichModel{0.1, 0.26, -65.0, 2.0, 1.0, 1.0};
  if (name == "RA") return IzhikevichModel{0.02, 0.25, -55.0, 0.05, 0.97, 9.0};
  throw std::invalid_argument("neuron.preset: expected one of RS IB CH FS LTS TC RZ RA, got '" +
                              name + "'");
}

namespace izh_config {

inline int32_t qfrac(double x, int frac, const char* field) {
  const double y = std::nearbyint(std::ldexp(x, frac));
  if (!(y >= -1073741824.0 && y <= 1073741823.0))
    throw std::invalid_argument(std::string(field) + ": expected |value| < 2^" +
                                std::to_string(30 - frac) + " (Q." + std::to_string(frac) +
                                "), got " + std::to_string(x));
  return int32_t(y);
}
inline int32_t q22(double x, const char* field) { return qfrac(x, izh::kFrac, field); }

// value = m * 2^-(s + offset), m in [2^14, 2^15) (sign of value), s in [lo, hi].
inline void mantissa(double value, int offset, int lo, int hi, const char* field, int16_t& m,
                     int& s) {
  if (value == 0.0) { m = 0; s = lo < 0 ? 0 : lo; return; }
  const double mag = std::fabs(value);
  s = int(std::floor(std::log2(16384.0 / mag))) - offset;
  double r = std::nearbyint(std::ldexp(mag, s + offset));
  while (r >= 32768.0) { --s; r = std::nearbyint(std::ldexp(mag, s + offset)); }
  while (r < 16384.0) { ++s; r = std::nearbyint(std::ldexp(mag, s + offset)); }
  if (s < lo || s > hi)
    throw std::invalid_argument(std::string(field) + ": constant " + std::to_string(value) +
                                " needs shift " + std::to_string(s) + ", expected " +
                                std::to_string(lo) + ".." + std::to_string(hi));
  m = int16_t(value < 0 ? -r : r);
}

}  // namespace izh_config

// Throws std::invalid_argument naming the field: dt_ms * tau must be in
// (0, 1] ms, c in [-128, 30) mV, a in (0, 1/k), |d k| < 256, input_lsb > 0.
inline IzhikevichConfig make_izhikevich_config(const IzhikevichModel& p, double dt_ms,
                                               double input_lsb, int x_shift = 0) {
  using namespace izh_config;
  const double k = p.tau * dt_ms;
  if (!(k > 0.0 && k <= 1.0))
    throw std::invalid_argument("neuron.dt_ms: expected 0 < tau * dt_ms <= 1 ms, got " +
                                std::to_string(k));
  if (!(p.c >= -128.0 && p.c < 30.0))
    throw std::invalid_argument("neuron.c: expected -128 <= c < 30 mV, got " + std::to_string(p.c));
  if (!(p.a > 0.0 && k * p.a < 1.0))
    throw std::invalid_argument("neuron.a: expected 0 < a < 1 / (tau dt), got " +
                                std::to_string(p.a));
  if (!(std::fabs(p.b) <= 1.0))
    throw std::invalid_argument("neuron.b: expected |b| <= 1, got " + std::to_string(p.b));
  if (!(std::fabs(k * p.d) < 128.0))
    throw std::invalid_argument("neuron.d: expected |tau dt d| < 128, got " + std::to_string(p.d));
  if (!(input_lsb > 0.0))
    throw std::invalid_argument("neuron.input_lsb: expected > 0, got " + std::to_string(input_lsb));
  if (x_shift < 0 || x_shift > 16)
    throw std::invalid_argument("neuron.x_shift: expected 0..16, got " + std::to_string(x_shift));

  IzhikevichConfig c;
  // FU: largest fraction width (<= 30) with |U| = k |u| < 2^(30-FU) for
  // |u| <= 256 mV; at least 22 (k <= 1).
  int fu = 30;
  while (fu > izh::kFrac && 256.0 * k > std::ldexp(1.0, 30 - fu)) --fu;
  c.u_frac = uint8_t(fu);
  c.v_init = q22(-65.0, "neuron.v_init");
  c.u_init = qfrac(k * p.b * -65.0, fu, "neuron.u_init");
  c.v_reset = q22(p.c, "neuron.c");
  c.u_jump = qfrac(k * p.d, fu, "neuron.d");
  c.c_const = q22(-16.25 * k, "neuron.dt_ms");
  int s = 0;
  mantissa(0.04 * k, 8, 0, 40, "neuron.dt_ms", c.m2, s);
  c.s2 = uint8_t(s);
  mantissa(k * k * p.a * p.b, fu - 8, 0, 40, "neuron.a*b", c.m3, s);
  c.s3 = uint8_t(s);
  mantissa(k * p.a, 0, 0, 40, "neuron.a", c.m4, s);
  c.s4 = uint8_t(s);
  // J (Q.22) per xs unit.
  const double g = k * p.gain * input_lsb * std::ldexp(1.0, x_shift + izh::kFrac);
  mantissa(g, 0, -15, 40, "neuron.gain", c.gain, s);
  c.gain_shift = int8_t(s);
  c.x_shift = uint8_t(x_shift);
  return c;
}

}  // namespace eskin::hls
