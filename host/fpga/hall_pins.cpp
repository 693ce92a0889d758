#include "host/fpga/hall_pins.h"

#include <fmt/core.h>

namespace eskin::fpga {

namespace {

// iCEBreaker v1.0e (icebreaker-fpga/icebreaker-verilog-examples,
// icebreaker.pcf): PMOD1A holds the Pmod AD1 of DTMF and mixed builds, so
// the Hall pins are PMOD1B's and PMOD2's eight signal pins each (Pmod pins
// 1-4 and 7-10; 5, 11 GND, 6, 12 3.3 V). PMOD2 carries the snap-off
// LED/button board until it is broken off.
std::vector<BoardPin> icebreaker_pool() {
  std::vector<BoardPin> p;
  const std::pair<const char*, std::vector<std::pair<int, const char*>>> pmods[] = {
      {"PMOD1B", {{1, "43"}, {2, "38"}, {3, "34"}, {4, "31"}, {7, "42"}, {8, "36"}, {9, "32"},
                  {10, "28"}}},
      {"PMOD2", {{1, "27"}, {2, "25"}, {3, "21"}, {4, "19"}, {7, "26"}, {8, "23"}, {9, "20"},
                 {10, "18"}}}};
  for (const auto& [pmod, pins] : pmods)
    for (const auto& [n, site] : pins) p.push_back({site, fmt::format("{} pin {}", pmod, n)});
  return p;
}

// ULX3S v2.x/v3.0.x (emard/ulx3s, doc/constraints/ulx3s_v20.lpf): the GPIO
// headers' single-ended pairs gp[n] / gn[n] (J1 pin 2n+5 +/-, J2 pin
// 2(n-14)+5 +/-, pins 19 and 21 being power). Left out: gp/gn[0..3] (the
// Pmod AD1 of DTMF and mixed builds sits on gp[0..3] with its row beside),
// gp/gn[11..13] (wired to the ESP32's GPIOs) and gp/gn[14..17] (wired to
// the on-board ADC's inputs).
std::vector<BoardPin> ulx3s_pool() {
  struct Pair { int n; const char *p, *m; };
  const Pair j1[] = {{4, "A7", "A8"}, {5, "C8", "B8"}, {6, "C6", "C7"}, {7, "A6", "B6"},
                     {8, "A4", "A5"}, {9, "A2", "B1"}, {10, "C4", "B4"}};
  const Pair j2[] = {{18, "H18", "H17"}, {19, "F17", "G18"}, {20, "D18", "E17"},
                     {21, "C18", "D17"}, {22, "B15", "C15"}, {23, "B17", "C17"},
                     {24, "C16", "D16"}, {25, "D14", "E14"}, {26, "B13", "C13"},
                     {27, "D13", "E13"}};
  // Header pin of pair n: 5, 7, ... 17 for the first seven of a header, then
  // 23, 25, ... (the lpf's J1_23+ is gp[7], J2_23+ gp[21]).
  auto header_pin = [](int k) { return k < 7 ? 5 + 2 * k : 9 + 2 * k; };
  std::vector<BoardPin> p;
  auto add = [&](const char* hdr, const Pair* pairs, int count, int first) {
    for (int i = 0; i < count; ++i) {
      const int pin = header_pin(pairs[i].n - first);
      p.push_back({pairs[i].p, fmt::format("{} pin {}+ (gp[{}])", hdr, pin, pairs[i].n)});
      p.push_back({pairs[i].m, fmt::format("{} pin {}- (gn[{}])", hdr, pin, pairs[i].n)});
    }
  };
  add("J1", j1, 7, 0);
  add("J2", j2, 10, 14);
  return p;
}

}  // namespace

const std::vector<BoardPin>& hall_pin_pool(const Board& b) {
  static const std::vector<BoardPin> ice = icebreaker_pool(), ulx = ulx3s_pool(), none;
  return b.name == "icebreaker" ? ice : b.name == "ulx3s" ? ulx : none;
}

std::string hall_pin_pool_where(const Board& b) {
  return b.name == "icebreaker" ? "PMOD1B and PMOD2"
         : b.name == "ulx3s"    ? "GPIO headers J1 and J2"
                                : "none";
}

HallPins assign_hall_pins(const Board& b, int nb, int nsb) {
  HallPins h;
  const auto& pool = hall_pin_pool(b);
  h.needed = 2 * nb + nb * nsb;
  if (h.needed > int(pool.size())) {
    h.failure = fmt::format(
        "does not fit: the Hall sensors need {} pins ({} I2C bus{} x 2 (SCL, SDA) + {} DRDY "
        "line{}), board {} has {} free ({})",
        h.needed, nb, nb == 1 ? "" : "es", nb * nsb, nb * nsb == 1 ? "" : "s", b.name,
        pool.size(), hall_pin_pool_where(b));
    return h;
  }
  // nextpnr names the pin of a one-bit port by the port alone ("drdy", not
  // "drdy[0]"), as Yosys writes it.
  auto bit = [](const char* port, int i, int width) {
    return width == 1 ? std::string(port) : fmt::format("{}[{}]", port, i);
  };
  size_t next = 0;
  for (int bus = 0; bus < nb; ++bus)
    for (const char* line : {"i2c_scl", "i2c_sda"})
      h.pins.push_back({bit(line, bus, nb), pool[next++], true});
  for (int s = 0; s < nb * nsb; ++s) h.pins.push_back({bit("drdy", s, nb * nsb), pool[next++], false});
  return h;
}

std::string hall_constraints(const Board& b, const std::string& base, const HallPins& p) {
  const bool ice = b.family == Family::Ice40;
  std::string t = base;
  t += fmt::format(
      "\n# Hall sensors, written by `eskin bitstream` (host/fpga/hall_pins.cpp) for {}'s\n"
      "# {}: each I2C bus's SCL and SDA (open drain: driven low or released) and each\n"
      "# sensor's DRDY (MLX90393 INT) line. The bus lines have the FPGA's weak pull-up on,\n"
      "# so that a bus with nothing on it idles high; it is far too weak for I2C: a real\n"
      "# bus needs its own pull-ups to 3.3 V (2.2 kohm for 400 kHz at 100 pF,\n"
      "# docs/hall_fpga.md). {}\n",
      b.hall_wrapper, hall_pin_pool_where(b),
      ice ? "DRDY lines are plain inputs (the iCE40 has no pull-downs)."
          : "DRDY lines are pulled down: a missing sensor's reads idle.");
  for (const auto& a : p.pins) {
    if (ice) {
      t += fmt::format("set_io -nowarn {}{} {}  # {}\n", a.i2c ? "-pullup yes " : "", a.signal,
                       a.pin.site, a.pin.connector);
    } else {
      t += fmt::format("LOCATE COMP \"{}\" SITE \"{}\";  # {}\n", a.signal, a.pin.site,
                       a.pin.connector);
      t += fmt::format("IOBUF PORT \"{}\" PULLMODE={} IO_TYPE=LVCMOS33{};\n", a.signal,
                       a.i2c ? "UP" : "DOWN", a.i2c ? " DRIVE=4" : "");
    }
  }
  return t;
}

}  // namespace eskin::fpga
