#include "host/report/simulate_dtmf_report.h"

#include <fmt/format.h>
#include <fmt/os.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "host/golden/sdft_bank.h"
#include "host/link/link_decoder.h"
#include "host/report/csv_fields.h"
#include "host/report/simulate_report.h"
#include "sim/world_model.h"

namespace eskin::report {
namespace {

namespace fs = std::filesystem;
using link::Packet;

struct FpgaFrame {  // a packet with its arrival at the host
  Packet p;
  double arrival_us = -1;
};

std::string ms(double v) { return fmt::format("{:.3f}", v); }

// What the report compares: the scene's skin, the FPGA build and the
// golden run.
struct DtmfRun {
  const sim::Scene& scene;
  const SkinConfig& skin;
  const vboard::FpgaBuild& build;
  const GoldenRun& gold;
  double fs;
  int R, C, T, K;
  std::string level;  // the board's fidelity level (its done line's "fidelity")
};

// The FPGA's packets scored: against the golden model and the truth, the
// spikes and the last status.
struct DtmfScores {
  double amp_err = 0, kpa_err = 0, kpa_sq = 0;
  size_t kpa_n = 0, status_n = 0, fspk2 = 0, gspk2 = 0;
  link::StatusBlock last_status;
  SpikeTrain fspk{"FPGA", {}, {}}, gspk{"golden", {}, {}};
  std::vector<double> fpga_lat;
};

// The output files written packet by packet, headers first.
struct DtmfFiles {
  fmt::ostream amp_csv, tax_csv, nd;
};

// The report's labels and per-carrier, per-taxel series.
void init_report(const DtmfRun& d, const std::string& scene_file, SimulateReport& rep) {
  rep.title = "eskin simulate: " + d.scene.name;
  rep.scene_file = scene_file;
  for (int i = 0; i < d.R; ++i)
    for (int j = 0; j < d.C; ++j) rep.taxel_labels.push_back(fmt::format("r{}c{}", i, j));
  rep.carrier_labels = d.skin.carrier_labels();
  for (int k = 0; k < d.K; ++k) {
    rep.fpga_amp.push_back({"FPGA " + rep.carrier_labels[size_t(k)], {}, {}});
    rep.golden_amp.push_back({"golden " + rep.carrier_labels[size_t(k)], {}, {}});
  }
  rep.fpga_kpa.assign(size_t(d.T), {});
  rep.golden_kpa.assign(size_t(d.T), {});
  rep.truth_kpa.assign(size_t(d.T), {});
}

DtmfFiles open_files(const DtmfRun& d, const SimulateReport& rep, const std::string& out_dir) {
  DtmfFiles f{fmt::output_file((fs::path(out_dir) / "fpga_amplitudes.csv").string()),
              fmt::output_file((fs::path(out_dir) / "fpga_taxels.csv").string()),
              fmt::output_file((fs::path(out_dir) / "fpga_packets.ndjson").string())};
  f.amp_csv.print("sample,t_ms,arrival_us");
  for (double fr : d.skin.carrier_freqs_hz()) f.amp_csv.print(",amp_{}hz", fr);
  f.tax_csv.print("sample,t_ms,arrival_us");
  for (const auto& l : rep.taxel_labels) f.tax_csv.print(",{}_kpa,{}_golden_kpa,{}_truth_kpa", l, l, l);
  f.amp_csv.print("\n");
  f.tax_csv.print("\n");
  return f;
}

// An AMPLITUDES packet in the scene's ADC LSB (peak), like golden's amp_lsb,
// against the golden frame `g` (null: none at this sample).
void on_amplitudes(const DtmfRun& d, const FpgaFrame& f, const golden::Frame* g, double amp_scale,
                   DtmfFiles& out, SimulateReport& rep, DtmfScores& s) {
  const Packet& p = f.p;
  const double t_ms = 1000.0 * p.t / d.fs;
  out.amp_csv.print("{},{:.4f},{:.2f}", p.t, t_ms, f.arrival_us);
  std::string vals;
  for (int k = 0; k < d.K; ++k) {
    const double v = p.amplitudes[size_t(k)] * amp_scale;
    out.amp_csv.print(",{:.6g}", v);
    vals += fmt::format("{}{:.6g}", k ? "," : "", v);
    rep.fpga_amp[size_t(k)].t_ms.push_back(t_ms);
    rep.fpga_amp[size_t(k)].value.push_back(v);
    if (g) {
      rep.golden_amp[size_t(k)].t_ms.push_back(t_ms);
      rep.golden_amp[size_t(k)].value.push_back(g->amp_lsb[k]);
      s.amp_err = std::max(s.amp_err, std::fabs(v - g->amp_lsb[k]));
    }
  }
  out.amp_csv.print("\n");
  out.nd.print("{{\"type\":\"amplitudes\",\"sample\":{},\"t_ms\":{:.4f},\"arrival_us\":{:.2f},\"amp_lsb\":[{}]}}\n",
               p.t, t_ms, f.arrival_us, vals);
}

// A TAXELS packet in kPa through the skin's conductance curve, scored like
// the golden model's frames, next to the golden frame `g` and the truth.
void on_taxels(const DtmfRun& d, const FpgaFrame& f, const golden::Frame* g,
               golden::DecodeScorer& scorer, sim::WorldModel& truth_world, DtmfFiles& out,
               SimulateReport& rep, DtmfScores& s) {
  const Packet& p = f.p;
  const double t_ms = 1000.0 * p.t / d.fs;
  const int C = d.C, T = d.T;
  golden::Frame ff;
  ff.sample = p.t;
  ff.pressure.resize(d.R, C);
  for (int i = 0; i < T; ++i)
    ff.pressure(i / C, i % C) = d.skin.conductance.inverse(p.taxels[size_t(i)] / 32768.0);
  ff.pressure_raw = ff.pressure;
  scorer.add(ff);
  std::vector<double> truth;
  truth_world.pressure_at(p.t, truth);
  rep.frame_t_ms.push_back(t_ms);
  out.tax_csv.print("{},{:.4f},{:.2f}", p.t, t_ms, f.arrival_us);
  for (int i = 0; i < T; ++i) {
    const double v = ff.pressure(i / C, i % C);
    const double gv = g ? g->pressure(i / C, i % C) : 0;
    rep.fpga_kpa[size_t(i)].push_back(v);
    rep.golden_kpa[size_t(i)].push_back(gv);
    rep.truth_kpa[size_t(i)].push_back(truth[size_t(i)]);
    rep.kpa_max = std::max({rep.kpa_max, truth[size_t(i)], v});
    out.tax_csv.print(",{:.6g},{:.6g},{:.6g}", v, gv, truth[size_t(i)]);
    if (g) {
      const double diff = v - gv;  // both ghost-corrected
      s.kpa_err = std::max(s.kpa_err, std::fabs(diff));
      s.kpa_sq += diff * diff;
      ++s.kpa_n;
    }
  }
  out.tax_csv.print("\n");
  out.nd.print("{{\"type\":\"taxels\",\"sample\":{},\"t_ms\":{:.4f},\"arrival_us\":{:.2f},\"pressure_kpa\":[{}]}}\n",
               p.t, t_ms, f.arrival_us, join(ff.pressure));
}

// A SPIKES packet: the receptors go to the raster, layer 1 is counted.
void on_spikes(const DtmfRun& d, const FpgaFrame& f, DtmfFiles& out, DtmfScores& s) {
  const Packet& p = f.p;
  for (const auto& sp : p.spikes) {
    const double ts = 1000.0 * (p.t + sp.dt) / d.fs;
    out.nd.print("{{\"type\":\"spike\",\"t_ms\":{:.4f},\"layer\":{},\"taxel\":{},\"arrival_us\":{:.2f}}}\n",
                 ts, sp.layer, sp.neuron, f.arrival_us);
    if (sp.layer != 0) {
      ++s.fspk2;
      continue;
    }
    s.fspk.t_ms.push_back(ts);
    s.fspk.taxel.push_back(sp.neuron);
  }
}

// The FPGA's frames in physical units, scored like the golden model's;
// returns the FPGA's score.
golden::DecodeScore score_packets(const DtmfRun& d, const std::vector<FpgaFrame>& rx,
                                  double amp_scale, DtmfFiles& out, SimulateReport& rep,
                                  DtmfScores& s) {
  sim::WorldModel truth_world(d.scene);
  golden::DecodeScorer scorer(d.skin, d.scene.decoder, [&](size_t n, std::vector<double>& p) {
    truth_world.pressure_at(n, p);
  });
  const auto& gf = d.gold.frames;
  for (const FpgaFrame& f : rx) {
    const Packet& p = f.p;
    const golden::Frame* g = p.t < gf.size() && gf[p.t].amp_lsb.size() ? &gf[p.t] : nullptr;
    if (p.type == link::kAmplitudes && int(p.amplitudes.size()) == d.K) {
      on_amplitudes(d, f, g, amp_scale, out, rep, s);
    } else if (p.type == link::kTaxelsDense && int(p.taxels.size()) == d.T) {
      on_taxels(d, f, g, scorer, truth_world, out, rep, s);
    } else if (p.type == link::kSpikes) {
      on_spikes(d, f, out, s);
    } else if (p.type == link::kStatus) {
      ++s.status_n;
      s.last_status = p.status;
    }
  }
  return scorer.score();
}

// The golden spikes next to the FPGA's: the raster and spikes.csv.
void spikes_section(const DtmfRun& d, const std::string& out_dir, SimulateReport& rep,
                    DtmfScores& s) {
  for (size_t t = 0; t < d.gold.spikes_ms.size(); ++t)
    for (double ts : d.gold.spikes_ms[t]) {
      s.gspk.t_ms.push_back(ts);
      s.gspk.taxel.push_back(int(t));
    }
  for (const auto& v : d.gold.spikes2_ms) s.gspk2 += v.size();
  rep.spikes = {s.fspk, s.gspk};
  auto s_csv = fmt::output_file((fs::path(out_dir) / "spikes.csv").string());
  s_csv.print("model,t_ms,taxel,row,col\n");
  for (const auto* tr : {&s.fspk, &s.gspk})
    for (size_t i = 0; i < tr->t_ms.size(); ++i)
      s_csv.print("{},{:.4f},{},{},{}\n", tr->label, tr->t_ms[i], tr->taxel[i], tr->taxel[i] / d.C,
                  tr->taxel[i] % d.C);
}

// Latency: touch onset (truth) -> first frame with the taxel lit, FPGA on
// the host and golden; latency.csv.
void latency_section(const DtmfRun& d, const std::vector<FpgaFrame>& rx, bool timed,
                     const std::string& out_dir, SimulateReport& rep, DtmfScores& s) {
  const double thr = d.scene.decoder.ghost_threshold, rate = d.fs;
  auto lat_csv = fmt::output_file((fs::path(out_dir) / "latency.csv").string());
  lat_csv.print("taxel,onset_ms,fpga_us,golden_us\n");
  for (const sim::Press& pr : d.scene.presses) {
    if (pr.at_position) continue;
    const int idx = pr.row * d.C + pr.col;
    const size_t onset = size_t(std::ceil(pr.t_start_s * rate));
    PressLatency l{rep.taxel_labels[size_t(idx)], pr.t_start_s * 1000.0, -1, -1};
    for (const FpgaFrame& f : rx)
      if (f.p.type == link::kTaxelsDense && f.p.t >= onset && int(f.p.taxels.size()) == d.T &&
          f.p.taxels[size_t(idx)] / 32768.0 > thr) {
        if (timed) l.fpga_us = f.arrival_us - pr.t_start_s * 1e6;
        break;
      }
    for (size_t n = onset; n < d.gold.frames.size(); ++n) {
      const golden::Frame& g = d.gold.frames[n];
      if (g.pressure.size() && d.skin.conductance.g(g.pressure(pr.row, pr.col)) > thr) {
        l.golden_us = (double(n) + 1) / rate * 1e6 - pr.t_start_s * 1e6;
        break;
      }
    }
    if (l.fpga_us >= 0) s.fpga_lat.push_back(l.fpga_us);
    lat_csv.print("{},{:.4f},{:.2f},{:.2f}\n", l.taxel, l.onset_ms, l.fpga_us, l.golden_us);
    rep.latency.push_back(l);
  }
}

// Errors against the truth, FPGA and golden.
void error_rows(const DtmfRun& d, const golden::DecodeScore& fs_, const DtmfScores& s,
                SimulateReport& rep) {
  const golden::DecodeScore& gs = d.gold.score;
  rep.error_head = {"model", "frames scored", "worst taxel RMS error (kPa)", "worst max error (kPa)",
                    "ghost taxel-frames", "missed taxel-frames", "spikes: receptors / layer 2"};
  rep.error_rows = {
      {"FPGA (virtual board)", std::to_string(fs_.steady_frames), ms(fs_.worst_rms_error_kpa()),
       ms(fs_.worst_max_error_kpa()), std::to_string(fs_.ghost_taxel_frames),
       std::to_string(fs_.missed_taxel_frames), fmt::format("{} / {}", s.fspk.t_ms.size(), s.fspk2)},
      {"golden", std::to_string(gs.steady_frames), ms(gs.worst_rms_error_kpa()),
       ms(gs.worst_max_error_kpa()), std::to_string(gs.ghost_taxel_frames),
       std::to_string(gs.missed_taxel_frames),
       fmt::format("{} / {} ({} / {} at the scene's neuron step)", s.gspk.t_ms.size(), s.gspk2,
                   d.gold.scene_step_spikes, d.gold.scene_step_spikes2)}};
}

// The run's figures from the board's done line.
struct DtmfRunFigures {
  double sim_s, cpu_s, wall_s, cyc, lat_med;
  uint64_t link_errors;
};

DtmfRunFigures run_figures(const stream::BoardRun& run, DtmfScores& s) {
  const nlohmann::json& done = run.done;
  const link::DecoderStats& ls = run.link;
  std::sort(s.fpga_lat.begin(), s.fpga_lat.end());
  return {done.at("sim_s"), done.at("cpu_s"), done.at("wall_s"), done.at("cycles"),
          s.fpga_lat.empty() ? -1 : s.fpga_lat[s.fpga_lat.size() / 2],
          ls.crc_errors + ls.framing_errors + ls.payload_errors};
}

// The run's figures: build, speed, link, the FPGA's status, FPGA against
// golden, latency.
void run_rows(const DtmfRun& d, const stream::BoardRun& run, size_t packets, const DtmfScores& s,
              const DtmfRunFigures& r, SimulateReport& rep) {
  const link::DecoderStats& ls = run.link;
  const link::StatusBlock& st = s.last_status;
  const std::string& level = d.level;
  rep.run_rows = {
      {"fidelity level (eskin simulate --fidelity)", level},
      {"FPGA build", d.build.key},
      {"simulated time (s)", fmt::format("{:.4f}", r.sim_s)},
      {"FPGA cycles", fmt::format("{:.0f}", r.cyc)},
      {"speed: simulated s per CPU s (board process)", fmt::format("{:.3f}", r.sim_s / r.cpu_s)},
      {"speed: simulated s per wall s", fmt::format("{:.3f}", r.sim_s / r.wall_s)},
      {"speed: FPGA cycles per CPU s", fmt::format("{:.3g}", r.cyc / r.cpu_s)},
      {"packets received", std::to_string(packets)},
      {"link: bytes / CRC errors / framing errors / lost packets",
       fmt::format("{} / {} / {} / {}", ls.bytes, ls.crc_errors, ls.framing_errors, ls.lost_packets)},
      {"ADC timing violations",
       run.done.contains("adc_violations")
           ? std::to_string(run.done.at("adc_violations").get<uint64_t>())
           : "not modelled at the " + level + " level"},
      {"FPGA status: ADC overruns / frame overruns / dropped packets / spikes dropped / UART rx "
       "errors / commands accepted",
       s.status_n ? fmt::format("{} / {} / {} / {} / {} / {}", st.adc_overruns, st.frame_overruns,
                                st.dropped_frames, st.spikes_dropped, st.uart_rx_errors,
                                st.cmd_accepted)
                  : std::string("no status packet")},
      {"FPGA vs golden: max carrier amplitude difference (LSB peak)", fmt::format("{:.3f}", s.amp_err)},
      {"FPGA vs golden (both ghost-corrected): taxel max / RMS difference (kPa)",
       fmt::format("{:.3f} / {:.3f}", s.kpa_err, s.kpa_n ? std::sqrt(s.kpa_sq / double(s.kpa_n)) : 0.0)},
      {"latency onset -> first FPGA frame on the host, median (us)", fmt::format("{:.1f}", r.lat_med)}};
}

// The report's opening paragraph: the skin, the FPGA build, the golden model.
std::string summary_text(const DtmfRun& d, size_t total) {
  const vboard::FpgaBuild& b = d.build;
  const DftVariant golden_variant = golden::resolve_variant(
      d.scene.decoder.variant, d.skin.carrier_freqs_hz(), d.fs, d.scene.decoder);
  return fmt::format(
      "{}x{} skin, {} carriers, {} samples at {} Hz; FPGA build {} at {:.0f} MHz ({} shifter, "
      "neurons on the {}), UART {:.0f} "
      "baud (exact sliding DFT{}, ghost filter, frames and neuron steps every {} samples); golden "
      "model: variant {}, ghost-corrected, neurons stepped every {} samples like the FPGA.",
      d.R, d.C, d.K, total, d.fs, b.key, b.clk_hz() / 1e6, fpga::shifter_name(engine_of(b)),
      b.plan.spec.neuron_unit ? "neuron unit" : "frame engine", b.baud(),
      b.plan.spec.demix ? " + least-squares demixing" : "", b.plan.step,
      to_string(golden_variant), b.plan.step);
}

// summary.json's contents.
nlohmann::json summary(const DtmfRun& d, const std::string& scene_file, size_t packets,
                       const golden::DecodeScore& fs_, const DtmfScores& s, const DtmfRunFigures& r) {
  const vboard::FpgaBuild& b = d.build;
  const link::StatusBlock& st = s.last_status;
  return {{"scene", scene_file}, {"fidelity", d.level}, {"fpga_build", b.key},
          {"fpga_clk_hz", b.clk_hz()},
          {"fpga_engine_shifter", fpga::shifter_name(engine_of(b))},
          {"fpga_neurons", fpga::neurons_name(engine_of(b))}, {"sim_s", r.sim_s},
          {"cpu_s", r.cpu_s}, {"wall_s", r.wall_s}, {"cycles", r.cyc},
          {"packets", packets}, {"link_errors", r.link_errors},
          {"fpga_worst_rms_kpa", fs_.worst_rms_error_kpa()},
          {"golden_worst_rms_kpa", d.gold.score.worst_rms_error_kpa()},
          {"fpga_vs_golden_max_amp_lsb", s.amp_err}, {"fpga_spikes", s.fspk.t_ms.size()},
          {"golden_spikes", s.gspk.t_ms.size()}, {"fpga_spikes_layer2", s.fspk2},
          {"golden_spikes_layer2", s.gspk2},
          {"golden_spikes_scene_step", d.gold.scene_step_spikes},
          {"golden_spikes_layer2_scene_step", d.gold.scene_step_spikes2},
          {"latency_median_us", r.lat_med},
          {"status_packets", s.status_n},
          {"adc_overruns", st.adc_overruns},
          {"frame_overruns", st.frame_overruns},
          {"dropped_packets", st.dropped_frames}};
}

// The summary on stdout.
void print_summary(const DtmfRun& d, size_t packets, const golden::DecodeScore& fs_,
                   const DtmfScores& s, const DtmfRunFigures& r, const std::string& html) {
  const golden::DecodeScore& gs = d.gold.score;
  fmt::print("scene {}: {}x{} skin, {:.3f} s simulated on the virtual board (FPGA build {}, {} "
             "level) in {:.1f} s ({:.2f} simulated s per CPU s)\n",
             d.scene.name, d.R, d.C, r.sim_s, d.build.key, d.level, r.wall_s, r.sim_s / r.cpu_s);
  fmt::print("FPGA: {} packets, {} link errors; worst taxel RMS error {:.3f} kPa; spikes {} "
             "receptor, {} layer 2\n",
             packets, r.link_errors, fs_.worst_rms_error_kpa(), s.fspk.t_ms.size(), s.fspk2);
  fmt::print("golden: worst taxel RMS error {:.3f} kPa; spikes {} receptor, {} layer 2 with "
             "the FPGA's neuron step ({} / {} at the scene's)\n",
             gs.worst_rms_error_kpa(), s.gspk.t_ms.size(), s.gspk2, d.gold.scene_step_spikes,
             d.gold.scene_step_spikes2);
  if (s.last_status.frame_overruns > 0)
    fmt::print("FPGA: {} frames skipped: the frame engine needs more clocks per frame than {:.0f} "
               "MHz gives (docs/fpga.md, cycle budget)\n",
               s.last_status.frame_overruns, d.build.clk_hz() / 1e6);
  if (r.lat_med >= 0)
    fmt::print("latency touch onset -> first FPGA frame on the host: median {:.0f} us over {} presses\n",
               r.lat_med, s.fpga_lat.size());
  fmt::print("report: {}\n", html);
}

}  // namespace

fpga::EngineVariant engine_of(const vboard::FpgaBuild& b) {
  return {b.plan.spec.engine_fast_shift, b.plan.spec.neuron_unit};
}

nlohmann::json report_dtmf(const sim::Scene& scene, const std::string& scene_file,
                           const vboard::FpgaBuild& build, const GoldenRun& gold,
                           const stream::BoardRun& run, size_t total, const std::string& out_dir) {
  fs::create_directories(out_dir);
  const SkinConfig& skin = scene.skin;
  const DtmfRun d{scene, skin, build, gold, skin.adc.rate_hz, skin.rows, skin.cols,
                  skin.rows * skin.cols, skin.carriers(), run.done.at("fidelity")};
  std::vector<FpgaFrame> rx;
  for (size_t i = 0; i < run.rx.size(); ++i)
    if (!link::is_hall_packet(run.rx[i].type)) rx.push_back({run.rx[i], run.arrival_us[i]});
  // Amplitude packets: window sums of 12-bit codes >> mag_shift; in the
  // scene's ADC LSB (peak), like golden's amp_lsb.
  const double amp_scale =
      std::ldexp(1.0, build.plan.mag_shift - build.adc_shift()) / (build.plan.N / 2.0);
  SimulateReport rep;
  init_report(d, scene_file, rep);
  DtmfScores s;
  golden::DecodeScore fs_;
  {
    DtmfFiles out = open_files(d, rep, out_dir);
    fs_ = score_packets(d, rx, amp_scale, out, rep, s);
  }
  spikes_section(d, out_dir, rep, s);
  latency_section(d, rx, run.timed, out_dir, rep, s);
  error_rows(d, fs_, s, rep);
  const DtmfRunFigures r = run_figures(run, s);
  run_rows(d, run, rx.size(), s, r, rep);
  rep.run_rows.insert(rep.run_rows.end(), run.line_rows.begin(), run.line_rows.end());
  rep.summary = summary_text(d, total);
  const std::string html = (fs::path(out_dir) / "report.html").string();
  write_simulate_report(rep, html);
  nlohmann::json sum = summary(d, scene_file, rx.size(), fs_, s, r);
  if (!run.line.is_null()) sum["line"] = run.line;
  if (!run.board_faults.is_null()) sum["board_faults"] = run.board_faults;
  fmt::output_file((fs::path(out_dir) / "summary.json").string()).print("{}\n", sum.dump(2));
  print_summary(d, rx.size(), fs_, s, r, html);
  return sum;
}

}  // namespace eskin::report
