#include "host/report/simulate_mixed_report.h"

#include <fmt/format.h>
#include <fmt/os.h>

#include <filesystem>

#include "host/fpga/scale_table.h"
#include "host/link/link_decoder.h"
#include "host/report/html_page.h"
#include "host/report/simulate_hall_report.h"

namespace eskin::report {
namespace {

// The board's packets: DTMF and Hall, and the shared link's errors.
struct MixedLink {
  size_t packets = 0, hall = 0;
  uint64_t link_errors = 0;
};

MixedLink mixed_link(const stream::BoardRun& run) {
  MixedLink m;
  m.packets = run.rx.size();
  for (const link::Packet& p : run.rx) m.hall += link::is_hall_packet(p.type);
  const link::DecoderStats& ls = run.link;
  m.link_errors = ls.crc_errors + ls.framing_errors + ls.payload_errors;
  return m;
}

// report.html: the board, the shared link, each part's headline figures.
void mixed_page(const sim::Scene& scene, const std::string& scene_file,
                const vboard::MixedBuild& build, const vboard::FpgaBuild& dtmf,
                const stream::BoardRun& run, const MixedLink& m, const nlohmann::json& skin,
                const nlohmann::json& hall, const std::string& path) {
  const link::DecoderStats& ls = run.link;
  Page page("eskin simulate: " + scene.name);
  page.text(fmt::format(
      "A DTMF skin and Hall sensors on one FPGA (rtl/mixed_top.v, build {} at {:.0f} MHz): both "
      "tops' packets share one link, numbered by one seq counter. The skin's report is "
      "skin/report.html, the Hall sensors' hall/report.html. Scene file: {}.",
      build.key, dtmf.clk_hz() / 1e6, scene_file));
  std::vector<std::vector<std::string>> rows{
              {"packets: DTMF / Hall", fmt::format("{} / {}", m.packets - m.hall, m.hall)},
              {"link: bytes / CRC errors / framing errors / lost packets",
               fmt::format("{} / {} / {} / {}", ls.bytes, ls.crc_errors, ls.framing_errors,
                           ls.lost_packets)},
              {"skin: worst taxel RMS error FPGA / golden (kPa)",
               fmt::format("{:.3f} / {:.3f}", skin.at("fpga_worst_rms_kpa").get<double>(),
                           skin.at("golden_worst_rms_kpa").get<double>())},
              {"skin: latency onset -> host, median (us)",
               fmt::format("{:.1f}", skin.at("latency_median_us").get<double>())},
              {"Hall: frames / incomplete", fmt::format("{} / {}", hall.at("frames").get<size_t>(),
                                                        hall.at("incomplete_frames").get<size_t>())},
              {"Hall: latency DRDY -> host, median (us)",
               fmt::format("{:.1f}", hall.at("latency_median_us").get<double>())},
              {"I2C timing violations / ADC timing violations",
               fmt::format("{} / {}", run.done.at("i2c_violations").get<uint64_t>(),
                           run.done.at("adc_violations").get<uint64_t>())}};
  rows.insert(rows.end(), run.line_rows.begin(), run.line_rows.end());  // faults
  page.table({"figure", "value"}, rows);
  page.write(path);
}

}  // namespace

nlohmann::json report_mixed(const sim::Scene& scene, const std::string& scene_file,
                            const vboard::MixedBuild& build, const vboard::FpgaBuild& dtmf,
                            const GoldenRun& gold, const hall::HallFpgaSetup& setup,
                            const stream::BoardRun& run, size_t total, const std::string& out_dir) {
  // Each part's report names the board's build.
  vboard::FpgaBuild skin_build = dtmf;
  skin_build.key = build.key;
  vboard::HallBuild hall_build = build.hall;
  hall_build.key = build.key;
  const std::filesystem::path out(out_dir);
  const nlohmann::json skin = report_dtmf(scene, scene_file, skin_build, gold, run, total, (out / "skin").string());
  const nlohmann::json hall = report_hall(scene, scene_file, hall_build, setup, run, (out / "hall").string());

  const MixedLink m = mixed_link(run);
  const link::DecoderStats& ls = run.link;
  nlohmann::json sum = {
      {"scene", scene_file}, {"fidelity", run.done.at("fidelity")}, {"top", "mixed_top"},
      {"fpga_build", build.key},
      {"fpga_clk_hz", dtmf.clk_hz()}, {"fpga_engine_shifter", fpga::shifter_name(engine_of(dtmf))},
      {"fpga_neurons", fpga::neurons_name(engine_of(dtmf))}, {"packets", m.packets},
      {"dtmf_packets", m.packets - m.hall}, {"hall_packets", m.hall},
      {"link_errors", m.link_errors}, {"lost_packets", ls.lost_packets},
      {"skin", skin}, {"hall", hall}};
  if (!run.line.is_null()) sum["line"] = run.line;
  if (!run.board_faults.is_null()) sum["board_faults"] = run.board_faults;
  fmt::output_file((out / "summary.json").string()).print("{}\n", sum.dump(2));
  mixed_page(scene, scene_file, build, dtmf, run, m, skin, hall, (out / "report.html").string());
  fmt::print("mixed board {}: {} DTMF and {} Hall packets on one link, {} link errors, {} lost; "
             "report: {}\n",
             build.key, m.packets - m.hall, m.hall, m.link_errors, ls.lost_packets,
             (out / "report.html").string());
  return sum;
}

}  // namespace eskin::report
