// eskin bench: the benchmarks (docs/bench.md), one subcommand each.
//   throughput  samples/s of golden, the fast engine and FFTW, side by side
#include <fmt/format.h>

#include <iostream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "bench/suite/throughput.h"
#include "cli/command.h"

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
    scenes = {ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml", ESKIN_SOURCE_DIR "/scenes/skin32x32.yaml"};
  std::cout << fmt::format(
      "throughput: best pass of >= {:.1f} s; single-thread rows by thread CPU time, threaded rows "
      "by wall clock beside the same engine on 1 thread\n\n", a.min_seconds);
  for (const auto& path : scenes) {
    const auto r = bench::measure_throughput(path, a.min_seconds, a.threads);
    std::cout << bench::format_throughput(r);
    const auto& amp = r.row("engine-amplitudes");
    if (r.carriers <= 8)
      std::cout << fmt::format("target: engine amplitudes >= 5x FFTW: {:.2f}x ({})\n", amp.vs_fftw,
                               amp.vs_fftw >= 5 ? "met" : "MISSED");
    std::cout << fmt::format("target: real time on one core at {:.0f} S/s: amplitudes {:.1f}x, "
                             "chain {:.1f}x ({})\n\n", r.fs, amp.samples_per_s / r.fs,
                             r.row("engine-chain").samples_per_s / r.fs,
                             amp.samples_per_s >= r.fs ? "met" : "MISSED");
  }
  return 0;
}

std::function<int()> setup(CLI::App& app) {
  CLI::App* bench = app.add_subcommand("bench", "Benchmarks: throughput (docs/bench.md)");
  bench->require_subcommand(1);
  auto t = std::make_shared<ThroughputArgs>();
  CLI::App* tp = bench->add_subcommand(
      "throughput", "samples/s and ns/sample of golden, the fast engine and FFTW, in one run");
  tp->add_option("scenes", t->scenes, "scene files (default: neuroskin2 and skin32x32)")
      ->check(CLI::ExistingFile);
  tp->add_option("--min-seconds", t->min_seconds, "measure each row for at least this long")
      ->check(CLI::PositiveNumber);
  tp->add_option("--threads", t->threads, "threads for the threaded engine row")
      ->check(CLI::Range(1, 256));
  return [=]() -> int {
    if (tp->parsed()) return run_throughput(*t);
    return 1;
  };
}

ESKIN_COMMAND("bench", setup);

}  // namespace
}  // namespace eskin::cli
