// Running the trade study's points: on a local thread pool, or as a Slurm
// job array (one task per point; `sbatch --array --wait`), then merging the
// per-point rows in point order, so both give the same CSV.
#pragma once

#include <string>
#include <vector>

#include "host/bench/tradeoff.h"

namespace eskin::bench {

struct TradeRunOptions {
  std::string out_dir;           // tradeoff.csv, tradeoff.html (and Slurm files)
  int threads = 1;
  std::string synth_table;       // stored synthesis results (read)
  std::string synth_cache;       // non-empty: run Yosys for builds not in the table
  bool slurm = false;
  std::string sbatch_args;       // extra sbatch arguments (partition, account, ...)
  std::string eskin_bin;         // this program, for the array tasks
};

// Evaluates every point (locally or on Slurm), marks the Pareto fronts,
// writes the CSV and the HTML report; returns the rows in point order.
std::vector<TradeRow> run_tradeoff(const std::vector<TradePoint>& points, const TradeRunOptions& o);

// One array task: point `index` of the points file -> one CSV row in `part`.
void run_tradeoff_task(const std::string& points_file, int index, const std::string& part,
                       const TradeRunOptions& o);

}  // namespace eskin::bench
