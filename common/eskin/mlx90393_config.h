// MLX90393 3-axis Hall sensor: register fields, commands, status byte,
// conversion timing, sensitivity and output code formats. The one place the
// device's facts live; the device model (sim/mlx90393_model.h), the scene
// loader, the golden decoder and the FPGA sequencer's generated parameters
// all use it. Header-only. Facts from the Melexis MLX90393 datasheet
// (register map, command set, timing table, sensitivity table, output format
// table); where the model has to choose, the comment says so.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <string>

#include "eskin/skin_config.h"  // ConfigError

namespace eskin::mlx90393 {

// ---- I2C addresses -------------------------------------------------------
// 7-bit address = variant base + (A1 << 1 | A0). The -011 variant's base is
// 0x0C (0x0C..0x0F with the two address pins); other variants use 0x10,
// 0x14, 0x18.
constexpr uint8_t kBaseAddress = 0x0C;
constexpr uint8_t address(int a1, int a0, uint8_t base = kBaseAddress) {
  return uint8_t(base + ((a1 & 1) << 1) + (a0 & 1));
}

// ---- Commands (first byte of every write) --------------------------------
// SB/SW/SM/RM take a zyxt nibble (bit 0 T, 1 X, 2 Y, 3 Z) in the low bits.
enum Command : uint8_t {
  kNOP = 0x00,
  kSB = 0x10,  // start burst mode
  kSW = 0x20,  // start wake-up-on-change mode
  kSM = 0x30,  // start single measurement
  kRM = 0x40,  // read measurement
  kRR = 0x50,  // read register: second byte = address << 2
  kWR = 0x60,  // write register: data MSB, data LSB, address << 2
  kEX = 0x80,  // exit mode
  kHR = 0xD0,  // memory recall (non-volatile -> RAM)
  kHS = 0xE0,  // memory store (RAM -> non-volatile)
  kRT = 0xF0,  // reset
};
enum AxisBit : uint8_t { kT = 0x1, kX = 0x2, kY = 0x4, kZ = 0x8, kXYZ = 0xE, kXYZT = 0xF };

// Number of 16-bit values a zyxt selection returns.
constexpr int value_count(uint8_t zyxt) {
  return (zyxt & 1) + ((zyxt >> 1) & 1) + ((zyxt >> 2) & 1) + ((zyxt >> 3) & 1);
}

// ---- Status byte (first byte of every reply) -----------------------------
enum StatusBit : uint8_t {
  kStatusBurst = 0x80,  // burst mode active
  kStatusWoc = 0x40,    // wake-up-on-change mode active
  kStatusSm = 0x20,     // single measurement mode active
  kStatusError = 0x10,  // command rejected or data not valid
  kStatusSed = 0x08,    // single error detected (corrected) in memory
  kStatusRs = 0x04,     // reset happened (cleared by the next command)
  kStatusD = 0x03,      // D1:D0: the reply carries 2 + 2*D data bytes
};
// D1:D0 for a reply carrying `bytes` data bytes after the status (2..8);
// replies without data (and RR, 2 bytes) carry D = 0.
constexpr uint8_t d_field(int bytes) { return bytes <= 2 ? 0 : uint8_t((bytes - 2) / 2); }

// ---- Register map (16-bit words in volatile RAM) -------------------------
enum Register : uint8_t {
  kReg0 = 0x00,  // [3:0] HALLCONF, [6:4] GAIN_SEL, [7] Z_SERIES, [8] BIST
  kReg1 = 0x01,  // [5:0] BURST_DATA_RATE, [9:6] BURST_SEL (zyxt), [10] TCMP_EN,
                 // [11] EXT_TRIG, [12] WOC_DIFF, [14:13] COMM_MODE, [15] TRIG_INT_SEL
  kReg2 = 0x02,  // [1:0] OSR, [4:2] DIG_FILT, [6:5] RES_X, [8:7] RES_Y,
                 // [10:9] RES_Z, [12:11] OSR2
  kRegSensTc = 0x03,  // [7:0] SENS_TC_LT, [15:8] SENS_TC_HT
  kRegOffsetX = 0x04, kRegOffsetY = 0x05, kRegOffsetZ = 0x06,
  kRegWoxyThreshold = 0x07, kRegWozThreshold = 0x08, kRegWotThreshold = 0x09,
  kRegTref = 0x24,  // reference temperature code (Melexis area, read-only)
};
constexpr int kRegisterCount = 0x40;  // addresses 0x00..0x3F (6-bit field)
constexpr int kUserRegisterLast = 0x1F;  // 0x20.. are Melexis' (not writable)

enum class Hallconf : uint8_t { k0x0 = 0x0, k0xC = 0xC };

struct Config {
  // register 0
  int hallconf = 0xC;  // only 0xC (default) and 0x0 have datasheet tables
  int gain_sel = 7;    // 0..7: analog gain 5x .. 1x
  bool z_series = false;
  bool bist = false;
  // register 1
  int burst_data_rate = 0;  // 0..63: burst interval = value * 20 ms (0: back to back)
  int burst_sel = kXYZ;     // zyxt measured in burst mode when SB's nibble is 0
  bool tcmp_en = false;     // on-chip temperature compensation
  bool ext_trig = false;
  bool woc_diff = false;
  int comm_mode = 3;        // 3: I2C only
  bool trig_int_sel = true; // INT pin mode (DRDY), not TRIG input
  // register 2
  int osr = 0;       // 0..3: magnetic ADC oversampling 2^OSR
  int dig_filt = 2;  // 0..7: digital filter 2^DIG_FILT
  int res_x = 0, res_y = 0, res_z = 0;  // 0..3: which 16 of the ADC bits
  int osr2 = 0;      // 0..3: temperature ADC oversampling

  uint16_t reg0() const {
    return uint16_t((hallconf & 0xF) | (gain_sel & 7) << 4 | int(z_series) << 7 | int(bist) << 8);
  }
  uint16_t reg1() const {
    return uint16_t((burst_data_rate & 0x3F) | (burst_sel & 0xF) << 6 | int(tcmp_en) << 10 |
                    int(ext_trig) << 11 | int(woc_diff) << 12 | (comm_mode & 3) << 13 |
                    int(trig_int_sel) << 15);
  }
  uint16_t reg2() const {
    return uint16_t((osr & 3) | (dig_filt & 7) << 2 | (res_x & 3) << 5 | (res_y & 3) << 7 |
                    (res_z & 3) << 9 | (osr2 & 3) << 11);
  }
  static Config from_registers(uint16_t r0, uint16_t r1, uint16_t r2) {
    Config c;
    c.hallconf = r0 & 0xF;
    c.gain_sel = (r0 >> 4) & 7;
    c.z_series = (r0 >> 7) & 1;
    c.bist = (r0 >> 8) & 1;
    c.burst_data_rate = r1 & 0x3F;
    c.burst_sel = (r1 >> 6) & 0xF;
    c.tcmp_en = (r1 >> 10) & 1;
    c.ext_trig = (r1 >> 11) & 1;
    c.woc_diff = (r1 >> 12) & 1;
    c.comm_mode = (r1 >> 13) & 3;
    c.trig_int_sel = (r1 >> 15) & 1;
    c.osr = r2 & 3;
    c.dig_filt = (r2 >> 2) & 7;
    c.res_x = (r2 >> 5) & 3;
    c.res_y = (r2 >> 7) & 3;
    c.res_z = (r2 >> 9) & 3;
    c.osr2 = (r2 >> 11) & 3;
    return c;
  }
  int res(int axis) const { return axis == 0 ? res_x : axis == 1 ? res_y : res_z; }
};

// Why a configuration is illegal, naming the field (prefix + "." + field),
// or "" when it is legal. With the default HALLCONF 0xC the datasheet does
// not permit OSR 0 with DIG_FILT 0 or 1, nor OSR 1 with DIG_FILT 0.
inline std::string illegal_reason(const Config& c, const std::string& prefix = "mlx90393") {
  auto range = [&](const char* f, int v, int lo, int hi) -> std::string {
    if (v >= lo && v <= hi) return "";
    return prefix + "." + f + ": " + std::to_string(v) + " is outside " + std::to_string(lo) +
           ".." + std::to_string(hi);
  };
  for (auto s : {range("gain_sel", c.gain_sel, 0, 7), range("osr", c.osr, 0, 3),
                 range("dig_filt", c.dig_filt, 0, 7), range("osr2", c.osr2, 0, 3),
                 range("res_x", c.res_x, 0, 3), range("res_y", c.res_y, 0, 3),
                 range("res_z", c.res_z, 0, 3),
                 range("burst_data_rate", c.burst_data_rate, 0, 63),
                 range("burst_sel", c.burst_sel, 0, 15), range("comm_mode", c.comm_mode, 0, 3)})
    if (!s.empty()) return s;
  if (c.hallconf != 0xC && c.hallconf != 0x0)
    return prefix + ".hallconf: " + std::to_string(c.hallconf) +
           " has no datasheet timing/sensitivity table (use 0xC, the default, or 0x0)";
  if (c.hallconf == 0xC && ((c.osr == 0 && c.dig_filt <= 1) || (c.osr == 1 && c.dig_filt == 0)))
    return prefix + ".dig_filt: DIG_FILT " + std::to_string(c.dig_filt) + " with OSR " +
           std::to_string(c.osr) +
           " is not permitted with HALLCONF 0xC (needs DIG_FILT >= 2 at OSR 0, >= 1 at OSR 1)";
  return "";
}
inline void validate(const Config& c, const std::string& prefix = "mlx90393") {
  const std::string why = illegal_reason(c, prefix);
  if (!why.empty()) {
    const auto colon = why.find(": ");
    throw ConfigError(why.substr(0, colon), why.substr(colon + 2));
  }
}

// ---- Conversion timing (µs, typical, HALLCONF 0xC) -----------------------
// Datasheet timing table: one magnetic axis takes
//   TCONVM = 67 + 64 * 2^OSR * (2 + 2^DIG_FILT),
// the temperature channel TCONVT = 67 + 192 * 2^OSR2, and a measurement adds
// the wake-up from idle (TSTBY), the analog start-up (TACTIVE) and the end of
// the analog phase (TCONV_END):
//   TCONV = TSTBY + TACTIVE + m * TCONVM + [T] * TCONVT + TCONV_END.
// The typical values are used (the internal oscillator spreads them by up to
// about 20 %; a master that cannot see DRDY must allow for that).
// HALLCONF 0x0 is modelled with the same formula (an assumption: the
// datasheet's timing table is given for 0xC).
constexpr double kTstbyUs = 220.0;
constexpr double kTactiveUs = 360.0;
constexpr double kTconvEndUs = 120.0;

constexpr double tconvm_us(int osr, int dig_filt) {
  return 67.0 + 64.0 * double(1 << osr) * (2.0 + double(1 << dig_filt));
}
constexpr double tconvt_us(int osr2) { return 67.0 + 192.0 * double(1 << osr2); }

// One measurement of the axes in `zyxt`, from the command's STOP to DRDY.
inline double conversion_us(const Config& c, uint8_t zyxt) {
  const int m = ((zyxt >> 1) & 1) + ((zyxt >> 2) & 1) + ((zyxt >> 3) & 1);
  return kTstbyUs + kTactiveUs + m * tconvm_us(c.osr, c.dig_filt) +
         ((zyxt & kT) ? tconvt_us(c.osr2) : 0.0) + kTconvEndUs;
}
// Burst mode repeats every max(TCONV, BURST_DATA_RATE * 20 ms).
inline double burst_period_us(const Config& c, uint8_t zyxt) {
  const double interval = 20000.0 * c.burst_data_rate;
  const double tconv = conversion_us(c, zyxt);
  return interval > tconv ? interval : tconv;
}
// The sensor's maximum output data rate for `zyxt` (burst, rate 0).
inline double max_output_rate_hz(const Config& c, uint8_t zyxt) {
  return 1e6 / conversion_us(c, zyxt);
}

// ---- Sensitivity (µT per LSB) --------------------------------------------
// Datasheet sensitivity table at RES 0 per GAIN_SEL (0 = 5x .. 7 = 1x); each
// RES step doubles the LSB. Index [hallconf == 0xC][axis is Z][gain_sel].
inline double sensitivity_uT(int hallconf, int gain_sel, int res, int axis) {
  static constexpr double kTable[2][2][8] = {
      {{0.787, 0.629, 0.472, 0.393, 0.315, 0.262, 0.210, 0.157},    // 0x0 XY
       {1.267, 1.014, 0.760, 0.634, 0.507, 0.422, 0.338, 0.253}},   // 0x0 Z
      {{0.751, 0.601, 0.451, 0.376, 0.300, 0.250, 0.200, 0.150},    // 0xC XY
       {1.210, 0.968, 0.726, 0.605, 0.484, 0.403, 0.323, 0.242}}};  // 0xC Z
  return kTable[hallconf == 0xC][axis == 2][gain_sel & 7] * double(1 << (res & 3));
}
inline double sensitivity_uT(const Config& c, int axis) {
  return sensitivity_uT(c.hallconf, c.gain_sel, c.res(axis), axis);
}

// ---- Output code format per RES and TCMP_EN ------------------------------
// The ADC keeps 19 bits; RES selects which 16 go out. The signed field value
// q (in LSB of the selected RES) is sent as code = q + offset, q clamped to
// [lo, hi]:
//   TCMP_EN 0, RES 0 and 1: two's complement int16          (offset 0)
//   TCMP_EN 0, RES 2:      unsigned, zero field at 0x8000    (offset 32768)
//   TCMP_EN 0, RES 3:      unsigned, zero field at 0x4000, 0..0x7FFF
//   TCMP_EN 1, any RES:    unsigned, zero field at 0x8000
// The analog range is +-2^17 LSB at RES 0 (that is why RES 3 spans only
// 15 bits); RES 0/1 clip at the int16 range first.
struct CodeFormat {
  int offset;
  int lo, hi;  // clamp range of q
};
constexpr CodeFormat code_format(int res, bool tcmp_en) {
  if (tcmp_en) return {32768, -32768, 32767};
  switch (res & 3) {
    case 0:
    case 1: return {0, -32768, 32767};
    case 2: return {32768, -32768, 32767};
    default: return {16384, -16384, 16383};
  }
}
struct Code {
  uint16_t code;
  bool saturated;  // the field was outside the format's range and clamped
};
// Quantise a field value (µT) on `axis` (0 X, 1 Y, 2 Z) as the device sends it.
inline Code encode_uT(const Config& c, int axis, double field_uT) {
  const CodeFormat f = code_format(c.res(axis), c.tcmp_en);
  const double q = std::nearbyint(field_uT / sensitivity_uT(c, axis));
  bool sat = false;
  long v = 0;
  if (!(q > f.lo)) {
    v = f.lo;
    sat = true;
  } else if (!(q < f.hi)) {
    v = f.hi;
    sat = true;
  } else {
    v = long(q);
  }
  return {uint16_t(v + f.offset), sat};
}
// Signed field value in LSB of the selected RES.
inline int code_to_lsb(const Config& c, int axis, uint16_t code) {
  const CodeFormat f = code_format(c.res(axis), c.tcmp_en);
  return f.offset ? int(code) - f.offset : int(int16_t(code));
}
inline double decode_uT(const Config& c, int axis, uint16_t code) {
  return code_to_lsb(c, axis, code) * sensitivity_uT(c, axis);
}
// A code at either end of its format's range: the field may have been clamped.
inline bool code_saturated(const Config& c, int axis, uint16_t code) {
  const CodeFormat f = code_format(c.res(axis), c.tcmp_en);
  const int q = code_to_lsb(c, axis, code);
  return q <= f.lo || q >= f.hi;
}

// ---- Temperature channel --------------------------------------------------
// T (°C) = 35 + (code - TREF) / 45.2, TREF read from register 0x24.
constexpr double kTempLsbPerK = 45.2;
constexpr double kTempRefC = 35.0;
inline uint16_t temperature_code(double celsius, uint16_t tref) {
  const double v = std::nearbyint(tref + (celsius - kTempRefC) * kTempLsbPerK);
  return uint16_t(v < 0 ? 0 : v > 65535 ? 65535 : v);
}

}  // namespace eskin::mlx90393
