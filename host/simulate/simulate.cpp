#include "host/simulate/simulate.h"

#include <fmt/format.h>
#include <fmt/os.h>

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <thread>

#include "eskin/skin_config.h"
#include "host/fpga/board.h"
#include "host/fpga/flow.h"
#include "host/hall/hall_fpga_setup.h"
#include "host/link/link_encoder.h"
#include "host/report/simulate_dtmf_report.h"
#include "host/report/simulate_hall_report.h"
#include "host/report/simulate_mixed_report.h"
#include "host/simulate/golden_run.h"
#include "host/simulate/line_report.h"
#include "host/simulate/packet_board.h"
#include "sim/cycle/dtmf_top.h"
#include "host/stream/board_link.h"
#include "sim/hall_world.h"
#include "sim/scene.h"
#include "sim/vboard/fpga_params.h"
#include "sim/vboard/hall_build.h"
#include "sim/vboard/mixed_build.h"
#include "sim/vboard/vboard_build.h"
#include "sim/vboard/vboard_process.h"

namespace eskin::simulate {
namespace {

using link::Packet;

// The scene's FPGA build on the virtual board, which models the
// iCEBreaker: the default scene's build at 18 MHz, any other with the
// engine and the slowest clock of the board's PLL at which the core keeps
// up with the scene's frames, as `eskin bitstream` chooses them
// (host/fpga/flow.h: the frame engine's measured load on the scene's
// samples).
vboard::FpgaBuild board_build(const sim::Scene& scene) {
  vboard::FpgaBuild b = vboard::fpga_build_for(scene);  // names a bad field
  if (b.key == "default") return b;
  fpga::CoreClock cc;
  try {
    cc = fpga::choose_core_clock(fpga::find_board("icebreaker"), scene, fpga::LoadPolicy::Scene);
  } catch (const std::invalid_argument& e) {
    throw ConfigError("skin", e.what());
  }
  if (!cc.budget.ok()) {
    std::string why;
    for (const auto& p : cc.budget.problems) why += (why.empty() ? "" : "; ") + p;
    throw ConfigError("skin", fmt::format("no clock of the iCEBreaker's PLL keeps the FPGA top up "
                                          "with this scene (it needs at least {:.1f} MHz): {}",
                                          double(cc.core_min_hz) / 1e6, why));
  }
  return vboard::fpga_build_for(scene, "", cc.plan.spec.clk_hz, cc.plan.spec.baud,
                                {cc.plan.spec.engine_fast_shift, cc.plan.spec.neuron_unit});
}

void note(const std::string& m) { fmt::print(stderr, "eskin simulate: {}\n", m); }

// Every packet the host received, raw, in order (fpga_link.csv): what two
// fidelity levels of one scene are compared by (docs/vboard.md).
void write_link_log(const std::string& out, const stream::BoardRun& run) {
  auto f = fmt::output_file((std::filesystem::path(out) / "fpga_link.csv").string());
  f.print("seq,type,t,arrival_us,payload_hex\n");
  for (size_t i = 0; i < run.rx.size(); ++i) {
    const Packet& p = run.rx[i];
    std::string hex;
    hex.reserve(2 * p.payload.size());
    for (uint8_t b : p.payload) hex += fmt::format("{:02x}", b);
    f.print("{},{},{},{:.3f},{}\n", p.seq, p.type, p.t, run.arrival_us[i], hex);
  }
}

// With line faults: the FPGA's bytes as sent, tapped at its pin by the board.
std::string tap_file(const SimulateOptions& o) {
  return (std::filesystem::path(o.out) / "fpga_sent.bin").string();
}

// The board's fault options: the line's, the tap that judges them, and
// the board's own.
std::vector<std::string> line_args(const SimulateOptions& o) {
  std::vector<std::string> a = vboard::board_fault_args(o.faults);
  if (!o.line.any()) return a;
  const std::vector<std::string> l = vboard::line_fault_args(o.line);
  a.insert(a.end(), l.begin(), l.end());
  a.insert(a.end(), {"--tap-to-host", tap_file(o)});
  return a;
}

// With line faults: what the host delivered against what the FPGA sent,
// into the run (the report's rows, summary.json), line.json and stdout.
void judge_line(const SimulateOptions& o, stream::BoardRun& run) {
  if (!o.line.any()) return;
  std::vector<link::PacketKey> keys;
  keys.reserve(run.rx.size());
  for (const Packet& p : run.rx) keys.push_back(link::key_of(p));
  const LineReport r = line_report(tap_file(o), keys, run.link, run.done);
  run.line = to_json(r);
  run.line_rows = line_rows(r);
  fmt::output_file((std::filesystem::path(o.out) / "line.json").string())
      .print("{}\n", run.line.dump(2));
  fmt::print("{}", line_text(r));
}

// With board faults: when each began and ended on the board's clock, and
// what the host saw (restarts, error frames, lost packets), into the run
// (the report's rows, summary.json) and stdout.
void note_board_faults(const SimulateOptions& o, stream::BoardRun& run) {
  if (o.faults.empty()) return;
  run.board_faults = run.done.at("board_faults");
  for (const auto& f : run.board_faults) {
    const std::string name = "board fault " + f.at("fault").get<std::string>();
    std::string v = "never began (its moment did not come)";
    if (f.at("begun").get<bool>()) {
      const double e = f.at("end_ns");
      v = fmt::format("from {:.3f} ms to {}", f.at("begin_ns").get<double>() / 1e6,
                      e < 0 ? std::string("the end of the run") : fmt::format("{:.3f} ms", e / 1e6));
    }
    run.line_rows.push_back({name, v});
  }
  run.line_rows.push_back(
      {"host: board restarts / error frames / lost packets",
       fmt::format("{} / {} / {}", run.link.restarts,
                   run.link.crc_errors + run.link.framing_errors + run.link.payload_errors,
                   run.link.lost_packets)});
  for (size_t i = run.line_rows.size() - run.board_faults.size() - 1; i < run.line_rows.size(); ++i)
    fmt::print("{}: {}\n", run.line_rows[i][0], run.line_rows[i][1]);
}

// The skin's outputs (amplitudes, taxels, spikes as the scene asks) plus
// the periodic status, whose counters go into the report.
std::vector<uint8_t> output_mask_command(const sim::Scene& scene, link::LinkEncoder& enc) {
  return enc.set_output_mask(uint8_t((scene.outputs.amplitudes ? 1 : 0) |
                                     (scene.outputs.taxels ? 2 : 0) |
                                     (scene.outputs.spikes ? 4 : 0) | 8));
}

// The decoding's constants, calibrated by the golden chain on the scene's
// skin and quantised for the FPGA, with the commands that load them
// (host/hall/hall_fpga_setup.h).
hall::HallFpgaSetup hall_simulation_setup(const sim::Scene& scene, const sim::HallTopSpec& spec) {
  const sim::HallWorld world(scene.hall);
  link::LinkEncoder enc;
  return hall::hall_fpga_setup(world, spec, scene.seed, enc);
}

// A Hall scene (docs/vboard.md, "Hall skins"): the scene's Hall build of
// rtl/hall_top.v with its MLX90393s on the I2C buses; the decoding
// configured over the link from the golden chain's calibration.
int run_simulate_hall(const sim::Scene& scene, const SimulateOptions& o) {
  const vboard::HallBuild build = vboard::hall_build_for(scene);  // names a bad field
  const hall::HallFpgaSetup setup = hall_simulation_setup(scene, build.spec);
  const std::string exe = o.board.empty() ? vboard::board_executable(build, note) : o.board;
  std::filesystem::create_directories(o.out);

  vboard::VboardProcess board(exe,
                              stream::board_args(o.scene, o.trace, {setup.commands}, line_args(o)));
  stream::BoardRun run = stream::run_board(
      board, int(build.baud), {setup.commands}, size_t(scene.duration_s * 1e6),
      [](const Packet& p) { return p.type == link::kHallSamples ? long(p.t) : -1L; });
  run.done["fidelity"] = "rtl";
  write_link_log(o.out, run);
  judge_line(o, run);
  note_board_faults(o, run);
  report::report_hall(scene, o.scene, build, setup, run, o.out);
  return board.wait() == 0 ? 0 : 1;
}

// A scene with both a DTMF skin and Hall sensors: rtl/mixed_top.v on one
// board, both tops' packets on one link. The host configures both (the
// skin's outputs; the Hall decoding's calibration).
int run_simulate_mixed(const sim::Scene& scene, const SimulateOptions& o) {
  const vboard::FpgaBuild dtmf = board_build(scene);
  const vboard::MixedBuild build = vboard::mixed_build_for(scene, dtmf);  // names a bad field
  const hall::HallFpgaSetup setup = hall_simulation_setup(scene, build.hall.spec);
  const std::string exe = o.board.empty() ? vboard::board_executable(build, note) : o.board;
  std::filesystem::create_directories(o.out);

  link::LinkEncoder enc;
  const std::vector<std::vector<uint8_t>> commands = {output_mask_command(scene, enc),
                                                      setup.commands};
  vboard::VboardProcess board(exe, stream::board_args(o.scene, o.trace, commands, line_args(o)));
  const size_t total = board.ready().at("scene_samples");
  report::GoldenRun gold;
  stream::BoardRun run = stream::run_board(
      board, int(dtmf.baud()), commands, total,
      [](const Packet& p) { return link::is_hall_packet(p.type) ? -1L : long(p.t); },
      [&] { gold = run_golden(scene, dtmf.plan.step); });
  run.done["fidelity"] = "rtl";
  write_link_log(o.out, run);
  judge_line(o, run);
  note_board_faults(o, run);
  report::report_mixed(scene, o.scene, build, dtmf, gold, setup, run, total, o.out);
  return board.wait() == 0 ? 0 : 1;
}

// A DTMF skin: the board's serial port through the host streaming library
// (host/stream), packets decoded and checked by host/link. The host
// configures the board like a host program: the scene's outputs, plus the
// periodic status (its counters go into the report).
int run_simulate_dtmf(const sim::Scene& scene, const SimulateOptions& o) {
  const vboard::FpgaBuild build = board_build(scene);
  link::LinkEncoder enc;
  const std::vector<std::vector<uint8_t>> commands = {output_mask_command(scene, enc)};
  if (o.fidelity == Fidelity::packet) {  // no board process: the packets on this thread
    std::filesystem::create_directories(o.out);
    report::GoldenRun gold;
    std::thread side([&] { gold = run_golden(scene, build.plan.step); });
    stream::BoardRun run;
    try {
      run = run_packet_board(scene, build.plan, commands);
    } catch (...) {
      side.join();
      throw;
    }
    side.join();
    write_link_log(o.out, run);
    report::report_dtmf(scene, o.scene, build, gold, run, run.done.at("scene_samples"), o.out);
    return 0;
  }
  std::vector<std::string> args = stream::board_args(o.scene, o.trace, commands, line_args(o));
  std::string exe;
  if (o.fidelity == Fidelity::cycle) {  // one board for every build it models: the build as options
    const std::string why = cycle::DtmfTop::unsupported(build.plan);
    if (!why.empty())
      throw ConfigError("--fidelity", fmt::format("{}: the cycle level does not model this scene's "
                                                  "build ({}): use --fidelity rtl",
                                                  o.scene, why));
    exe = vboard::cycle_board_executable();
    const hls::DtmfTopSpec& sp = build.plan.spec;
    args.insert(args.end(), {"--clk-hz", std::to_string(sp.clk_hz), "--baud", std::to_string(sp.baud),
                             "--engine-shifter", sp.engine_fast_shift ? "barrel" : "bit-serial",
                             "--neurons", sp.neuron_unit ? "unit" : "microcode"});
  } else {
    exe = o.board.empty() ? vboard::board_executable(build, note) : o.board;
  }
  std::filesystem::create_directories(o.out);

  vboard::VboardProcess board(exe, args);
  const size_t total = board.ready().at("scene_samples");
  report::GoldenRun gold;
  stream::BoardRun run = stream::run_board(
      board, int(build.baud()), commands, total,
      [](const Packet& p) { return long(p.t); },
      [&] { gold = run_golden(scene, build.plan.step); });
  run.done["fidelity"] = fidelity_name(o.fidelity);
  write_link_log(o.out, run);
  judge_line(o, run);
  note_board_faults(o, run);
  report::report_dtmf(scene, o.scene, build, gold, run, total, o.out);
  return board.wait() == 0 ? 0 : 1;
}

}  // namespace

// The output folder, created and written to once (a file made and removed)
// before the simulation: an unwritable --out is found in a second, not
// after the whole run. Throws ConfigError naming the path and the reason.
void check_out_dir(const std::string& out) {
  std::error_code ec;
  std::filesystem::create_directories(out, ec);
  if (ec)
    throw ConfigError("--out", fmt::format("'{}': cannot create the output folder: {}", out,
                                           ec.message()));
  const std::string probe = (std::filesystem::path(out) / (".eskin-write-probe." + std::to_string(::getpid()))).string();
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0)
    throw ConfigError("--out", fmt::format("'{}': cannot write in the output folder: {}", out,
                                           std::strerror(errno)));
  ::close(fd);
  ::unlink(probe.c_str());
}

const char* fidelity_name(Fidelity f) {
  return f == Fidelity::packet ? "packet" : f == Fidelity::cycle ? "cycle" : "rtl";
}

Fidelity parse_fidelity(const std::string& s) {
  if (s == "rtl") return Fidelity::rtl;
  if (s == "cycle") return Fidelity::cycle;
  if (s == "packet") return Fidelity::packet;
  throw ConfigError("--fidelity", "'" + s + "': expected rtl, cycle or packet");
}

int run_simulate(const SimulateOptions& o) {
  const sim::Scene scene = sim::load_scene(o.scene);  // a bad scene fails here, before anything runs
  for (const vboard::CablePull& p : o.line.pulls)
    if (p.at_ms >= scene.duration_s * 1e3)
      throw std::invalid_argument(fmt::format(
          "--pull-cable {}:{}: the scene ends at {} ms, so the cable would be pulled after it",
          p.at_ms, p.for_ms, scene.duration_s * 1e3));
  vboard::check_board_faults(o.faults, scene.has_skin ? scene.skin.rows + scene.skin.cols : 0,
                             scene.has_hall ? scene.hall.config.bus_count() : 0);
  for (const vboard::BoardFault& f : o.faults)
    if (f.at_ms >= scene.duration_s * 1e3)
      throw std::invalid_argument(fmt::format("--fault {}: the scene ends at {} ms, before it",
                                              vboard::board_fault_text(f), scene.duration_s * 1e3));
  if (o.fidelity != Fidelity::rtl) {  // what the faster levels do not model is refused
    if (scene.has_hall)
      throw ConfigError("--fidelity", fmt::format("{}: the {} level models DTMF skins; this scene "
                                                  "has Hall sensors: use --fidelity rtl",
                                                  o.scene, fidelity_name(o.fidelity)));
    // The cycle level has the board and the FPGA's pins (faults act there)
    // but no waveforms, and is one board executable of its own.
    const bool packet = o.fidelity == Fidelity::packet;
    const char* opt = !o.board.empty()   ? "--board"
                      : !o.trace.empty() ? "--trace"
                      : packet && o.line.any() ? "line faults (--ber, --drop-rate, --insert-rate, --pull-cable)"
                      : packet && !o.faults.empty() ? "--fault"
                                                    : nullptr;
    if (opt)
      throw ConfigError("--fidelity", fmt::format("{} needs the Verilated board (--fidelity rtl); "
                                                  "the {} level has {}",
                                                  opt, fidelity_name(o.fidelity),
                                                  packet ? "no pins to fault or trace"
                                                         : "no waveforms and one board of its own"));
  }
  check_out_dir(o.out);
  if (scene.has_hall && scene.has_skin) return run_simulate_mixed(scene, o);
  if (scene.has_hall) return run_simulate_hall(scene, o);
  return run_simulate_dtmf(scene, o);
}

}  // namespace eskin::simulate
