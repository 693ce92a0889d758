#include "host/bench/tradeoff_run.h"

#include <fmt/format.h>

#include "eskin/process.h"
#include "host/bench/text_file.h"

#include <sys/wait.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

namespace fs = std::filesystem;

namespace eskin::bench {
namespace {

std::string slurp(const fs::path& p) { return eskin::bench::read_text(p.string()); }

std::vector<TradeRow> run_local(const std::vector<TradePoint>& pts, const TradeRunOptions& o) {
  const SynthTable table = read_synth_table(o.synth_table);
  std::vector<TradeRow> rows(pts.size());
  std::vector<std::string> errors(pts.size());
  std::atomic<size_t> next{0};
  const auto worker = [&] {
    for (size_t i; (i = next++) < pts.size();) {
      try {
        rows[i] = evaluate_point(pts[i], table, o.synth_cache);
      } catch (const std::exception& e) {
        errors[i] = pts[i].key() + ": " + e.what();
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < o.threads; ++t) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
  for (const auto& e : errors)
    if (!e.empty()) throw std::runtime_error("tradeoff point " + e);
  return rows;
}

// Rows come back as CSV lines; the numbers are re-read from the CSV so a
// merged Slurm run and a local run go through the same formatting.
TradeRow parse_row(const std::string& line) {
  TradeRow r;
  r.p = parse_point(line);
  std::istringstream s(line);
  std::vector<std::string> f;
  for (std::string x; std::getline(s, x, ',');) f.push_back(x);
  if (f.size() != 28) throw std::invalid_argument("tradeoff row: expected 28 columns in '" + line + "'");
  r.latency_cycles = std::stod(f[9]);
  r.latency_us = std::stod(f[10]);
  r.delay_ms = std::stod(f[11]);
  r.update_hz = std::stod(f[12]);
  r.packet_hz = std::stod(f[13]);
  r.luts = std::stol(f[14]);
  r.dsp = std::stol(f[15]);
  r.bram = std::stol(f[16]);
  r.spram = std::stol(f[17]);
  r.resources = f[18];
  r.amp_err_truth = std::stod(f[19]);
  r.amp_err_golden = std::stod(f[20]);
  r.pressure_err = std::stod(f[21]);
  r.spikes = std::stol(f[22]);
  r.spikes_ref = std::stol(f[23]);
  r.spike_err = std::stod(f[24]);
  r.keeps_up = std::stoi(f[27]);
  return r;
}

std::vector<TradeRow> run_slurm(const std::vector<TradePoint>& pts, const TradeRunOptions& o) {
  const fs::path dir = fs::absolute(o.out_dir), parts = dir / "parts";
  fs::remove_all(parts);
  fs::create_directories(parts);
  const fs::path points = dir / "points.csv";
  {
    std::ofstream f(points);
    for (const auto& p : pts) f << p.key() << "\n";
  }
  // The job script is fixed text: every path and option reaches the task
  // as an argument (sbatch passes the words after the script name to it as
  // "$@"), so no path is ever read by a shell as code. The task writes its
  // row and log into the job's working directory (--chdir: the parts
  // folder), so Slurm's filename patterns (%a) never meet a user's path.
  const fs::path script = dir / "tradeoff.sbatch";
  {
    std::ofstream f(script);
    f << "#!/bin/sh\n"
         "# One point of eskin's trade study per array task (eskin bench tradeoff --slurm).\n"
         "# The command comes as arguments; the row goes to TASK.csv in the working directory.\n"
         "exec \"$@\" --run-point \"$SLURM_ARRAY_TASK_ID\" --part \"$SLURM_ARRAY_TASK_ID.csv\"\n";
    if (!f) throw std::runtime_error(script.string() + ": cannot write the Slurm job script");
  }
  std::vector<std::string> cmd{"sbatch", "--wait", "--parsable", "--job-name=eskin-tradeoff",
                               fmt::format("--array=0-{}", pts.size() - 1),
                               "--chdir=" + parts.string(), "--output=%a.log"};
  // --sbatch-args: options separated by blanks, each given to sbatch as one
  // argument (no shell reads them).
  {
    std::istringstream words(o.sbatch_args);
    for (std::string w; words >> w;) cmd.push_back(w);
  }
  for (const auto& a : {script.string(), o.eskin_bin, std::string("bench"), std::string("tradeoff"),
                        std::string("--points"), points.string()})
    cmd.push_back(a);
  if (!o.synth_table.empty()) cmd.push_back("--synth-table"), cmd.push_back(fs::absolute(o.synth_table).string());
  if (!o.synth_cache.empty()) cmd.push_back("--synth-cache"), cmd.push_back(fs::absolute(o.synth_cache).string());
  const int st = eskin::run_logged(cmd, (dir / "sbatch.out").string());
  if (st == -1)
    throw std::runtime_error("could not run sbatch (" + std::string(std::strerror(errno)) +
                             "): is Slurm installed and on PATH? " + eskin::printable_command(cmd));
  std::vector<TradeRow> rows;
  for (size_t i = 0; i < pts.size(); ++i) {
    const fs::path part = parts / (std::to_string(i) + ".csv");
    std::string line = slurp(part);
    while (!line.empty() && line.back() == '\n') line.pop_back();
    if (line.empty())
      throw std::runtime_error(fmt::format("slurm task {} ({}) wrote no row; sbatch exit {}; see {} "
                                           "and {}", i, pts[i].key(), WIFEXITED(st) ? WEXITSTATUS(st) : -1,
                                           (parts / (std::to_string(i) + ".log")).string(),
                                           (dir / "sbatch.out").string()));
    rows.push_back(parse_row(line));
  }
  return rows;
}

}  // namespace

std::vector<TradeRow> run_tradeoff(const std::vector<TradePoint>& pts, const TradeRunOptions& o) {
  if (pts.empty()) throw std::invalid_argument("tradeoff: no points");
  fs::create_directories(o.out_dir);
  std::vector<TradeRow> rows = o.slurm ? run_slurm(pts, o) : run_local(pts, o);
  if (!o.slurm)  // the same formatting round trip as the Slurm rows
    for (auto& r : rows) r = parse_row(tradeoff_csv_row(r));
  mark_pareto(rows);
  std::ofstream csv(fs::path(o.out_dir) / "tradeoff.csv");
  csv << tradeoff_csv_header() << "\n";
  for (const auto& r : rows) csv << tradeoff_csv_row(r) << "\n";
  if (!csv) throw std::runtime_error(o.out_dir + "/tradeoff.csv: write failed");
  write_tradeoff_report((fs::path(o.out_dir) / "tradeoff.html").string(), rows,
                        fmt::format("eskin trade study: {} points", rows.size()));
  return rows;
}

void run_tradeoff_task(const std::string& points_file, int index, const std::string& part,
                       const TradeRunOptions& o) {
  std::ifstream f(points_file);
  if (!f) throw std::runtime_error(points_file + ": cannot read the points file");
  std::string line;
  for (int i = 0; std::getline(f, line); ++i) {
    if (i != index) continue;
    const TradeRow r = evaluate_point(parse_point(line), read_synth_table(o.synth_table), o.synth_cache);
    std::ofstream out(part);
    out << tradeoff_csv_row(r) << "\n";
    if (!out) throw std::runtime_error(part + ": write failed");
    return;
  }
  throw std::runtime_error(fmt::format("{}: no point {}", points_file, index));
}

}  // namespace eskin::bench
