#include "sim/vboard/vboard_cli.h"

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <systemc>

namespace eskin::vboard {

int vboard_cli_main(int argc, char** argv, const std::string& title, double default_tail_s,
                    const std::function<int(const VboardArgs&, FILE* json)>& run,
                    bool build_options) {
  // stdout is for the JSON lines only: keep it on its own stream and send
  // everything else written to fd 1 (SystemC's banner) to stderr.
  FILE* json = fdopen(dup(1), "w");
  dup2(2, 1);
  sc_core::sc_report_handler::set_actions("/OSCI/SystemC", sc_core::SC_INFO, sc_core::SC_DO_NOTHING);
  VboardArgs a;
  a.tail_s = default_tail_s;
  CLI::App app{title};
  app.add_option("scene", a.scene, "scene file (YAML, docs/scenes.md)")->required()->check(CLI::ExistingFile);
  app.add_option("--pty-link", a.pty_link, "also make this path a symlink to the pty");
  app.add_option("--trace", a.trace, "write an FST waveform of the FPGA (GTKWave; ~7x slower)");
  CLI::Option* no_wait = app.add_flag("--no-wait", a.no_wait,
               "start at once instead of waiting for a reader to set a baud rate");
  app.add_option("--hold-for-host-bytes", a.hold_for_host_bytes,
                 "once a reader is there, hold time at 0 until it has sent this many bytes (its "
                 "start-up commands, which then act from the first frame)")
      ->excludes(no_wait);
  app.add_option("--reader-timeout", a.reader_timeout_s, "seconds to wait for a reader")
      ->capture_default_str();
  app.add_option("--tail", a.tail_s, "seconds of idle input after the scene (last frames out)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 10.0));
  app.add_option("--ber", a.line_args.ber,
                 "line faults: probability that a wire bit (start, data, stop) is flipped");
  app.add_option("--drop-rate", a.line_args.drop_rate,
                 "line faults: probability that a character is lost");
  app.add_option("--insert-rate", a.line_args.insert_rate,
                 "line faults: probability that a random character comes before one");
  app.add_option("--fault-direction", a.line_args.direction,
                 "line faults: which way --ber/--drop-rate/--insert-rate act: both (default), "
                 "to-host, to-fpga");
  app.add_option("--pull-cable", a.line_args.pulls,
                 "line faults: AT_MS:FOR_MS, the cable out for FOR_MS from AT_MS of simulated "
                 "time (repeatable)");
  app.add_option("--fault-seed", a.line_args.seed, "line faults: the seed of every fault (default 1)");
  app.add_option("--fault", a.fault_args,
                 "board fault KIND@AT_MS[:FOR_MS]: reset, reset-in-frame, reset-in-command, "
                 "adc-stuck-low, adc-stuck-high, carrier-off=K, sda-low=B (repeatable; "
                 "docs/vboard.md, \"Board faults\")");
  app.add_option("--tap-to-host", a.tap_to_host,
                 "write the FPGA's bytes on uart_txd, before the line's faults, to this file");
  std::string shifter = "bit-serial", neurons = "microcode";
  if (build_options) {
    app.add_option("--clk-hz", a.build.clk_hz, "the FPGA build's clock, Hz")->required()
        ->check(CLI::PositiveNumber);
    app.add_option("--baud", a.build.baud, "the FPGA build's UART rate")->required()
        ->check(CLI::PositiveNumber);
    app.add_option("--engine-shifter", shifter, "the frame engine's shifter: bit-serial or barrel")
        ->check(CLI::IsMember({"bit-serial", "barrel"}))->capture_default_str();
    app.add_option("--neurons", neurons, "the neurons: microcode or unit")
        ->check(CLI::IsMember({"microcode", "unit"}))->capture_default_str();
  }
  try {
    app.parse(argc, argv);
    a.build.fast_shift = shifter == "barrel";
    a.build.neuron_unit = neurons == "unit";
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
    a.line = parse_line_faults(a.line_args);
    a.faults = parse_board_faults(a.fault_args);
    return run(a, json);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "eskin-vboard: error: %s\n", e.what());
    return 2;
  }
}

void apply_start_options(const VboardArgs& a, BoardConfig& cfg, int carriers, int buses) {
  check_board_faults(a.faults, carriers, buses);
  cfg.faults = a.faults;
  cfg.wait_for_reader = !a.no_wait;
  cfg.reader_timeout_s = a.reader_timeout_s;
  cfg.hold_for_host_bytes = a.hold_for_host_bytes;
  cfg.trace = a.trace;
  cfg.line = a.line;
  cfg.tap_to_host = a.tap_to_host;
}

void print_ready(FILE* json, const PtyPort& pty, const std::string& key, double clk_hz, double baud,
                 const nlohmann::json& extra) {
  nlohmann::json j = {{"event", "ready"}, {"pty", pty.slave_path()}, {"params", key},
                      {"clk_hz", clk_hz}, {"baud", baud}};
  j.update(extra);
  std::fprintf(json, "%s\n", j.dump().c_str());
  std::fflush(json);
}

void print_done(FILE* json, const BoardStats& s, const nlohmann::json& extra) {
  if (!s.error.empty()) throw std::runtime_error(s.error);
  nlohmann::json j = {{"event", "done"},
                      {"cycles", s.cycles},
                      {"sim_s", s.sim_s},
                      {"wall_s", s.wall_s},
                      {"cpu_s", s.cpu_s},
                      {"samples", s.samples},
                      {"adc_violations", s.adc_violations},
                      {"adc_first_violation", s.first_adc_violation},
                      {"i2c_violations", s.i2c_violations},
                      {"i2c_first_violation", s.first_i2c_violation},
                      {"bytes_to_host", s.bytes_to_host},
                      {"bytes_to_fpga", s.bytes_to_fpga},
                      {"usb_framing_errors", s.usb_framing_errors},
                      {"reader_baud", s.reader_baud},
                      {"baud_mismatches", s.baud_mismatches},
                      {"reader_closes", s.reader_closes},
                      {"bytes_dropped", s.bytes_dropped},
                      {"frame_end_ns", s.frame_end_ns},
                      {"line_faults", to_json(s.line)},
                      {"board_faults", to_json(s.faults)}};
  j.update(extra);
  std::fprintf(json, "%s\n", j.dump().c_str());
  std::fflush(json);
}

void hang_up_when_read(PtyPort& pty, const BoardStats& s, double timeout_s) {
  using clock = std::chrono::steady_clock;
  auto progress = clock::now();
  long last = -2;
  int empty = 0;
  while (s.reader_baud > 0 && !pty.reader_closed()) {
    const long n = pty.unread();
    if (n == 0 && ++empty >= 2) break;
    if (n != 0) empty = 0;
    if (n != last) progress = clock::now();
    last = n;
    // Unknown (-1): a reader that reads at all drains the pty's few KB
    // within milliseconds; a second is plenty.
    const double limit = n < 0 ? std::min(timeout_s, 1.0) : timeout_s;
    if (clock::now() - progress > std::chrono::duration<double>(limit)) {
      std::fprintf(stderr,
                   n > 0 ? "virtual board: the reader left %ld bytes unread for %.0f s (--reader-timeout): "
                           "hanging up\n"
                         : "virtual board: cannot tell what the reader has read (%ld): hanging up "
                           "after %.0f s\n",
                   n, limit);
      break;
    }
    usleep(10000);
  }
  pty.hang_up();
}

void require_build(const std::string& scene_file, const std::string& kind,
                   const std::string& needed, const std::string& board_key) {
  if (needed != board_key)
    throw std::runtime_error(scene_file + ": this scene needs the " + kind + " build '" + needed +
                             "', this virtual board is '" + board_key +
                             "' (run the scene with `eskin simulate`, which builds the board it "
                             "needs)");
}

size_t load_skin_samples(BoardConfig& cfg, const sim::Scene& scene, int adc_shift, double tail_s) {
  SkinSamples s = skin_samples(scene, adc_shift, tail_s, cfg.faults);
  cfg.sample_hz = s.sample_hz;
  cfg.codes = std::move(s.codes);
  cfg.samples = s.samples;
  return s.scene_samples;
}

nlohmann::json drdy_times_ns(const sim::HallSensorArray& sensors) {
  nlohmann::json drdy = nlohmann::json::array();
  for (size_t s = 0; s < sensors.size(); ++s) {
    std::vector<double> t;
    for (const auto& m : sensors.device(s).delivered()) t.push_back(m.t_done_ns);
    drdy.push_back(t);
  }
  return drdy;
}

nlohmann::json dtmf_board_config(const VboardArgs& a, const sim::Scene& scene, double clk_hz,
                                 double baud, int adc_shift, BoardConfig& cfg) {
  cfg.clk_hz = clk_hz;
  cfg.baud = baud;
  apply_start_options(a, cfg, scene.skin.rows + scene.skin.cols, 0);
  const size_t scene_samples = load_skin_samples(cfg, scene, adc_shift, a.tail_s);
  return {{"top", "dtmf_top"},
          {"sample_hz", scene.skin.adc.rate_hz},
          {"samples", cfg.samples},
          {"scene_samples", scene_samples}};
}

int run_to_end(const VboardArgs& a, FILE* json, FpgaModel& fpga, PtyPort& pty,
               const BoardConfig& cfg, const std::string& key, const nlohmann::json& ready_extra,
               const std::function<nlohmann::json()>& done_extra) {
  VirtualBoard board("board", fpga, pty, cfg);
  print_ready(json, pty, key, cfg.clk_hz, cfg.baud, ready_extra);
  sc_core::sc_start();
  fpga.close_trace();
  print_done(json, board.stats(), done_extra ? done_extra() : nlohmann::json::object());
  hang_up_when_read(pty, board.stats(), a.reader_timeout_s);
  return 0;
}

}  // namespace eskin::vboard
