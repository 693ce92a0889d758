#include "host/fpga/board.h"

#include <fmt/core.h>

#include <algorithm>
#include <cstdlib>
#include <stdexcept>

namespace eskin::fpga {

namespace {

const std::vector<Board>& boards() {
  static const std::vector<Board> b = {
      {"icebreaker", Family::Ice40, "up5k", "sg48", "board_icebreaker",
       "constraints/icebreaker.pcf", 12000000, hls::kDtmfTopClkHz, "ICESTORM_LC",
       "board_icebreaker_hall", true, false, 1, false, 0, true},
      {"ulx3s", Family::Ecp5, "85k", "CABGA381", "board_ulx3s", "constraints/ulx3s.lpf",
       25000000, 30000000, "TRELLIS_COMB", "board_ulx3s_hall", false, true, 32, true, 5, false, true},
  };
  return b;
}

// Fastest of 3, 2, 1 Mbaud with an exact bit period at clk_hz (0: none).
long exact_baud(long clk_hz) {
  for (long baud : {3000000L, 2000000L, 1000000L})
    if (clk_hz % baud == 0) return baud;
  return 0;
}

std::string mhz(long hz) { return fmt::format("{:g} MHz", hz / 1e6); }

// iCE40 SB_PLL40_PAD, SIMPLE feedback (iCE40 sysCLOCK PLL guide, as
// icestorm's icepll computes it): PFD = osc / (DIVR + 1) in 10..133 MHz,
// VCO = PFD x (DIVF + 1) in 533..1066 MHz, CLK = VCO / 2^DIVQ in 16..275 MHz,
// DIVR 0..15, DIVF 0..127, DIVQ 1..6; FILTER_RANGE from the PFD. Every
// exact clock up to 100 MHz with an exact UART (above it the UP5K's logic
// does not go), the first divider set icepll would list for it.
std::vector<Clocking> ice40_clocks(long osc_hz) {
  std::vector<Clocking> out;
  for (int divr = 0; divr <= 15; ++divr) {
    if (osc_hz % (divr + 1) != 0) continue;
    const long pfd = osc_hz / (divr + 1);
    if (pfd < 10000000L || pfd > 133000000L) continue;
    const int filter = pfd < 17000000L ? 1 : pfd < 26000000L ? 2 : pfd < 44000000L ? 3
                       : pfd < 66000000L ? 4 : pfd < 101000000L ? 5 : 6;
    for (int divf = 0; divf <= 127; ++divf) {
      const long vco = pfd * (divf + 1);
      if (vco < 533000000L || vco > 1066000000L) continue;
      for (int divq = 1; divq <= 6; ++divq) {
        if (vco % (1L << divq) != 0) continue;
        const long hz = vco >> divq;
        if (hz < 16000000L || hz > 100000000L || exact_baud(hz) == 0) continue;
        bool seen = false;
        for (const auto& c : out) seen = seen || c.clk_hz == hz;
        if (seen) continue;
        out.push_back({hz, exact_baud(hz), {{"PLL_DIVR", std::to_string(divr)},
                                            {"PLL_DIVF", std::to_string(divf)},
                                            {"PLL_DIVQ", std::to_string(divq)},
                                            {"PLL_FILTER_RANGE", std::to_string(filter)}}});
      }
    }
  }
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.clk_hz < b.clk_hz; });
  return out;
}

// ECP5 EHXPLLL from the 25 MHz oscillator: CLK = 25 MHz * FB / REF with the
// phase detector at 25 MHz / REF >= 3.125 MHz (REF <= 8), VCO = CLK * OP in
// 400..800 MHz. Every exact clock from 25 to 200 MHz (whole kHz).
std::vector<Clocking> ecp5_clocks(long osc_hz) {
  std::vector<Clocking> out;
  for (long khz = 25000; khz <= 200000; khz += 1) {
    const long hz = khz * 1000;
    const long baud = exact_baud(hz);
    if (baud == 0) continue;
    // The smallest REF that works, and the VCO nearest the middle of its
    // range (600 MHz), as Lattice's and prjtrellis' PLL calculators pick.
    for (int ref = 1; ref <= 8; ++ref) {
      if ((hz * ref) % osc_hz != 0) continue;
      const long fb = hz * ref / osc_hz;
      if (fb < 1 || fb > 128) continue;
      int best = 0;
      for (int op = 1; op <= 128; ++op) {
        const long vco = hz * op;
        if (vco >= 400000000L && vco <= 800000000L &&
            (best == 0 || std::labs(vco - 600000000L) < std::labs(hz * best - 600000000L)))
          best = op;
      }
      if (best == 0) continue;
      out.push_back({hz, baud, {{"CLKI_DIV", std::to_string(ref)},
                                {"CLKFB_DIV", std::to_string(fb)},
                                {"CLKOP_DIV", std::to_string(best)}}});
      break;
    }
  }
  return out;
}

// The first (slowest) of ascending `clocks` at or above want.
std::optional<Clocking> first_clock_from(const std::vector<Clocking>& clocks, long want) {
  for (const auto& c : clocks)
    if (c.clk_hz >= want) return c;
  return std::nullopt;
}

}  // namespace

std::vector<std::string> board_names() {
  std::vector<std::string> n;
  for (const auto& b : boards()) n.push_back(b.name);
  return n;
}

Board find_board(const std::string& name, const std::string& device_override) {
  for (Board b : boards()) {
    if (b.name != name) continue;
    if (device_override.empty() || device_override == b.device) return b;
    if (b.family == Family::Ecp5 &&
        (device_override == "25k" || device_override == "45k" || device_override == "85k")) {
      b.device = device_override;
      return b;
    }
    throw std::invalid_argument(fmt::format(
        "--device: board {} takes {}, got '{}'", name,
        b.family == Family::Ecp5 ? "25k, 45k or 85k (ECP5 in CABGA381)" : "only up5k",
        device_override));
  }
  std::string names;
  for (const auto& n : board_names()) names += (names.empty() ? "" : ", ") + n;
  throw std::invalid_argument(fmt::format("--board: expected one of {}, got '{}'", names, name));
}

std::vector<Clocking> board_clocks(const Board& b) {
  return b.family == Family::Ecp5 ? ecp5_clocks(b.osc_hz) : ice40_clocks(b.osc_hz);
}

Clocking choose_clock(const Board& b, long min_hz, long clk_hz) {
  const auto clocks = board_clocks(b);
  auto list = [&] {
    std::string s;
    for (size_t i = 0; i < clocks.size() && i < 12; ++i)
      s += (i ? ", " : "") + mhz(clocks[i].clk_hz);
    return s + (clocks.size() > 12 ? ", ..." : "");
  };
  if (clk_hz > 0) {
    for (const auto& c : clocks)
      if (c.clk_hz == clk_hz) return c;
    throw std::invalid_argument(fmt::format(
        "--clk-mhz: board {} cannot make {} exactly with a 3, 2 or 1 Mbaud UART; it makes {}",
        b.name, mhz(clk_hz), list()));
  }
  const long want = std::max(min_hz, b.default_clk_hz);
  if (const auto c = first_clock_from(clocks, want)) return *c;
  throw std::invalid_argument(fmt::format("board {}: the core needs {} or more; the board makes {}",
                                          b.name, mhz(want), list()));
}

std::optional<Clocking> with_adc_clock(const Board& b, const Clocking& core, double sample_hz) {
  if (b.family != Family::Ecp5) return std::nullopt;
  // ecp5_clocks' REF and FB for the core clock; then every OP with the VCO
  // in range and every OS that divides the VCO into whole Hz.
  std::optional<Clocking> best;
  long best_vco = 0;
  const long hz = core.clk_hz;
  for (int ref = 1; ref <= 8 && !best; ++ref) {
    if ((hz * ref) % b.osc_hz != 0) continue;
    const long fb = hz * ref / b.osc_hz;
    if (fb < 1 || fb > 128) continue;
    for (int op = 1; op <= 128; ++op) {
      const long vco = hz * op;
      if (vco < 400000000L || vco > 800000000L) continue;
      for (int os = 1; os <= 128; ++os) {
        if (vco % os != 0) continue;
        const long adc = vco / os;
        if (adc > 40000000L || !hls::dtmf_top_adc_problem(sample_hz, adc).empty()) continue;
        const bool better = !best || adc > best->adc_clk_hz ||
                            (adc == best->adc_clk_hz &&
                             std::labs(vco - 600000000L) < std::labs(best_vco - 600000000L));
        if (!better) continue;
        best = Clocking{hz, core.baud,
                        {{"CLKI_DIV", std::to_string(ref)},
                         {"CLKFB_DIV", std::to_string(fb)},
                         {"CLKOP_DIV", std::to_string(op)},
                         {"CLKOS_DIV", std::to_string(os)}},
                        adc};
        best_vco = vco;
      }
    }
  }
  return best;
}

std::optional<Clocking> slowest_clock_from(const Board& b, long min_hz) {
  return first_clock_from(board_clocks(b), std::max(min_hz, b.default_clk_hz));
}

Clocking choose_hall_clock(const Board& b, long clk_hz) {
  if (clk_hz > 0 && clk_hz % 1000000 != 0)
    throw std::invalid_argument(fmt::format(
        "--clk-mhz: hall_top counts microseconds and needs a whole number of MHz, got {}",
        mhz(clk_hz)));
  const bool ice = b.family == Family::Ice40;
  if (b.hall_osc_clock && exact_baud(b.osc_hz) > 0 && (clk_hz == 0 || clk_hz == b.osc_hz))
    return {b.osc_hz, exact_baud(b.osc_hz), {{"PLL", "0"}}};
  Clocking c = choose_clock(b, 0, clk_hz);  // every board clock is whole MHz (exact UART)
  if (ice) c.wrapper_params.insert(c.wrapper_params.begin(), {"PLL", "1"});
  return c;
}

}  // namespace eskin::fpga
