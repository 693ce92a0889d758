// The SystemC virtual board: the Verilated FPGA top clocked at its real
// frequency; the AD7476A pin model on its SPI pins fed with the scene's ADC
// codes (a DTMF skin), or the Hall skin's MLX90393s (and TCA9548As) on its
// I2C buses, their field from the scene's world (sim/hall_sensor_array.h);
// and the USB-serial bridge on its UART pins, exposed to the host as a
// pseudo-terminal. Time is real: the FPGA clock, the ADC's SCLK edges, the
// I2C lines and the UART bits are placed in ns and checked in ns.
//
// Two SystemC threads share the time axis:
//   fpga   clocks the model for one batch (kBatch of simulated time) in a
//          plain loop, with the ADC and UART pins exchanged every cycle at
//          their real times, then waits for the batch's time to pass;
//   usb    every kUsbPeriod moves bytes between the bridge and the pty,
//          follows the reader's baud rate and reports a mismatch.
// A reader may close the pty and open it again, as a program does with a
// USB serial adapter: while nobody reads, the bytes for the host are
// dropped (a board sends them all the same) and time goes on; a reader
// that opens the port again gets the bytes from then on.
// Cycles are never SystemC events: one event per clock edge would cost
// more than the model (docs/vboard.md).
#pragma once

#include <systemc>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "sim/ad7476_model.h"
#include "sim/hall_sensor_array.h"
#include "sim/vboard/board_faults.h"
#include "sim/vboard/fpga_model.h"
#include "sim/vboard/line_faults.h"
#include "sim/vboard/pty_port.h"
#include "sim/vboard/usb_serial.h"

namespace eskin::vboard {

struct BoardConfig {
  double clk_hz = 12e6;          // the FPGA top's CLK_HZ
  double baud = 3e6;             // the FPGA top's BAUD
  std::vector<uint16_t> codes;   // 12-bit ADC codes, one per conversion
  uint64_t samples = 0;          // stop once the ADC has taken this many
  sim::HallSensorArray* hall = nullptr;  // the Hall skin's devices (none: no I2C side)
  uint64_t cycles = 0;           // with no ADC: stop after this many FPGA cycles
  bool wait_for_reader = true;   // hold time at 0 until a reader sets a baud rate
  std::string trace;             // FST waveform file ("": none), from the first cycle
  double reader_timeout_s = 60;  // ... for at most this long (wall clock)
  // ... and then, until the host has sent this many bytes (its start-up
  // commands, which then act from the first cycle however busy the machine
  // is; 0: start at once)
  uint64_t hold_for_host_bytes = 0;
  // The line between the UART pins and the bridge (line_faults.h), and a
  // file for the FPGA's bytes as sent, before the line's faults ("": none).
  LineFaultOptions line;
  std::string tap_to_host;
  // Faults of the board (board_faults.h): the ADC's are already in `codes`
  // (load_skin_samples); the board injects the rest and times them all.
  std::vector<BoardFault> faults;
  double sample_hz = 0;  // the ADC's rate: an ADC fault's samples from its ms
};

struct BoardStats {
  uint64_t cycles = 0;
  double sim_s = 0, wall_s = 0, cpu_s = 0;
  uint64_t samples = 0;                 // ADC conversions started
  uint64_t adc_violations = 0;
  std::string first_adc_violation;
  uint64_t i2c_violations = 0;          // bus timing limits broken (sim/i2c_bus.h)
  std::string first_i2c_violation;
  uint64_t bytes_to_host = 0, bytes_to_fpga = 0;
  uint64_t usb_framing_errors = 0;      // stop bits the bridge read as 0
  double reader_baud = 0;               // last rate the reader set
  uint64_t baud_mismatches = 0;         // times the reader's rate differed from the FPGA's
  uint64_t reader_closes = 0;           // times the reader closed the port while the board ran
  uint64_t bytes_dropped = 0;           // bytes for the host while nobody was reading
  std::vector<double> frame_end_ns;     // time each 0x00 frame delimiter reached the host
  std::string error;                    // why the run stopped early (empty: it did not)
  LineCounts line;                      // the faults the line injected
  std::vector<BoardFaultRecord> faults; // the board's faults, when each began and ended
};

SC_MODULE(VirtualBoard) {
 public:
  SC_HAS_PROCESS(VirtualBoard);
  VirtualBoard(sc_core::sc_module_name name, FpgaModel& fpga, PtyPort& pty, BoardConfig cfg);
  const BoardStats& stats() const { return stats_; }
  bool finished() const { return finished_; }

 private:
  void fpga_thread();
  void usb_thread();
  void run_cycles(uint64_t until);
  void time_faults(double t);
  bool running() const;  // the scene (plus its tail) is not over yet
  void move_bytes();
  void follow_reader_baud();
  bool wait_for_host_bytes();
  sc_core::sc_time time_of(uint64_t cycle) const;

  FpgaModel& fpga_;
  PtyPort& pty_;
  BoardConfig cfg_;
  sim::Ad7476Model adc_;
  LineFaults line_;
  UsbSerial usb_;
  FpgaInputs in_;
  FpgaOutputs out_;
  uint64_t cycle_ = 0;
  double cycle_ns_;
  sc_core::sc_event reader_ready_;
  bool started_ = false, finished_ = false;
  size_t sent_to_host_ = 0;  // bytes of usb_.to_host() already in the pty
  bool reading_ = false;     // a reader had the pty open at the last visit
  BoardStats stats_;
  // Board faults: the inputs they hold (reset, SDA pulled low per bus) and
  // the FPGA's UART pin read back, for a reset in a frame.
  bool fault_reset_ = false;
  uint64_t fault_sda_low_ = 0;
  UartRxModel pin_rx_;
  bool pin_in_frame_ = false, watch_pin_ = false;
};

}  // namespace eskin::vboard
