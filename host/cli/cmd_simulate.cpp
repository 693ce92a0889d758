// eskin simulate SCENE.yaml [--out DIR] [--trace F.fst]: the scene on the
// SystemC virtual board (sim/vboard/), read over its serial port (a pty)
// like a real board; the golden model on the same samples; both scored
// against the scene's ground truth; one self-contained HTML report plus
// the raw outputs (docs/vboard.md).
#include <unistd.h>

#include <fmt/format.h>
#include <fmt/os.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <thread>

#include "cli/board_link.h"
#include "cli/command.h"
#include "cli/csv_fields.h"
#include "cli/progress.h"
#include "cli/simulate_hall.h"
#include "host/golden/decode_score.h"
#include "host/golden/golden_decoder.h"
#include "host/golden/sdft_bank.h"
#include "host/fpga/board.h"
#include "host/fpga/flow.h"
#include "host/fpga/scale_table.h"
#include "host/link/link_decoder.h"
#include "host/link/link_encoder.h"
#include "host/report/html_page.h"
#include "host/report/simulate_report.h"
#include "host/stream/link_stream.h"
#include "sim/scene.h"
#include "sim/vboard/fpga_params.h"
#include "sim/vboard/mixed_build.h"
#include "sim/vboard/vboard_build.h"
#include "sim/vboard/vboard_process.h"
#include "sim/world_model.h"

namespace eskin::cli {
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

// The build's frame engine, as `eskin bitstream --engine-shifter` and
// `--neurons` name it.
fpga::EngineVariant engine_of(const vboard::FpgaBuild& b) {
  return {b.plan.spec.engine_fast_shift, b.plan.spec.neuron_unit};
}

struct Args {
  std::string scene, out = "eskin-out", trace;
};

struct FpgaFrame {  // a packet with its arrival at the host
  Packet p;
  double arrival_us = -1;
};

struct GoldenRun {
  std::vector<golden::Frame> frames;  // by sample index (empty before the window fills)
  // Spikes of the receptors and the second layer, neurons stepped like the
  // FPGA's (once per frame); and the receptors' count at the scene's own
  // neuron step (neuron.dt_ms, one sample by default).
  std::vector<std::vector<double>> spikes_ms, spikes2_ms;
  size_t scene_step_spikes = 0, scene_step_spikes2 = 0;
  golden::DecodeScore score;
};

// The golden model on the scene as written: frames at the scene's hop
// (every sample by default), neurons at its neuron.dt_ms. The FPGA steps
// its neurons once per frame (every `fpga_step` samples), a coarser Euler
// step that fires differently near threshold; a second run framed and
// stepped like it gives the spikes the FPGA's are compared with.
GoldenRun run_golden(const sim::Scene& scene, int fpga_step) {
  GoldenRun g;
  golden::GoldenOptions opt;
  opt.taxels = true;
  opt.spikes = scene.outputs.spikes;
  golden::GoldenDecoder dec(scene.skin, scene.decoder, scene.neuron, opt);
  sim::WorldModel world(scene), truth(scene);
  golden::DecodeScorer scorer(scene.skin, scene.decoder,
                              [&truth](size_t n, std::vector<double>& p) { truth.pressure_at(n, p); });
  g.frames.resize(world.total_samples());
  int code = 0;
  for (size_t n = 0; world.next(code); ++n)
    if (dec.push(code)) {
      g.frames[n] = dec.frame();
      scorer.add(dec.frame());
    }
  g.score = scorer.score();
  if (scene.outputs.spikes) {
    for (const auto& v : dec.spike_times_ms()) g.scene_step_spikes += v.size();
    for (const auto& v : dec.spike_times2_ms()) g.scene_step_spikes2 += v.size();
    DecoderConfig d = scene.decoder;
    d.hop = fpga_step;
    NeuronConfig n = scene.neuron;
    n.dt_ms = 1000.0 * fpga_step / scene.skin.adc.rate_hz;
    golden::GoldenOptions so;
    so.taxels = so.spikes = true;
    golden::GoldenDecoder sd(scene.skin, d, n, so);
    sim::WorldModel w(scene);
    for (int c = 0; w.next(c);) sd.push(c);
    g.spikes_ms = sd.spike_times_ms();
    g.spikes2_ms = sd.spike_times2_ms();
  }
  return g;
}

std::string ms(double v) { return fmt::format("{:.3f}", v); }

// The DTMF skin's packets of a board run (`run.rx`, other types ignored),
// scored against the truth and the golden model: report.html, CSVs,
// fpga_packets.ndjson and summary.json in `out_dir`; a summary on stdout.
// Returns summary.json's contents.
nlohmann::json report_dtmf(const sim::Scene& scene, const std::string& scene_file,
                           const vboard::FpgaBuild& build, const GoldenRun& gold,
                           const BoardRun& run, size_t total, const std::string& out_dir) {
  std::filesystem::create_directories(out_dir);
  const SkinConfig& skin = scene.skin;
  const double fs = skin.adc.rate_hz;
  const int R = skin.rows, C = skin.cols, T = R * C, K = skin.carriers();
  const nlohmann::json& done = run.done;
  const link::DecoderStats& ls = run.link;
  const bool timed = run.timed;
  std::vector<FpgaFrame> rx;
  for (size_t i = 0; i < run.rx.size(); ++i)
    if (!link::is_hall_packet(run.rx[i].type)) rx.push_back({run.rx[i], run.arrival_us[i]});
  // ---- FPGA frames in physical units, scored like the golden model's.
  sim::WorldModel truth_world(scene);
  golden::DecodeScorer fpga_scorer(skin, scene.decoder, [&](size_t n, std::vector<double>& p) {
    truth_world.pressure_at(n, p);
  });
  // Amplitude packets: window sums of 12-bit codes >> mag_shift; in the
  // scene's ADC LSB (peak), like golden's amp_lsb.
  const double amp_scale =
      std::ldexp(1.0, build.plan.mag_shift - build.adc_shift()) / (build.plan.N / 2.0);
  report::SimulateReport rep;
  rep.title = "eskin simulate: " + scene.name;
  rep.scene_file = scene_file;
  for (int i = 0; i < R; ++i)
    for (int j = 0; j < C; ++j) rep.taxel_labels.push_back(fmt::format("r{}c{}", i, j));
  const auto freqs = skin.carrier_freqs_hz();
  for (int k = 0; k < K; ++k) {
    rep.carrier_labels.push_back(fmt::format("{} {} Hz", k < R ? "row" : "col", freqs[size_t(k)]));
    rep.fpga_amp.push_back({"FPGA " + rep.carrier_labels.back(), {}, {}});
    rep.golden_amp.push_back({"golden " + rep.carrier_labels.back(), {}, {}});
  }
  rep.fpga_kpa.assign(size_t(T), {});
  rep.golden_kpa.assign(size_t(T), {});
  rep.truth_kpa.assign(size_t(T), {});
  report::SpikeTrain fspk{"FPGA", {}, {}}, gspk{"golden", {}, {}};
  auto amp_csv = fmt::output_file((std::filesystem::path(out_dir) / "fpga_amplitudes.csv").string());
  auto tax_csv = fmt::output_file((std::filesystem::path(out_dir) / "fpga_taxels.csv").string());
  auto nd = fmt::output_file((std::filesystem::path(out_dir) / "fpga_packets.ndjson").string());
  amp_csv.print("sample,t_ms,arrival_us");
  for (double f : freqs) amp_csv.print(",amp_{}hz", f);
  tax_csv.print("sample,t_ms,arrival_us");
  for (const auto& l : rep.taxel_labels) tax_csv.print(",{}_kpa,{}_golden_kpa,{}_truth_kpa", l, l, l);
  amp_csv.print("\n");
  tax_csv.print("\n");
  double amp_err = 0, kpa_err = 0, kpa_sq = 0;
  size_t kpa_n = 0, status_n = 0, fspk2 = 0;
  link::StatusBlock last_status;
  std::vector<double> truth;
  for (const FpgaFrame& f : rx) {
    const Packet& p = f.p;
    const double t_ms = 1000.0 * p.t / fs;
    const golden::Frame* g = p.t < gold.frames.size() && gold.frames[p.t].amp_lsb.size()
                                 ? &gold.frames[p.t] : nullptr;
    if (p.type == link::kAmplitudes && int(p.amplitudes.size()) == K) {
      amp_csv.print("{},{:.4f},{:.2f}", p.t, t_ms, f.arrival_us);
      std::string vals;
      for (int k = 0; k < K; ++k) {
        const double v = p.amplitudes[size_t(k)] * amp_scale;
        amp_csv.print(",{:.6g}", v);
        vals += fmt::format("{}{:.6g}", k ? "," : "", v);
        rep.fpga_amp[size_t(k)].t_ms.push_back(t_ms);
        rep.fpga_amp[size_t(k)].value.push_back(v);
        if (g) {
          rep.golden_amp[size_t(k)].t_ms.push_back(t_ms);
          rep.golden_amp[size_t(k)].value.push_back(g->amp_lsb[k]);
          amp_err = std::max(amp_err, std::fabs(v - g->amp_lsb[k]));
        }
      }
      amp_csv.print("\n");
      nd.print("{{\"type\":\"amplitudes\",\"sample\":{},\"t_ms\":{:.4f},\"arrival_us\":{:.2f},\"amp_lsb\":[{}]}}\n",
               p.t, t_ms, f.arrival_us, vals);
    } else if (p.type == link::kTaxelsDense && int(p.taxels.size()) == T) {
      golden::Frame ff;
      ff.sample = p.t;
      ff.pressure.resize(R, C);
      for (int i = 0; i < T; ++i)
        ff.pressure(i / C, i % C) = skin.conductance.inverse(p.taxels[size_t(i)] / 32768.0);
      ff.pressure_raw = ff.pressure;
      fpga_scorer.add(ff);
      truth_world.pressure_at(p.t, truth);
      rep.frame_t_ms.push_back(t_ms);
      tax_csv.print("{},{:.4f},{:.2f}", p.t, t_ms, f.arrival_us);
      for (int i = 0; i < T; ++i) {
        const double v = ff.pressure(i / C, i % C);
        const double gv = g ? g->pressure(i / C, i % C) : 0;
        rep.fpga_kpa[size_t(i)].push_back(v);
        rep.golden_kpa[size_t(i)].push_back(gv);
        rep.truth_kpa[size_t(i)].push_back(truth[size_t(i)]);
        rep.kpa_max = std::max({rep.kpa_max, truth[size_t(i)], v});
        tax_csv.print(",{:.6g},{:.6g},{:.6g}", v, gv, truth[size_t(i)]);
        if (g) {
          const double d = v - gv;  // both ghost-corrected
          kpa_err = std::max(kpa_err, std::fabs(d));
          kpa_sq += d * d;
          ++kpa_n;
        }
      }
      tax_csv.print("\n");
      nd.print("{{\"type\":\"taxels\",\"sample\":{},\"t_ms\":{:.4f},\"arrival_us\":{:.2f},\"pressure_kpa\":[{}]}}\n",
               p.t, t_ms, f.arrival_us, join(ff.pressure));
    } else if (p.type == link::kSpikes) {
      for (const auto& s : p.spikes) {
        const double ts = 1000.0 * (p.t + s.dt) / fs;
        nd.print("{{\"type\":\"spike\",\"t_ms\":{:.4f},\"layer\":{},\"taxel\":{},\"arrival_us\":{:.2f}}}\n",
                 ts, s.layer, s.neuron, f.arrival_us);
        if (s.layer != 0) {  // the raster shows the receptors; layer 1 is counted
          ++fspk2;
          continue;
        }
        fspk.t_ms.push_back(ts);
        fspk.taxel.push_back(s.neuron);
      }
    } else if (p.type == link::kStatus) {
      ++status_n;
      last_status = p.status;
    }
  }
  for (size_t t = 0; t < gold.spikes_ms.size(); ++t)
    for (double ts : gold.spikes_ms[t]) {
      gspk.t_ms.push_back(ts);
      gspk.taxel.push_back(int(t));
    }
  size_t gspk2 = 0;
  for (const auto& v : gold.spikes2_ms) gspk2 += v.size();
  rep.spikes = {fspk, gspk};
  {
    auto s_csv = fmt::output_file((std::filesystem::path(out_dir) / "spikes.csv").string());
    s_csv.print("model,t_ms,taxel,row,col\n");
    for (const auto* tr : {&fspk, &gspk})
      for (size_t i = 0; i < tr->t_ms.size(); ++i)
        s_csv.print("{},{:.4f},{},{},{}\n", tr->label, tr->t_ms[i], tr->taxel[i], tr->taxel[i] / C,
                    tr->taxel[i] % C);
  }

  // ---- latency: touch onset (truth) -> first frame with the taxel lit.
  const double thr = scene.decoder.ghost_threshold;
  auto lat_csv = fmt::output_file((std::filesystem::path(out_dir) / "latency.csv").string());
  lat_csv.print("taxel,onset_ms,fpga_us,golden_us\n");
  std::vector<double> fpga_lat;
  for (const sim::Press& pr : scene.presses) {
    if (pr.at_position) continue;
    const int idx = pr.row * C + pr.col;
    const size_t onset = size_t(std::ceil(pr.t_start_s * fs));
    report::PressLatency l{rep.taxel_labels[size_t(idx)], pr.t_start_s * 1000.0, -1, -1};
    for (const FpgaFrame& f : rx)
      if (f.p.type == link::kTaxelsDense && f.p.t >= onset && int(f.p.taxels.size()) == T &&
          f.p.taxels[size_t(idx)] / 32768.0 > thr) {
        if (timed) l.fpga_us = f.arrival_us - pr.t_start_s * 1e6;
        break;
      }
    for (size_t n = onset; n < gold.frames.size(); ++n) {
      const golden::Frame& g = gold.frames[n];
      if (g.pressure.size() && skin.conductance.g(g.pressure(pr.row, pr.col)) > thr) {
        l.golden_us = (double(n) + 1) / fs * 1e6 - pr.t_start_s * 1e6;
        break;
      }
    }
    if (l.fpga_us >= 0) fpga_lat.push_back(l.fpga_us);
    lat_csv.print("{},{:.4f},{:.2f},{:.2f}\n", l.taxel, l.onset_ms, l.fpga_us, l.golden_us);
    rep.latency.push_back(l);
  }

  // ---- error summary and run figures.
  const golden::DecodeScore fs_ = fpga_scorer.score(), gs = gold.score;
  rep.error_head = {"model", "frames scored", "worst taxel RMS error (kPa)", "worst max error (kPa)",
                    "ghost taxel-frames", "missed taxel-frames", "spikes: receptors / layer 2"};
  rep.error_rows = {
      {"FPGA (virtual board)", std::to_string(fs_.steady_frames), ms(fs_.worst_rms_error_kpa()),
       ms(fs_.worst_max_error_kpa()), std::to_string(fs_.ghost_taxel_frames),
       std::to_string(fs_.missed_taxel_frames), fmt::format("{} / {}", fspk.t_ms.size(), fspk2)},
      {"golden", std::to_string(gs.steady_frames), ms(gs.worst_rms_error_kpa()),
       ms(gs.worst_max_error_kpa()), std::to_string(gs.ghost_taxel_frames),
       std::to_string(gs.missed_taxel_frames),
       fmt::format("{} / {} ({} / {} at the scene's neuron step)", gspk.t_ms.size(), gspk2,
                   gold.scene_step_spikes, gold.scene_step_spikes2)}};
  const double sim_s = done.at("sim_s"), cpu_s = done.at("cpu_s"), wall_s = done.at("wall_s");
  const double cyc = done.at("cycles");
  std::sort(fpga_lat.begin(), fpga_lat.end());
  const double lat_med = fpga_lat.empty() ? -1 : fpga_lat[fpga_lat.size() / 2];
  rep.run_rows = {
      {"FPGA build", build.key},
      {"simulated time (s)", fmt::format("{:.4f}", sim_s)},
      {"FPGA cycles", fmt::format("{:.0f}", cyc)},
      {"speed: simulated s per CPU s (board process)", fmt::format("{:.3f}", sim_s / cpu_s)},
      {"speed: simulated s per wall s", fmt::format("{:.3f}", sim_s / wall_s)},
      {"speed: FPGA cycles per CPU s", fmt::format("{:.3g}", cyc / cpu_s)},
      {"packets received", std::to_string(rx.size())},
      {"link: bytes / CRC errors / framing errors / lost packets",
       fmt::format("{} / {} / {} / {}", ls.bytes, ls.crc_errors, ls.framing_errors, ls.lost_packets)},
      {"ADC timing violations", std::to_string(done.at("adc_violations").get<uint64_t>())},
      {"FPGA status: ADC overruns / frame overruns / dropped packets / spikes dropped / UART rx "
       "errors / commands accepted",
       status_n ? fmt::format("{} / {} / {} / {} / {} / {}", last_status.adc_overruns,
                              last_status.frame_overruns, last_status.dropped_frames,
                              last_status.spikes_dropped, last_status.uart_rx_errors,
                              last_status.cmd_accepted)
                : std::string("no status packet")},
      {"FPGA vs golden: max carrier amplitude difference (LSB peak)", fmt::format("{:.3f}", amp_err)},
      {"FPGA vs golden (both ghost-corrected): taxel max / RMS difference (kPa)",
       fmt::format("{:.3f} / {:.3f}", kpa_err, kpa_n ? std::sqrt(kpa_sq / double(kpa_n)) : 0.0)},
      {"latency onset -> first FPGA frame on the host, median (us)", fmt::format("{:.1f}", lat_med)}};
  const DftVariant golden_variant = golden::resolve_variant(
      scene.decoder.variant, skin.carrier_freqs_hz(), fs, scene.decoder);
  rep.summary = fmt::format(
      "{}x{} skin, {} carriers, {} samples at {} Hz; FPGA build {} at {:.0f} MHz ({} shifter, "
      "neurons on the {}), UART {:.0f} "
      "baud (exact sliding DFT{}, ghost filter, frames and neuron steps every {} samples); golden "
      "model: variant {}, ghost-corrected, neurons stepped every {} samples like the FPGA.",
      R, C, K, total, fs, build.key, build.clk_hz() / 1e6, fpga::shifter_name(engine_of(build)),
      build.plan.spec.neuron_unit ? "neuron unit" : "frame engine", build.baud(),
      build.plan.spec.demix ? " + least-squares demixing" : "", build.plan.step,
      to_string(golden_variant), build.plan.step);
  const std::string html = (std::filesystem::path(out_dir) / "report.html").string();
  report::write_simulate_report(rep, html);
  nlohmann::json summary;
  {
    nlohmann::json sum = {{"scene", scene_file}, {"fpga_build", build.key},
                          {"fpga_clk_hz", build.clk_hz()},
                          {"fpga_engine_shifter", fpga::shifter_name(engine_of(build))},
                          {"fpga_neurons", fpga::neurons_name(engine_of(build))}, {"sim_s", sim_s},
                          {"cpu_s", cpu_s}, {"wall_s", wall_s}, {"cycles", cyc},
                          {"packets", rx.size()}, {"link_errors", ls.crc_errors + ls.framing_errors + ls.payload_errors},
                          {"fpga_worst_rms_kpa", fs_.worst_rms_error_kpa()},
                          {"golden_worst_rms_kpa", gs.worst_rms_error_kpa()},
                          {"fpga_vs_golden_max_amp_lsb", amp_err}, {"fpga_spikes", fspk.t_ms.size()},
                          {"golden_spikes", gspk.t_ms.size()}, {"fpga_spikes_layer2", fspk2},
                          {"golden_spikes_layer2", gspk2},
                          {"golden_spikes_scene_step", gold.scene_step_spikes},
                          {"golden_spikes_layer2_scene_step", gold.scene_step_spikes2},
                          {"latency_median_us", lat_med},
                          {"status_packets", status_n},
                          {"adc_overruns", last_status.adc_overruns},
                          {"frame_overruns", last_status.frame_overruns},
                          {"dropped_packets", last_status.dropped_frames}};
    auto js = fmt::output_file((std::filesystem::path(out_dir) / "summary.json").string());
    js.print("{}\n", sum.dump(2));
    summary = sum;
  }
  fmt::print("scene {}: {}x{} skin, {:.3f} s simulated on the virtual board (FPGA build {}) in "
             "{:.1f} s ({:.2f} simulated s per CPU s)\n",
             scene.name, R, C, sim_s, build.key, wall_s, sim_s / cpu_s);
  fmt::print("FPGA: {} packets, {} link errors; worst taxel RMS error {:.3f} kPa; spikes {} "
             "receptor, {} layer 2\n",
             rx.size(), ls.crc_errors + ls.framing_errors + ls.payload_errors,
             fs_.worst_rms_error_kpa(), fspk.t_ms.size(), fspk2);
  fmt::print("golden: worst taxel RMS error {:.3f} kPa; spikes {} receptor, {} layer 2 with "
             "the FPGA's neuron step ({} / {} at the scene's)\n",
             gs.worst_rms_error_kpa(), gspk.t_ms.size(), gspk2, gold.scene_step_spikes,
             gold.scene_step_spikes2);
  if (last_status.frame_overruns > 0)
    fmt::print("FPGA: {} frames skipped: the frame engine needs more clocks per frame than {:.0f} "
               "MHz gives (docs/fpga.md, cycle budget)\n",
               last_status.frame_overruns, build.clk_hz() / 1e6);
  if (lat_med >= 0)
    fmt::print("latency touch onset -> first FPGA frame on the host: median {:.0f} us over {} presses\n",
               lat_med, fpga_lat.size());
  fmt::print("report: {}\n", html);
  return summary;
}

void note(const std::string& m) { fmt::print(stderr, "eskin simulate: {}\n", m); }

// The skin's outputs (amplitudes, taxels, spikes as the scene asks) plus
// the periodic status, whose counters go into the report.
std::vector<uint8_t> output_mask_command(const sim::Scene& scene, link::LinkEncoder& enc) {
  return enc.set_output_mask(uint8_t((scene.outputs.amplitudes ? 1 : 0) |
                                     (scene.outputs.taxels ? 2 : 0) |
                                     (scene.outputs.spikes ? 4 : 0) | 8));
}

// A scene with both a DTMF skin and Hall sensors: rtl/mixed_top.v on one
// board, both tops' packets on one link. The host configures both (the
// skin's outputs; the Hall decoding's calibration), then scores the skin's
// packets as a DTMF scene's (OUT/skin) and the Hall top's as a Hall
// scene's (OUT/hall); OUT/summary.json and OUT/report.html hold both and the
// shared link's figures.
int run_simulate_mixed(const sim::Scene& scene, const Args& a) {
  const vboard::FpgaBuild dtmf = board_build(scene);
  const vboard::MixedBuild build = vboard::mixed_build_for(scene, dtmf);  // names a bad field
  const HallFpgaSetup setup = hall_simulation_setup(scene, build.hall.spec);
  const std::string exe = vboard::board_executable(build, note);
  std::filesystem::create_directories(a.out);

  link::LinkEncoder enc;
  const std::vector<std::vector<uint8_t>> commands = {output_mask_command(scene, enc),
                                                      setup.commands};
  vboard::VboardProcess board(exe, board_args(a.scene, a.trace, commands));
  const size_t total = board.ready().at("scene_samples");
  GoldenRun gold;
  const BoardRun run = run_board(
      board, int(dtmf.baud()), commands, total,
      [](const Packet& p) { return link::is_hall_packet(p.type) ? -1L : long(p.t); },
      [&] { gold = run_golden(scene, dtmf.plan.step); });

  // Each part's report names the board's build.
  vboard::FpgaBuild skin_build = dtmf;
  skin_build.key = build.key;
  vboard::HallBuild hall_build = build.hall;
  hall_build.key = build.key;
  const std::filesystem::path out(a.out);
  const nlohmann::json skin = report_dtmf(scene, a.scene, skin_build, gold, run, total, (out / "skin").string());
  const nlohmann::json hall = report_hall(scene, a.scene, hall_build, setup, run, (out / "hall").string());

  size_t hall_n = 0;
  for (const Packet& p : run.rx) hall_n += link::is_hall_packet(p.type);
  const link::DecoderStats& ls = run.link;
  const uint64_t link_errors = ls.crc_errors + ls.framing_errors + ls.payload_errors;
  const nlohmann::json sum = {
      {"scene", a.scene}, {"top", "mixed_top"}, {"fpga_build", build.key},
      {"fpga_clk_hz", dtmf.clk_hz()}, {"fpga_engine_shifter", fpga::shifter_name(engine_of(dtmf))},
      {"fpga_neurons", fpga::neurons_name(engine_of(dtmf))}, {"packets", run.rx.size()},
      {"dtmf_packets", run.rx.size() - hall_n}, {"hall_packets", hall_n},
      {"link_errors", link_errors}, {"lost_packets", ls.lost_packets},
      {"skin", skin}, {"hall", hall}};
  fmt::output_file((out / "summary.json").string()).print("{}\n", sum.dump(2));
  report::Page page("eskin simulate: " + scene.name);
  page.text(fmt::format(
      "A DTMF skin and Hall sensors on one FPGA (rtl/mixed_top.v, build {} at {:.0f} MHz): both "
      "tops' packets share one link, numbered by one seq counter. The skin's report is "
      "skin/report.html, the Hall sensors' hall/report.html. Scene file: {}.",
      build.key, dtmf.clk_hz() / 1e6, a.scene));
  page.table({"figure", "value"},
             {{"packets: DTMF / Hall", fmt::format("{} / {}", run.rx.size() - hall_n, hall_n)},
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
                           run.done.at("adc_violations").get<uint64_t>())}});
  page.write((out / "report.html").string());
  fmt::print("mixed board {}: {} DTMF and {} Hall packets on one link, {} link errors, {} lost; "
             "report: {}\n",
             build.key, run.rx.size() - hall_n, hall_n, link_errors, ls.lost_packets,
             (out / "report.html").string());
  return board.wait() == 0 ? 0 : 1;
}

int run_simulate(const Args& a) {
  const sim::Scene scene = sim::load_scene(a.scene);  // a bad scene fails here, before anything runs
  if (scene.has_hall && scene.has_skin) return run_simulate_mixed(scene, a);
  if (scene.has_hall) return run_simulate_hall(scene, a.scene, a.out, a.trace);
  const vboard::FpgaBuild build = board_build(scene);
  const std::string exe = vboard::board_executable(build, note);
  std::filesystem::create_directories(a.out);

  // The board's serial port through the host streaming library
  // (host/stream), packets decoded and checked by host/link. The host
  // configures the board like a host program: the scene's outputs, plus
  // the periodic status (its counters go into the report).
  link::LinkEncoder enc;
  const std::vector<std::vector<uint8_t>> commands = {output_mask_command(scene, enc)};
  vboard::VboardProcess board(exe, board_args(a.scene, a.trace, commands));
  const size_t total = board.ready().at("scene_samples");
  GoldenRun gold;
  const BoardRun run = run_board(
      board, int(build.baud()), commands, total,
      [](const Packet& p) { return long(p.t); },
      [&] { gold = run_golden(scene, build.plan.step); });
  report_dtmf(scene, a.scene, build, gold, run, total, a.out);
  return board.wait() == 0 ? 0 : 1;
}

std::function<int()> setup(CLI::App& app) {
  auto a = std::make_shared<Args>();
  CLI::App* sub = app.add_subcommand(
      "simulate", "Run a scene on the SystemC virtual board (Verilated FPGA, pty serial port), "
                  "compare with the golden model and write an HTML report");
  sub->add_option("scene", a->scene, "scene file (YAML, see docs/scenes.md)")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("--out", a->out, "output directory (created)")->capture_default_str();
  sub->add_option("--trace", a->trace, "FST waveform of the FPGA (GTKWave; several times slower)");
  return [a] { return run_simulate(*a); };
}

ESKIN_COMMAND("simulate", setup);

}  // namespace
}  // namespace eskin::cli
