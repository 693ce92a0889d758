// Faults of the board itself on the virtual board (docs/vboard.md, "Board
// faults"), beside the serial line's (line_faults.h). One `--fault` value
// each, KIND@AT_MS[:FOR_MS] in simulated ms:
//   reset                 the reset button held FOR_MS (default 0.01) from AT_MS
//   reset-in-frame        ... from the first clock at or after AT_MS at which
//                         the FPGA is inside a frame to the host (a byte of
//                         it out, its 0x00 not yet)
//   reset-in-command      ... from the first clock at or after AT_MS at which
//                         the bridge is sending the FPGA a byte of a command
//                         other than its closing 0x00
//   adc-stuck-low         every ADC conversion of samples AT .. AT+FOR reads 0
//   adc-stuck-high        ... reads the top code (4095)
//   carrier-off=K         carrier K (the scene's rows, then its columns, from
//                         0) absent from the skin's signal for those samples
//   sda-low=B             a sensor holds SDA of I2C bus B low for FOR_MS, from
//                         the first clock at or after AT_MS at which the FPGA
//                         holds that bus's SCL low (mid-transfer)
// The ADC faults act on the scene's samples (sample n is at n / rate_hz of
// scene time, the ADC's n-th conversion); the others on the board's clock.
// The two differ by the FPGA's start-up, well under a millisecond.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace eskin::vboard {

enum class BoardFaultKind {
  reset,
  reset_in_frame,
  reset_in_command,
  adc_stuck_low,
  adc_stuck_high,
  carrier_off,
  sda_low
};

struct BoardFault {
  BoardFaultKind kind = BoardFaultKind::reset;
  double at_ms = 0, for_ms = 0;
  int index = -1;  // carrier-off: the carrier; sda-low: the bus
  bool is_reset() const { return kind <= BoardFaultKind::reset_in_command; }
  bool on_adc() const {
    return kind >= BoardFaultKind::adc_stuck_low && kind <= BoardFaultKind::carrier_off;
  }
  // An ADC fault's samples [first, end) at the ADC's rate fs.
  size_t first_sample(double fs) const { return size_t(std::llround(at_ms * 1e-3 * fs)); }
  size_t end_sample(double fs) const { return size_t(std::llround((at_ms + for_ms) * 1e-3 * fs)); }
};

// Throws std::invalid_argument naming --fault, the value and what it
// expects.
std::vector<BoardFault> parse_board_faults(const std::vector<std::string>& values);
// The same faults back as eskin-vboard arguments (--fault VALUE ...).
std::vector<std::string> board_fault_args(const std::vector<BoardFault>& faults);
std::string board_fault_text(const BoardFault& f);  // its --fault value
// Throws std::invalid_argument, naming --fault, for a fault this board
// cannot have: `carriers`, the skin's rows + columns (0: no skin, no
// ADC); `buses`, the I2C buses with sensors on them (0: no Hall sensors).
void check_board_faults(const std::vector<BoardFault>& faults, int carriers, int buses);

// What happened to each fault in a run: when it began and ended on the
// board's clock (ns; a fault waiting for its moment that never came has
// begun = false; an ADC fault whose last sample the run never reached has
// end_ns -1), for the done line's "board_faults".
struct BoardFaultRecord {
  BoardFault fault;
  bool begun = false;
  double begin_ns = 0, end_ns = 0;
};
nlohmann::json to_json(const std::vector<BoardFaultRecord>& r);

}  // namespace eskin::vboard
