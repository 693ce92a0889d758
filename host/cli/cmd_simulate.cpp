// eskin simulate SCENE.yaml [--out DIR] [--trace F.fst]: the scene on the
// SystemC virtual board (sim/vboard/), read over its serial port (a pty)
// like a real board; the golden model on the same samples; both scored
// against the scene's ground truth; one self-contained HTML report plus
// the raw outputs (docs/vboard.md). The run and the reports are
// host/simulate's and host/report's.
#include <memory>

#include "cli/command.h"
#include "host/simulate/simulate.h"

namespace eskin::cli {
namespace {

std::function<int()> setup(CLI::App& app) {
  auto a = std::make_shared<simulate::SimulateOptions>();
  auto line = std::make_shared<vboard::LineFaultArgs>();
  CLI::App* sub = app.add_subcommand(
      "simulate", "Run a scene on the SystemC virtual board (Verilated FPGA, pty serial port), "
                  "compare with the golden model and write an HTML report");
  sub->add_option("scene", a->scene, "scene file (YAML, see docs/scenes.md)")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("--out", a->out, "output directory (created)")->capture_default_str();
  sub->add_option("--trace", a->trace, "FST waveform of the FPGA (GTKWave; several times slower)");
  sub->add_option("--ber", line->ber,
                  "line faults: probability that a wire bit (start, data, stop) is flipped");
  sub->add_option("--drop-rate", line->drop_rate, "line faults: probability that a character is lost");
  sub->add_option("--insert-rate", line->insert_rate,
                  "line faults: probability that a random character comes before one");
  sub->add_option("--fault-direction", line->direction,
                  "line faults: which way --ber/--drop-rate/--insert-rate act: both (default), "
                  "to-host, to-fpga");
  sub->add_option("--pull-cable", line->pulls,
                  "line faults: AT_MS:FOR_MS, the cable out for FOR_MS from AT_MS of simulated "
                  "time (repeatable)");
  sub->add_option("--fault-seed", line->seed, "line faults: the seed of every fault (default 1)");
  sub->add_option("--board", a->board,
                  "run this virtual board executable instead of the one the scene's build needs "
                  "(a Verilator variant: eskin bench sim-speed --verilator); it refuses a scene "
                  "of another build")
      ->check(CLI::ExistingFile);
  auto fidelity = std::make_shared<std::string>("rtl");
  sub->add_option("--fidelity", *fidelity,
                  "how much of the board to model: rtl (the Verilated FPGA top, clock by clock, "
                  "behind a pty; the default), cycle (the same board with the FPGA's clock-exact "
                  "C++ models: the same bytes at the same clocks, DTMF skins of the builds it "
                  "models) or packet (the FPGA's integer chain's packets, timed per packet: DTMF "
                  "skins; docs/vboard.md, \"Fidelity levels\")")
      ->capture_default_str();
  auto faults = std::make_shared<std::vector<std::string>>();
  sub->add_option("--fault", *faults,
                  "board fault KIND@AT_MS[:FOR_MS]: reset, reset-in-frame, reset-in-command, "
                  "adc-stuck-low, adc-stuck-high, carrier-off=K, sda-low=B (repeatable; "
                  "docs/vboard.md, \"Board faults\")");
  return [a, line, faults, fidelity] {
    a->fidelity = simulate::parse_fidelity(*fidelity);
    a->line = vboard::parse_line_faults(*line);  // std::invalid_argument: exit 2
    a->faults = vboard::parse_board_faults(*faults);
    return simulate::run_simulate(*a);
  };
}

ESKIN_COMMAND("simulate", setup);

}  // namespace
}  // namespace eskin::cli
