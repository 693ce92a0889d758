#include "host/simulate/soak.h"

#include <fmt/format.h>
#include <fmt/os.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include "host/link/delivery_check.h"
#include "host/link/link_encoder.h"
#include "host/report/html_page.h"
#include "host/stream/board_link.h"
#include "sim/scene.h"
#include "sim/vboard/fpga_params.h"
#include "sim/vboard/vboard_build.h"
#include "sim/vboard/vboard_process.h"

namespace eskin::simulate {

SoakResult run_soak(const SoakOptions& o) {
  const sim::Scene scene = sim::load_scene(o.scene);
  if (scene.has_hall || !scene.has_skin)
    throw std::invalid_argument(o.scene + ": the soak runs a DTMF skin scene (no Hall sensors)");
  const vboard::FpgaBuild build = vboard::fpga_build_for(scene);
  if (build.key != "default")
    throw std::invalid_argument(o.scene + ": the soak runs on the prebuilt board (FPGA build "
                                "'default'); this scene needs build '" + build.key + "'");
  if (!o.line.any())
    throw std::invalid_argument("the soak needs a line fault (--ber, --drop-rate, --insert-rate, "
                                "--pull-cable)");
  std::filesystem::create_directories(o.out);
  const std::string tap = (std::filesystem::path(o.out) / "fpga_sent.bin").string();
  std::vector<std::string> extra = vboard::line_fault_args(o.line);
  extra.insert(extra.end(), {"--tap-to-host", tap});
  const std::string exe = vboard::board_executable(
      build, [](const std::string& m) { fmt::print(stderr, "eskin bench soak: {}\n", m); });
  vboard::VboardProcess board(exe, stream::board_args(o.scene, "", {}, extra));

  SoakResult r;
  stream::LinkStream port(stream::board_link_options(board.pty(), int(build.baud())));
  std::vector<link::PacketKey> keys;  // on the reader thread, read after port.stop()
  link::LinkEncoder enc;
  std::atomic<long> last_t{0};
  port.on_packet([&](const link::Packet& p) {
    keys.push_back(link::key_of(p));
    last_t = long(p.t);
    if (p.type == link::kStatus) {
      ++r.status_received;
      r.last_status = p.status;
    }
    if (p.type == link::kAmplitudes && o.status_requests > 0) {
      std::vector<uint8_t> w;
      for (int i = 0; i < o.status_requests; ++i) {
        const std::vector<uint8_t> c = enc.request_status();
        w.insert(w.end(), c.begin(), c.end());
      }
      port.send(w);
      r.commands_sent += uint64_t(o.status_requests);
    }
  });
  port.start();
  stream::Progress bar(size_t(scene.duration_s * scene.skin.adc.rate_hz));
  stream::read_until_board_done(board, port, [&] { bar.update(size_t(last_t.load())); });
  bar.update(size_t(scene.duration_s * scene.skin.adc.rate_hz));
  const stream::BoardRun run = stream::finish_board_run(board, port, {});
  if (board.wait() != 0) throw std::runtime_error("the virtual board failed (its messages above)");
  r.line = line_report(tap, keys, run.link, run.done);
  r.sim_s = run.done.at("sim_s");
  r.wall_s = run.done.at("wall_s");
  r.cpu_s = run.done.at("cpu_s");
  fmt::output_file((std::filesystem::path(o.out) / "soak.json").string())
      .print("{}\n", to_json(r.line).dump(2));
  write_soak_report(r, o, (std::filesystem::path(o.out) / "report.html").string());
  return r;
}

std::vector<std::vector<std::string>> soak_rows(const SoakResult& r) {
  std::vector<std::vector<std::string>> rows = line_rows(r.line);
  const link::StatusBlock& s = r.last_status;
  rows.push_back({"host -> FPGA: REQUEST_STATUS sent / STATUS delivered",
                  fmt::format("{} / {}", r.commands_sent, r.status_received)});
  rows.push_back({"the board's last STATUS: commands accepted / CRC errors / frame errors / UART "
                  "errors / dropped packets",
                  fmt::format("{} / {} / {} / {} / {}", s.cmd_accepted, s.cmd_crc_errors,
                              s.cmd_frame_errors, s.uart_rx_errors, s.dropped_frames)});
  rows.push_back({"simulated s / wall s / simulated s per CPU s of the board",
                  fmt::format("{:.3f} / {:.0f} / {:.2f}", r.sim_s, r.wall_s, r.sim_s / r.cpu_s)});
  return rows;
}

void write_soak_report(const SoakResult& r, const SoakOptions& o, const std::string& path) {
  report::Page page("eskin line soak: " + std::filesystem::path(o.scene).filename().string());
  page.text(fmt::format(
      "Scene {} on the virtual board, the serial line faulty both ways (BER {:g} to the host, "
      "{:g} to the FPGA, seed {}), the host sending {} REQUEST_STATUS per AMPLITUDES packet. "
      "Every packet the host delivered is judged against the FPGA's own bytes, tapped at its "
      "uart_txd pin before the line (docs/vboard.md, \"Line faults\").",
      o.scene, o.line.to_host.ber, o.line.to_fpga.ber, o.line.seed, o.status_requests));
  page.heading("The soak");
  page.table({"figure", "value"}, soak_rows(r));
  page.write(path);
}

std::string soak_csv(const SoakResult& r, const SoakOptions& o, const std::string& command) {
  const link::DeliveryCheck& c = r.line.check;
  const vboard::DirectionCounts& h = r.line.injected.to_host;
  const vboard::DirectionCounts& f = r.line.injected.to_fpga;
  const std::string src = "\"" + command + "\"";
  std::string s = fmt::format(
      "# The line soak (docs/vboard.md, \"Line faults: the soak\"), written by `eskin bench "
      "soak --csv` (host/simulate/soak.h);\n# cited as <!--fig:soak/NAME-->. BER {:g} to the "
      "host, {:g} to the FPGA; seed {}; {} REQUEST_STATUS per AMPLITUDES packet.\n"
      "name,value,unit,source\n",
      o.line.to_host.ber, o.line.to_fpga.ber, o.line.seed, o.status_requests);
  const auto row = [&](const char* name, double v, const char* unit) {
    s += fmt::format("{},{},{},{}\n", name, v, unit, src);
  };
  row("ber", o.line.to_host.ber, "per bit");
  row("sim_s", std::round(r.sim_s * 1000) / 1000, "s");
  row("packets_sent", double(c.sent), "packets");
  row("packets_delivered", double(c.delivered), "packets");
  row("packets_lost", double(c.lost), "packets");
  row("packets_counted_lost", double(r.line.host.lost_packets), "packets");
  row("packets_lost_unseen", double(c.unseen), "packets");
  row("packets_delivered_wrong", double(c.wrong), "packets");
  row("recoveries", double(c.recoveries), "recoveries");
  row("host_error_frames",
      double(r.line.host.crc_errors + r.line.host.framing_errors + r.line.host.payload_errors),
      "frames");
  row("to_host_chars", double(h.chars), "characters");
  row("to_host_flips", double(h.flips()), "bits");
  row("to_fpga_chars", double(f.chars), "characters");
  row("to_fpga_flips", double(f.flips()), "bits");
  row("commands_sent", double(r.commands_sent), "commands");
  row("status_received", double(r.status_received), "packets");
  row("board_cmd_errors", double(r.last_status.cmd_crc_errors + r.last_status.cmd_frame_errors),
      "frames");
  return s;
}

std::string soak_text(const SoakResult& r) {
  std::string s;
  for (const auto& row : soak_rows(r)) s += row[0] + ": " + row[1] + "\n";
  return s;
}

}  // namespace eskin::simulate
