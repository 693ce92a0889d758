#include "sim/vboard/virtual_board.h"

#include <time.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>

namespace eskin::vboard {
namespace {

// Simulated time per batch of FPGA cycles, and between two visits of the
// USB bridge to the pty. 100 us is 1200 cycles at 12 MHz: the SystemC
// wait per batch costs < 1% of the batch; the host sees bytes in 100 us
// chunks of simulated time (a real FT2232H sends USB packets every 125 us
// at best).
const sc_core::sc_time kBatch(100, sc_core::SC_US);
const sc_core::sc_time kUsbPeriod(100, sc_core::SC_US);
constexpr int kBaudCheckEvery = 10;  // USB visits between termios reads (1 ms)
// A held board's first host bytes go out on RXD from this time, not at 0: on
// a board the host can write only after the FPGA has been configured and
// left its power-on reset (16 cycles, rtl/power_on_reset.v; 10 us is 120
// cycles at 12 MHz). A start bit inside the reset garbles the first command.
constexpr double kHostBytesFromNs = 10000;

double cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

}  // namespace

VirtualBoard::VirtualBoard(sc_core::sc_module_name name, FpgaModel& fpga, PtyPort& pty,
                           BoardConfig cfg)
    : sc_core::sc_module(name),
      fpga_(fpga),
      pty_(pty),
      cfg_(std::move(cfg)),
      adc_(cfg_.codes),
      line_(cfg_.line),
      cycle_ns_(1e9 / cfg_.clk_hz) {
  usb_.set_line(&line_);
  line_.set_bit_ns(LineDir::to_host, 1e9 / cfg_.baud);
  if (!cfg_.tap_to_host.empty()) line_.tap_to(cfg_.tap_to_host, 1e9 / cfg_.baud);
  pin_rx_.set_bit_ns(1e9 / cfg_.baud);
  for (const BoardFault& f : cfg_.faults) {
    stats_.faults.push_back({f});
    watch_pin_ |= f.kind == BoardFaultKind::reset_in_frame;
  }
  SC_THREAD(fpga_thread);
  SC_THREAD(usb_thread);
}

sc_core::sc_time VirtualBoard::time_of(uint64_t cycle) const {
  return sc_core::sc_time(double(cycle) * cycle_ns_, sc_core::SC_NS);
}

bool VirtualBoard::running() const {
  return cfg_.codes.empty() ? cycle_ < cfg_.cycles : adc_.samples_taken() < cfg_.samples;
}

// One FPGA clock per iteration, as tests/rtl/dtmf_top_board.h and
// hall_top_board.h do it: the ADC's SDATA, the I2C lines and DRDYs and the
// bridge's RXD as they are just before the rising edge at t, the edge, then
// the pins the FPGA drives after it.
void VirtualBoard::run_cycles(uint64_t until) {
  const bool adc = !cfg_.codes.empty();
  sim::HallSensorArray* hall = cfg_.hall;
  while (cycle_ < until && running()) {
    const double t = double(cycle_ + 1) * cycle_ns_;
    if (adc) in_.adc_sdata = adc_.sdata(t);
    if (hall) hall->before(t, in_.scl_i, in_.sda_i, in_.drdy);
    if (!stats_.faults.empty()) {
      time_faults(t);
      in_.reset = fault_reset_;
      in_.sda_i &= ~fault_sda_low_;
    }
    in_.uart_rxd = line_.wire(LineDir::to_fpga, t, usb_.rxd_level(t));
    out_ = fpga_.cycle(in_, uint64_t(std::llround(t * 1000.0)));
    ++cycle_;
    if (adc) adc_.drive(t, out_.adc_cs_n, out_.adc_sclk);
    if (hall) hall->after(t, out_.scl_oe, out_.sda_oe);
    usb_.sample_txd(t, line_.wire(LineDir::to_host, t, out_.uart_txd));
  }
}

// Each board fault's start and end on this clock, and the inputs the
// active ones hold. A fault that waits for its moment (a reset in a frame
// or a command, SDA held low mid-transfer) begins at the first clock at or
// after its time that finds it. The ADC's faults are in the codes already:
// they are timed by the conversions that read their first sample and the
// first one after.
void VirtualBoard::time_faults(double t) {
  if (watch_pin_) {
    if (const int b = pin_rx_.sample(t, out_.uart_txd); b >= 0) pin_in_frame_ = b != 0;
  }
  fault_reset_ = false;
  fault_sda_low_ = 0;
  for (BoardFaultRecord& r : stats_.faults) {
    const BoardFault& f = r.fault;
    if (f.on_adc()) {
      const size_t taken = adc_.samples_taken();
      if (!r.begun && taken > f.first_sample(cfg_.sample_hz)) {
        r.begun = true;
        r.begin_ns = t;
        r.end_ns = -1;  // not yet: the run may end first
      }
      if (r.begun && r.end_ns < 0 && taken > f.end_sample(cfg_.sample_hz)) r.end_ns = t;
      continue;
    }
    if (!r.begun) {
      if (t < f.at_ms * 1e6) continue;
      const bool now =
          f.kind == BoardFaultKind::reset_in_frame     ? pin_in_frame_
          : f.kind == BoardFaultKind::reset_in_command ? usb_.byte_to_fpga_in_flight() > 0
          : f.kind == BoardFaultKind::sda_low          ? ((out_.scl_oe >> f.index) & 1) != 0
                                                       : true;
      if (!now) continue;
      r.begun = true;
      r.begin_ns = t;
      r.end_ns = t + f.for_ms * 1e6;
    }
    if (t >= r.end_ns) continue;
    if (f.is_reset()) fault_reset_ = true;
    if (f.kind == BoardFaultKind::sda_low) fault_sda_low_ |= uint64_t(1) << f.index;
  }
}

void VirtualBoard::fpga_thread() {
  if (!started_) wait(reader_ready_);
  if (!cfg_.trace.empty()) fpga_.open_trace(cfg_.trace);  // needs elaboration done
  const auto wall0 = std::chrono::steady_clock::now();
  const double cpu0 = cpu_seconds();
  const uint64_t batch = uint64_t(std::llround(kBatch.to_seconds() * cfg_.clk_hz));
  while (running()) {
    run_cycles(cycle_ + batch);
    wait(time_of(cycle_) - sc_core::sc_time_stamp());
  }
  stats_.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  stats_.cpu_s = cpu_seconds() - cpu0;
  finished_ = true;
}

void VirtualBoard::follow_reader_baud() {
  const double b = pty_.reader_baud();
  if (b == stats_.reader_baud) return;
  stats_.reader_baud = b;
  usb_.set_baud(b);
  if (b > 0) line_.set_bit_ns(LineDir::to_fpga, 1e9 / b);
  if (b > 0 && b != cfg_.baud) {
    ++stats_.baud_mismatches;
    std::fprintf(stderr,
                 "virtual board: the reader set its serial port to %.0f baud, the FPGA's UART "
                 "runs at %.0f baud: bytes are garbled both ways until it matches\n",
                 b, cfg_.baud);
  }
}

// Bridge -> pty (blocking while a reader is connected and behind: the
// simulation waits for the host instead of dropping its data), pty ->
// bridge (non-blocking). With nobody reading (no reader has set a rate yet,
// or the reader closed the pty) the bytes are dropped, as on a board whose
// USB port nobody has open; a reader that opens the pty again resumes the
// delivery.
void VirtualBoard::move_bytes() {
  auto& out = usb_.to_host();
  auto& when = usb_.byte_times();
  const bool reading = stats_.reader_baud > 0 && !pty_.reader_closed();
  if (reading != reading_) {
    if (!reading) ++stats_.reader_closes;
    std::fprintf(stderr,
                 !reading ? "virtual board: the reader closed %s: bytes to the host are dropped "
                            "until a reader opens it again\n"
                 : stats_.reader_closes > 0 ? "virtual board: a reader opened %s again: bytes to "
                                              "the host resume\n"
                                            : "virtual board: a reader opened %s\n",
                 pty_.slave_path().c_str());
    reading_ = reading;
  }
  while (reading && sent_to_host_ < out.size()) {
    const size_t w = pty_.write(out.data() + sent_to_host_, out.size() - sent_to_host_);
    for (size_t i = sent_to_host_; i < sent_to_host_ + w; ++i)
      if (out[i] == 0) stats_.frame_end_ns.push_back(when[i]);
    sent_to_host_ += w;
    if (w > 0) continue;
    if (pty_.reader_closed()) break;  // closed while we waited: the rest is lost
    pty_.wait_writable(100);
  }
  stats_.bytes_dropped += out.size() - sent_to_host_;
  out.clear();
  when.clear();
  sent_to_host_ = 0;
  uint8_t buf[256];
  while (size_t n = pty_.read(buf, sizeof buf)) usb_.queue_to_fpga(buf, n);
  line_.flush_tap();
}

// Time still at 0: the host's first bytes are queued for the FPGA's RXD as
// they come; they go out from kHostBytesFromNs on, before the first frame.
// False (and the error set) if the reader closes or the timeout passes
// first.
bool VirtualBoard::wait_for_host_bytes() {
  const auto t0 = std::chrono::steady_clock::now();
  uint64_t got = 0;
  uint8_t buf[256];
  while (got < cfg_.hold_for_host_bytes) {
    while (size_t n = pty_.read(buf, sizeof buf)) {
      usb_.queue_to_fpga(buf, n);
      got += n;
    }
    if (got >= cfg_.hold_for_host_bytes) {
      usb_.send_from(kHostBytesFromNs);
      break;
    }
    if (pty_.reader_closed() ||
        std::chrono::steady_clock::now() - t0 >
            std::chrono::duration<double>(cfg_.reader_timeout_s)) {
      stats_.error = "the host sent " + std::to_string(got) + " of the " +
                     std::to_string(cfg_.hold_for_host_bytes) +
                     " bytes the board was told to wait for (--hold-for-host-bytes) before " +
                     (pty_.reader_closed() ? "it closed " + pty_.slave_path()
                                           : "the " + std::to_string(int(cfg_.reader_timeout_s)) +
                                                 " s timeout");
      return false;
    }
    usleep(1000);
  }
  return true;
}

void VirtualBoard::usb_thread() {
  if (cfg_.wait_for_reader) {
    const auto t0 = std::chrono::steady_clock::now();
    while (pty_.reader_baud() == 0) {
      if (std::chrono::steady_clock::now() - t0 >
          std::chrono::duration<double>(cfg_.reader_timeout_s)) {
        stats_.error = "no program opened " + pty_.slave_path() + " and set a baud rate within " +
                       std::to_string(int(cfg_.reader_timeout_s)) + " s";
        sc_core::sc_stop();
        return;
      }
      usleep(2000);
    }
  }
  follow_reader_baud();
  if (cfg_.hold_for_host_bytes > 0 && !wait_for_host_bytes()) {
    sc_core::sc_stop();
    return;
  }
  started_ = true;
  reader_ready_.notify(sc_core::SC_ZERO_TIME);
  reading_ = stats_.reader_baud > 0;
  for (int visit = 1; !finished_; ++visit) {
    wait(kUsbPeriod);
    move_bytes();
    if (visit % kBaudCheckEvery == 0) follow_reader_baud();
  }
  move_bytes();
  stats_.cycles = cycle_;
  stats_.sim_s = double(cycle_) / cfg_.clk_hz;
  stats_.samples = adc_.samples_taken();
  stats_.adc_violations = adc_.violation_count();
  if (!adc_.violations().empty()) stats_.first_adc_violation = adc_.violations()[0];
  if (cfg_.hall) {
    const std::vector<std::string> v = cfg_.hall->violations();
    stats_.i2c_violations = cfg_.hall->violation_count();
    if (!v.empty()) stats_.first_i2c_violation = v[0];
  }
  stats_.bytes_to_host = usb_.bytes_to_host();
  stats_.bytes_to_fpga = usb_.bytes_to_fpga();
  stats_.usb_framing_errors = usb_.framing_errors();
  stats_.line = line_.counts();
  sc_core::sc_stop();
}

}  // namespace eskin::vboard
