// eskin bench: the benchmarks (docs/bench.md), one subcommand each.
//   latency     cycle-exact stage latencies (Verilator) against the baseline
//   throughput  samples/s of golden, the fast engine and FFTW, side by side
//   tradeoff    speed/accuracy/resources map (CSV + HTML with Pareto fronts)
//   stability   10^9-sample exact-DFT run, naive/damped drift, neuron extremes
//   scale       golden and engine from 3x3 to 256x256 skins
//   soak        10^6 packets through the virtual board's faulty serial line
//   memory      eskin stream's RSS over 10^7 packets from a pty
//   sim-speed   the virtual board's fidelity levels, simulated s per CPU s
#include <fmt/format.h>
#include <fmt/os.h>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "eskin/source_tree.h"
#include "host/bench/latency.h"
#include "host/bench/scale.h"
#include "host/bench/stability.h"
#include "host/bench/timing.h"
#include "host/bench/throughput.h"
#include "host/bench/tradeoff_run.h"
#include "cli/command.h"
#include "eskin/exit_codes.h"
#include "eskin/skin_config.h"
#include "host/engine/engine_setup.h"
#include "host/simulate/sim_speed.h"
#include "host/simulate/soak.h"
#include "sim/vboard/vboard_build.h"
#include "host/stream/stream_memory.h"
#include "sim/scene.h"

namespace eskin::cli {
namespace {

struct ThroughputArgs {
  std::vector<std::string> scenes;
  double min_seconds = 1.0;
  int threads = int(std::max(1u, std::thread::hardware_concurrency()));
};

// The targets, checked on the rows that carry them.
int run_throughput(const ThroughputArgs& a) {
  std::vector<std::string> scenes = a.scenes;
  if (scenes.empty())
    scenes = {eskin::source_dir() + "/scenes/neuroskin2.yaml",
              eskin::source_dir() + "/scenes/skin32x32.yaml",
              eskin::source_dir() + "/scenes/skin64x64.yaml"};
  std::cout << fmt::format(
      "throughput: best pass of >= {:.1f} s; single-thread rows by thread CPU time, threaded rows "
      "by wall clock beside the same engine on 1 thread\n\n", a.min_seconds);
  for (const auto& path : scenes) {
    const auto r = bench::measure_throughput(path, a.min_seconds, a.threads);
    std::cout << bench::format_throughput(r);
    const auto& amp = r.row("engine-amplitudes");
    const auto& chain = r.row("engine-chain");
    if (r.carriers <= 8)
      std::cout << fmt::format(
          "target: engine amplitudes >= 20x FFTW: {:.2f}x ({}); against fftw-stft-hypot, the "
          "row the first ratios were measured against: {:.2f}x\n",
          amp.vs_fftw, amp.vs_fftw >= 20 ? "met" : "MISSED",
          amp.samples_per_s / r.row("fftw-stft-hypot").samples_per_s);
    std::cout << fmt::format("target: real time on one core at {:.0f} S/s: amplitudes {:.1f}x, "
                             "chain {:.1f}x ({})\n\n", r.fs, amp.samples_per_s / r.fs,
                             chain.samples_per_s / r.fs,
                             std::min(amp.samples_per_s, chain.samples_per_s) >= r.fs ? "met" : "MISSED");
  }
  return 0;
}

struct LatencyArgs {
  bool update = false;
  std::string baseline = eskin::source_dir() + "/bench/baselines/latency.csv";
  std::string cache = eskin::build_dir() + "/bench/latency";
  std::vector<std::string> configs;
  bool ci = false;  // only the builds the CI test measures
};

// Fails (exit 1) naming config, stage and cycles when a latency grew, or a
// stage appeared or vanished; the baseline is rewritten only on request.
int run_latency(const LatencyArgs& a) {
  std::vector<bench::LatencyRun> runs;
  for (const auto& c : bench::latency_configs())
    if ((a.configs.empty() || std::find(a.configs.begin(), a.configs.end(), c.name) != a.configs.end()) &&
        (!a.ci || c.ci))
      runs.push_back(bench::measure_latency(c, a.cache, std::cout));
  if (runs.empty()) throw ConfigError("--config", "no reference build of that name");
  std::cout << "\n" << bench::format_latency(runs) << "\n";
  // The frame engine's instruction-set model (the trade study's latency)
  // must take the clocks Verilator measured for the same frame.
  bool model_ok = true;
  for (const auto& r : runs) {
    if (r.config.top == bench::LatencyConfig::Top::Hall) continue;  // no frame engine
    const bool same = r.model_clocks == r.engine_clocks && r.model_first_byte == r.engine_first_byte;
    model_ok = model_ok && same;
    std::cout << fmt::format("engine model {}: frame {} released after {} clocks, first byte at {}; "
                             "Verilator {} and {} ({})\n",
                             r.config.name, r.sample, r.model_clocks, r.model_first_byte,
                             r.engine_clocks, r.engine_first_byte, same ? "agrees" : "DISAGREES");
  }
  if (!model_ok) return eskin::exit_code(eskin::Exit::failure);
  if (a.update) {
    bench::write_latency_baseline(a.baseline, runs);
    std::cout << "baseline written: " << a.baseline << "\n";
    return 0;
  }
  std::vector<std::string> notes;
  const auto fail = bench::compare_latency(runs, bench::read_latency_baseline(a.baseline), notes);
  for (const auto& n : notes) std::cout << "faster than the baseline: " << n << "\n";
  for (const auto& f : fail) std::cout << "LATENCY REGRESSION: " << f << "\n";
  std::cout << (fail.empty() ? "latency: no stage slower than " : "latency: FAILED against ")
            << a.baseline << "\n";
  return fail.empty() ? 0 : 1;
}

struct TradeArgs {
  bench::TradeRunOptions o;
  bool quick = false, synth = false, write_table = false;
  std::string points;  // array task: points file
  int run_point = -1;
  std::string part;
};

int run_tradeoff(TradeArgs a) {
  if (a.synth && a.o.synth_cache.empty()) a.o.synth_cache = eskin::build_dir() + "/bench/synth";
  if (a.run_point >= 0) {  // one Slurm array task
    if (a.points.empty() || a.part.empty())
      throw ConfigError("--run-point", "needs --points FILE and --part FILE");
    bench::run_tradeoff_task(a.points, a.run_point, a.part, a.o);
    return 0;
  }
  const auto pts = bench::tradeoff_points(a.quick);
  std::cout << fmt::format("tradeoff: {} points ({} sweep), {}\n", pts.size(),
                           a.quick ? "quick" : "full",
                           a.o.slurm ? "as a Slurm job array" : fmt::format("{} threads", a.o.threads));
  const double t0 = bench::wall_seconds();
  const auto rows = bench::run_tradeoff(pts, a.o);
  int front = 0;
  for (const auto& r : rows) front += r.pareto_latency;
  std::cout << fmt::format("{} rows in {:.0f} s: {}/tradeoff.csv, {}/tradeoff.html ({} on the "
                           "error-latency front)\n", rows.size(), bench::wall_seconds() - t0,
                           a.o.out_dir, a.o.out_dir, front);
  if (a.write_table) {
    // This run's builds only: entries of older builds or flows would never match again.
    bench::SynthTable t;
    for (const auto& r : rows)
      if (r.luts >= 0) t[bench::synth_key(r.p)] = {r.luts, r.dsp, r.bram, r.spram};
    bench::write_synth_table(a.o.synth_table, t);
    std::cout << "synthesis table written: " << a.o.synth_table << "\n";
  }
  return 0;
}

struct StabilityArgs {
  double samples = 1e9, neuron_steps = 1e7;
  int checkpoints = 40;
  std::string out = "stability.html";
  std::string scene = eskin::source_dir() + "/scenes/neuroskin2.yaml";
};

int run_stability(const StabilityArgs& a) {
  // The neurons as the top runs them for the scene (both layers' constants).
  const sim::Scene sc = sim::load_scene(a.scene);
  const hls::DtmfTopPlan plan = engine::top_plan(sc.skin, sc.decoder, sc.neuron, true);
  const auto r = bench::run_stability(uint64_t(a.samples), uint64_t(a.neuron_steps), a.checkpoints,
                                      plan.neuron);
  std::cout << bench::format_stability(r);
  bench::write_stability_report(a.out, r);
  std::cout << "report: " << a.out << "\n";
  bool ok = r.recovered;
  for (const auto& d : r.drift) ok = ok && d.exact_lsb == 0;
  for (const auto& e : r.neurons)
    ok = ok && e.in_range && e.note.find("MISSED") == std::string::npos &&
         e.note.find("NOT") == std::string::npos && e.note.find("FIRES") == std::string::npos;
  return ok ? 0 : 1;
}

struct SoakArgs {
  eskin::simulate::SoakOptions o;
  eskin::vboard::LineFaultArgs line;
  std::string csv;
  uint64_t min_packets = 0;
};

struct MemoryArgs {
  eskin::stream::MemoryOptions o;
  std::string csv;
  int64_t max_growth_kib = -1;  // < 0: no bound
};

// Exit 1 when eskin stream failed, a packet was not counted or was lost,
// or RSS grew by more than --max-growth-kib after warm-up.
int run_memory(MemoryArgs a) {
  a.o.eskin_bin = std::filesystem::read_symlink("/proc/self/exe").string();
  const eskin::stream::MemoryResult r = eskin::stream::measure_stream_memory(a.o);
  std::cout << eskin::stream::memory_text(r);
  bool ok = r.delivered_all();
  if (!ok) std::cout << "FAILED: eskin stream did not take every packet once (stderr below)\n"
                     << r.child_stderr;
  if (ok && a.max_growth_kib >= 0 && r.growth_kib() > a.max_growth_kib) {
    std::cout << fmt::format("FAILED: RSS grew {} KiB, more than --max-growth-kib {}\n",
                             r.growth_kib(), a.max_growth_kib);
    ok = false;
  }
  if (!a.csv.empty()) {
    std::string cmd = fmt::format("eskin bench memory --packets {}", a.o.packets);
    if (a.o.hdf5) cmd += " --hdf5";
    fmt::output_file(a.csv).print("{}", eskin::stream::memory_csv(r, cmd));
    std::cout << "table: " << a.csv << "\n";
  }
  return ok ? 0 : eskin::exit_code(eskin::Exit::failure);
}

// Exit 1 when a packet was delivered wrong, the host's count of lost
// packets differs from the packets lost that a host can see (not before
// its first or after its last packet), or fewer than --min-packets were
// sent.
int run_soak(SoakArgs a) {
  if (a.line.ber.empty() && a.line.drop_rate.empty() && a.line.insert_rate.empty() &&
      a.line.pulls.empty())
    a.line.ber = "1e-5";
  a.o.line = eskin::vboard::parse_line_faults(a.line);  // std::invalid_argument: exit 2
  if (a.o.scene.empty()) a.o.scene = eskin::source_dir() + "/scenes/soak.yaml";
  const eskin::simulate::SoakResult r = eskin::simulate::run_soak(a.o);
  std::cout << eskin::simulate::soak_text(r);
  const auto& c = r.line.check;
  const bool ok =
      c.wrong == 0 && r.line.host.lost_packets == c.lost - c.unseen && c.sent >= a.min_packets;
  if (c.sent < a.min_packets)
    std::cout << fmt::format("FAILED: {} packets sent, fewer than --min-packets {}\n", c.sent,
                             a.min_packets);
  if (!a.csv.empty()) {
    std::string scene = a.o.scene;
    const std::string src = eskin::source_dir() + "/";
    if (scene.rfind(src, 0) == 0) scene = scene.substr(src.size());
    std::string cmd = "eskin bench soak " + scene;
    for (const std::string& w : eskin::vboard::line_fault_args(a.o.line)) cmd += " " + w;
    cmd += fmt::format(" --status-requests {}", a.o.status_requests);
    fmt::output_file(a.csv).print("{}", eskin::simulate::soak_csv(r, a.o, cmd));
    std::cout << "table: " << a.csv << "\n";
  }
  return ok ? 0 : eskin::exit_code(eskin::Exit::failure);
}

struct SimSpeedArgs {
  std::vector<std::string> scenes;
  std::vector<std::string> levels{"rtl", "cycle", "packet"};
  std::string out = "eskin-out/sim-speed";
  bool verilator = false;
  std::string csv;
};

// The targets, on the rows that carry them (the default scene's).
int run_sim_speed(const SimSpeedArgs& a) {
  std::vector<std::string> scenes = a.scenes;
  if (scenes.empty())
    for (const char* s : {"neuroskin2", "staggered10x10", "hall_000_skin", "mixed_neuroskin_split"})
      scenes.push_back(eskin::source_dir() + "/scenes/" + s + ".yaml");
  std::vector<simulate::SimSpeedConfig> configs;
  for (const std::string& l : a.levels) {
    const simulate::Fidelity f = simulate::parse_fidelity(l);
    configs.push_back({simulate::fidelity_name(f), f, {}});
    if (a.verilator && f == simulate::Fidelity::rtl)  // beside the product's board
      for (const std::string& v : vboard::verilator_variants())
        configs.push_back({"rtl/" + v, f,
                           {"--board", vboard::variant_executable(v, [](const std::string& m) {
                              std::cerr << "eskin bench sim-speed: " << m << "\n";
                            })},
                           true});
  }
  const std::string self = std::filesystem::canonical("/proc/self/exe").string();
  const auto rows = simulate::measure_sim_speed(self, scenes, configs, a.out);
  std::cout << "sim-speed: each row one `eskin simulate --fidelity LEVEL`, in this one run; CPU s "
               "of the board's own work (summary.json's cpu_s)\n\n"
            << simulate::format_sim_speed(rows);
  if (!a.csv.empty()) {
    std::string cmd = "eskin bench sim-speed";
    if (a.verilator) cmd += " --verilator";
    for (const auto& s : a.scenes) cmd += " " + std::filesystem::path(s).filename().string();
    fmt::output_file(a.csv).print("{}", simulate::sim_speed_csv(rows, cmd));
    std::cout << "table: " << a.csv << "\n";
  }
  for (const auto& r : rows) {
    if (r.ran && r.scene == "neuroskin2" && r.level == "packet")
      std::cout << fmt::format("target: packet level >= 20x real time on the default scene: {:.1f}x ({})\n",
                               r.x_real_time(), r.x_real_time() >= 20 ? "met" : "MISSED");
    if (r.ran && r.scene == "neuroskin2" && r.level == "cycle")
      std::cout << fmt::format("target: cycle level >= 1x real time on the default scene: {:.2f}x ({})\n",
                               r.x_real_time(), r.x_real_time() >= 1 ? "met" : "MISSED");
  }
  return 0;
}

std::function<int()> setup(CLI::App& app) {
  CLI::App* bench = app.add_subcommand(
      "bench",
      "Benchmarks: latency, throughput, tradeoff, stability, scale, soak, memory (docs/bench.md)");
  bench->require_subcommand(1);
  auto l = std::make_shared<LatencyArgs>();
  CLI::App* lat = bench->add_subcommand(
      "latency", "cycle-exact stage latencies of the reference FPGA builds against the baseline");
  lat->add_flag("--update-baseline", l->update, "write the measured latencies as the new baseline");
  lat->add_option("--baseline", l->baseline, "baseline CSV (config,stage,cycles)");
  lat->add_option("--cache", l->cache, "directory of the cached Verilator builds");
  lat->add_option("--config", l->configs, "only these reference builds (3x3, 10x10, 16x16, 64x64, hall000)");
  lat->add_flag("--ci", l->ci, "only the builds CI measures (all but 16x16 and 64x64: their simulations are long)");
  auto d = std::make_shared<TradeArgs>();
  d->o.out_dir = "tradeoff";
  d->o.threads = int(std::max(1u, std::thread::hardware_concurrency()));
  d->o.synth_table = eskin::source_dir() + "/bench/baselines/tradeoff_synth.csv";
  d->o.eskin_bin = std::filesystem::canonical("/proc/self/exe").string();
  CLI::App* tr = bench->add_subcommand(
      "tradeoff", "speed/accuracy/resources sweep: CSV and HTML report with Pareto fronts");
  tr->add_flag("--quick", d->quick, "the small sweep CI runs");
  tr->add_option("--out", d->o.out_dir, "output directory (tradeoff.csv, tradeoff.html)");
  tr->add_option("--threads", d->o.threads, "local worker threads")->check(CLI::Range(1, 256));
  tr->add_flag("--slurm", d->o.slurm, "run the points as a Slurm job array (sbatch --array --wait)");
  tr->add_option("--sbatch-args", d->o.sbatch_args, "extra sbatch arguments, split at blanks, each word one argument (e.g. \"-p PARTITION\")");
  tr->add_flag("--synth", d->synth, "run Yosys for builds not in the synthesis table (cached)");
  tr->add_option("--synth-cache", d->o.synth_cache, "directory of cached Yosys runs");
  tr->add_option("--synth-table", d->o.synth_table, "stored synthesis results (CSV)");
  tr->add_flag("--write-synth-table", d->write_table,
               "add this run's synthesis results to --synth-table");
  tr->add_option("--run-point", d->run_point, "(Slurm array task) evaluate point INDEX only");
  tr->add_option("--points", d->points, "(Slurm array task) the points file");
  tr->add_option("--part", d->part, "(Slurm array task) where to write the row");
  auto st = std::make_shared<StabilityArgs>();
  CLI::App* stab = bench->add_subcommand(
      "stability", "exact sliding DFT over 10^9 worst-case samples, naive/damped drift, neurons "
                   "at their range edges (exit 1 on any mismatch)");
  stab->add_option("--samples", st->samples, "DFT samples (default 1e9)")->check(CLI::Range(64.0, 1e13));
  stab->add_option("--neuron-steps", st->neuron_steps, "steps per extreme-input phase")
      ->check(CLI::Range(1.0, 1e12));
  stab->add_option("--checkpoints", st->checkpoints, "comparisons, spaced geometrically")
      ->check(CLI::Range(1, 10000));
  stab->add_option("--out", st->out, "HTML report");
  stab->add_option("--scene", st->scene, "scene whose top's neuron layers run (default neuroskin2)");
  auto sc = std::make_shared<std::pair<int, double>>(256, 0.5);
  CLI::App* scale = bench->add_subcommand(
      "scale", "golden and the fast engine on 3x3 .. 256x256 skins: samples/s per core, memory");
  scale->add_option("--max-side", sc->first, "largest skin side")->check(CLI::Range(3, 256));
  scale->add_option("--min-seconds", sc->second, "measure each row for at least this long")
      ->check(CLI::PositiveNumber);
  auto t = std::make_shared<ThroughputArgs>();
  CLI::App* tp = bench->add_subcommand(
      "throughput", "samples/s and ns/sample of golden, the fast engine and FFTW, in one run");
  tp->add_option("scenes", t->scenes, "scene files (default: neuroskin2, skin32x32, skin64x64)")
      ->check(CLI::ExistingFile);
  tp->add_option("--min-seconds", t->min_seconds, "measure each row for at least this long")
      ->check(CLI::PositiveNumber);
  tp->add_option("--threads", t->threads, "threads for the threaded engine row")
      ->check(CLI::Range(1, 256));
  auto so = std::make_shared<SoakArgs>();
  CLI::App* soak = bench->add_subcommand(
      "soak", "a long scene through the virtual board's faulty serial line (default BER 1e-5 "
              "both ways): packets sent, delivered, lost, delivered wrong, recoveries (exit 1 on "
              "a packet delivered wrong)");
  soak->add_option("scene", so->o.scene, "DTMF scene of the default build (default scenes/soak.yaml)")
      ->check(CLI::ExistingFile);
  soak->add_option("--ber", so->line.ber, "probability that a wire bit is flipped (default 1e-5)");
  soak->add_option("--drop-rate", so->line.drop_rate, "probability that a character is lost");
  soak->add_option("--insert-rate", so->line.insert_rate,
                   "probability that a random character comes before one");
  soak->add_option("--fault-direction", so->line.direction, "both (default), to-host, to-fpga");
  soak->add_option("--pull-cable", so->line.pulls, "AT_MS:FOR_MS (repeatable)");
  soak->add_option("--fault-seed", so->line.seed, "the seed of every fault (default 1)");
  soak->add_option("--status-requests", so->o.status_requests,
                   "REQUEST_STATUS commands sent per AMPLITUDES packet received")
      ->capture_default_str()
      ->check(CLI::Range(0, 16));
  soak->add_option("--out", so->o.out,
                   "output directory (the FPGA's tapped bytes, soak.json, report.html)")
      ->capture_default_str();
  soak->add_option("--csv", so->csv, "write the table here (docs/soak.csv)");
  soak->add_option("--min-packets", so->min_packets, "fail if the FPGA sent fewer packets");
  auto mem = std::make_shared<MemoryArgs>();
  CLI::App* memory = bench->add_subcommand(
      "memory", "eskin stream's memory (VmRSS) while N packets go through a pty");
  memory->add_option("--packets", mem->o.packets, "packets to stream")->capture_default_str()
      ->check(CLI::PositiveNumber);
  memory->add_flag("--hdf5", mem->o.hdf5, "record --hdf5 while streaming (a temporary file)");
  memory->add_option("--csv", mem->csv, "write the table here (docs/stream_memory.csv)");
  memory->add_option("--max-growth-kib", mem->max_growth_kib,
                     "fail if RSS grows by more than K KiB from the first sample to the end")
      ->check(CLI::NonNegativeNumber);
  auto ss = std::make_shared<SimSpeedArgs>();
  CLI::App* speed = bench->add_subcommand(
      "sim-speed", "simulated s per CPU s of each fidelity level of eskin simulate on each scene, "
                   "side by side in one run");
  speed->add_option("scenes", ss->scenes,
                    "scene files (default: neuroskin2, staggered10x10, hall_000_skin, "
                    "mixed_neuroskin_split)")
      ->check(CLI::ExistingFile);
  speed->add_option("--levels", ss->levels, "fidelity levels, in this order (default: rtl cycle packet)")
      ->delimiter(',');
  speed->add_option("--out", ss->out, "output directory (one eskin simulate output per row)")
      ->capture_default_str();
  speed->add_option("--csv", ss->csv, "write the rows here as CSV");
  speed->add_flag("--verilator", ss->verilator,
                  "also the default board built with each Verilator variant (sim/vboard/"
                  "CMakeLists.txt: built when out of date), on the scenes of the default build");
  return [=]() -> int {
    if (speed->parsed()) return run_sim_speed(*ss);
    if (soak->parsed()) return run_soak(*so);
    if (memory->parsed()) return run_memory(*mem);
    if (lat->parsed()) return run_latency(*l);
    if (tp->parsed()) return run_throughput(*t);
    if (tr->parsed()) return run_tradeoff(*d);
    if (stab->parsed()) return run_stability(*st);
    if (scale->parsed()) {
      std::cout << bench::format_scale(bench::run_scale(sc->first, sc->second));
      return 0;
    }
    return eskin::exit_code(eskin::Exit::failure);
  };
}

ESKIN_COMMAND("bench", setup);

}  // namespace
}  // namespace eskin::cli
