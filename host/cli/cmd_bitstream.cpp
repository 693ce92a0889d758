// `eskin bitstream --board icebreaker|ulx3s [--scene SCENE.yaml] [--out DIR]
//  [--seed N] [--seeds N] [--device 25k|45k|85k] [--clk-mhz F] [--engine-load scene|stress]
//  [--engine-shifter serial|barrel] [--neurons engine|unit|lanes] [--datapath engine|streaming]`:
// builds the core the scene needs (host/fpga/flow.h): its DTMF skin's
// (parameters from common/eskin/dtmf_top_plan.h, microcode and constants from
// ucode/dtmf_ucode.h), its Hall sensors' (sim/hall_top_spec.h, with their I2C
// and DRDY pins), or both on one link (rtl/mixed_top.v), in the board's
// wrapper with Yosys, nextpnr and icepack / ecppack, writes the bitstream,
// OUT/bitstream_report.json and OUT/bitstream_report.txt, prints the table,
// and exits 1 with the numbers (for a skin, also the skins that would fit,
// from docs/scale_table.csv) when the design does not fit (logic, RAM,
// pins) or misses timing.
//
// `eskin bitstream --scale-table [--scene BASE.yaml] [--out DIR] [--targets
// L] [--rates L] [--sizes L]`: measures the scale table
// (host/fpga/scale_table.h) with real runs (hours: see docs/bitstream.md),
// updates docs/scale_table.csv and prints the table.
#include <fmt/core.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>

#include <unistd.h>

#include "cli/command.h"
#include "eskin/exit_codes.h"
#include "host/fpga/flow.h"
#include "host/fpga/scale_table.h"
#include "eskin/skin_config.h"
#include "sim/scene.h"

#include "eskin/source_tree.h"

namespace {

namespace fs = std::filesystem;

struct BitstreamArgs {
  std::string board;
  std::string scene;
  std::string out;
  std::string device;
  int seed = 1;
  int seeds = 1;
  double clk_mhz = 0;
  std::string engine_load = "scene";
  bool engine_load_given = false;  // a Hall-only scene has no engine to load
  std::string engine_shifter;      // "serial", "barrel"; empty: the board's
  std::string neurons;             // "engine", "unit", "lanes"; empty: the board's
  std::string datapath;            // "engine", "streaming"; empty: the board's choice
  bool scale_table = false;
  eskin::fpga::ScaleSelection scale;  // --targets, --rates, --sizes
};

using eskin::source_dir;  // $ESKIN_SOURCE_DIR, else the tree built from

std::string scene_or_default(const std::string& scene) {
  return scene.empty() ? source_dir() + "/scenes/neuroskin2.yaml" : scene;
}

std::vector<eskin::fpga::ScaleRow> read_scale_table(const std::string& path) {
  std::ifstream f(path);
  if (!f) return {};
  std::stringstream s;
  s << f.rdbuf();
  return eskin::fpga::parse_scale_csv(s.str());
}

int run_scale_table(const BitstreamArgs& a) {
  const auto base = eskin::sim::load_scene(scene_or_default(a.scene));
  // The table is of DTMF skins: its scenes are the base's skin resized.
  if (eskin::fpga::scene_core(base) != eskin::fpga::Core::Dtmf)
    throw std::invalid_argument("--scale-table: the table is of DTMF skins, and " +
                                scene_or_default(a.scene) + " has " +
                                (base.has_skin ? "Hall sensors too" : "no skin") +
                                " (a base scene with a skin: section only)");
  eskin::fpga::FlowOptions opt;
  opt.source_dir = source_dir();
  opt.out_dir = a.out.empty() ? "build/bitstream/scale" : a.out;
  eskin::fpga::check_out_dir_for_tools(opt.out_dir);
  opt.seed = a.seed;
  opt.seeds = a.seeds;
  // The CSV is rewritten after every probe, so an interrupted run keeps
  // what it measured; it is read again each time (and replaced by a
  // rename), so runs of other targets at the same time keep theirs.
  const std::string csv = source_dir() + "/docs/scale_table.csv";
  std::vector<eskin::fpga::ScaleRow> done;
  eskin::fpga::run_scale_table(base, opt, a.scale, [&](const eskin::fpga::ScaleRow& r) {
    std::cerr << fmt::format("scale: {} {:.0f} S/s {}x{}: {} ({:.0f} s)\n", r.target, r.sample_hz,
                             r.rows, r.cols, r.ok() ? "fits and meets timing" : r.failure,
                             r.seconds);
    done.push_back(r);
    const std::string text =
        eskin::fpga::scale_csv(eskin::fpga::merge_scale_rows(read_scale_table(csv), done));
    const std::string tmp = csv + ".tmp" + std::to_string(::getpid());
    std::ofstream(tmp) << text;
    std::filesystem::rename(tmp, csv);
  });
  std::cout << eskin::fpga::scale_markdown(read_scale_table(csv));
  std::cerr << "scale: wrote " << csv << "\n";
  return 0;
}

// Options of one build and options of the scale table are refused in the
// other mode rather than ignored.
void check_mode_options(const BitstreamArgs& a) {
  if (a.scale_table) {
    const std::pair<bool, const char*> single[] = {
        {!a.board.empty(), "--board"},          {!a.device.empty(), "--device"},
        {a.clk_mhz > 0, "--clk-mhz"},           {a.engine_load_given, "--engine-load"},
        {!a.engine_shifter.empty(), "--engine-shifter"}, {!a.neurons.empty(), "--neurons"},
        {!a.datapath.empty(), "--datapath"}};
    for (const auto& [given, name] : single)
      if (given)
        throw std::invalid_argument(
            std::string("--scale-table: ") + name +
            " does not apply: the table builds each target on its own board with that board's "
            "engine (and, when that misses timing, with the smallest engine that keeps up at a "
            "slower clock), at the slowest clock each skin needs under the stress load (choose "
            "targets with --targets)");
  } else {
    const std::pair<bool, const char*> table[] = {{!a.scale.sizes.empty(), "--sizes"},
                                                  {!a.scale.targets.empty(), "--targets"},
                                                  {!a.scale.rates.empty(), "--rates"}};
    for (const auto& [given, name] : table)
      if (given) throw std::invalid_argument(std::string(name) + ": only with --scale-table");
  }
}

int run_bitstream(const BitstreamArgs& a) {
  check_mode_options(a);
  if (a.scale_table) return run_scale_table(a);
  if (a.board.empty()) throw std::invalid_argument("--board: required (icebreaker or ulx3s)");
  const auto board = eskin::fpga::find_board(a.board, a.device);
  const std::string scene_path = scene_or_default(a.scene);
  const auto scene = eskin::sim::load_scene(scene_path);
  if (a.engine_load_given && eskin::fpga::scene_core(scene) == eskin::fpga::Core::Hall)
    throw std::invalid_argument("--engine-load: " + scene_path +
                                " has no skin, so no frame engine to load");
  if (!a.engine_shifter.empty() && eskin::fpga::scene_core(scene) == eskin::fpga::Core::Hall)
    throw std::invalid_argument("--engine-shifter: " + scene_path +
                                " has no skin, so no frame engine to build");
  if (!a.neurons.empty() && eskin::fpga::scene_core(scene) == eskin::fpga::Core::Hall)
    throw std::invalid_argument("--neurons: " + scene_path +
                                " has no skin, so no neuron layers to build");
  if (!a.datapath.empty() && eskin::fpga::scene_core(scene) != eskin::fpga::Core::Dtmf)
    throw std::invalid_argument("--datapath: " + scene_path + " has " +
                                (scene.has_skin ? "Hall sensors beside its skin (rtl/mixed_top.v "
                                                  "builds the frame engine alone)"
                                                : "no skin") +
                                ", so no datapath to choose");
  eskin::fpga::FlowOptions opt;
  opt.source_dir = source_dir();
  opt.out_dir = a.out.empty() ? "build/bitstream/" + board.name : a.out;
  eskin::fpga::check_out_dir_for_tools(opt.out_dir);
  opt.seed = a.seed;
  opt.seeds = a.seeds;
  opt.clk_hz = std::lround(a.clk_mhz * 1e6);
  opt.load = a.engine_load == "stress" ? eskin::fpga::LoadPolicy::Stress
                                       : eskin::fpga::LoadPolicy::Scene;
  opt.fast_shift = a.engine_shifter.empty() ? -1 : a.engine_shifter == "barrel" ? 1 : 0;
  opt.neuron_unit = a.neurons.empty() ? -1 : a.neurons == "lanes" ? 2 : a.neurons == "unit" ? 1 : 0;
  opt.datapath = a.datapath.empty() ? -1 : a.datapath == "streaming" ? 1 : 0;
  // A clock the board cannot make is named before anything runs.
  if (opt.clk_hz > 0 && eskin::fpga::scene_core(scene) == eskin::fpga::Core::Hall)
    eskin::fpga::choose_hall_clock(board, opt.clk_hz);
  else if (opt.clk_hz > 0)
    eskin::fpga::choose_clock(board, 0, opt.clk_hz);
  eskin::fpga::FlowReport r;
  try {
    r = eskin::fpga::run_flow(board, scene, opt);
  } catch (const std::invalid_argument& e) {
    // The plan names the scene field it cannot build.
    throw std::invalid_argument(scene_path + ": " + e.what());
  } catch (const eskin::ConfigError& e) {
    throw eskin::ConfigError(scene_path, e.what());  // a hall: field hall_top cannot carry
  }
  fs::create_directories(opt.out_dir);
  std::ofstream(fs::path(opt.out_dir) / "bitstream_report.json") << eskin::fpga::report_json(r);
  const std::string table = eskin::fpga::report_table(r);
  std::ofstream(fs::path(opt.out_dir) / "bitstream_report.txt") << table;
  std::cout << table;
  if (r.ok()) return 0;
  // Another engine may keep up where the board's did not (only offered when
  // the user left the engine and the clock to the board).
  const std::string engine_hint =
      r.core == eskin::fpga::Core::Dtmf && opt.fast_shift < 0 && opt.neuron_unit < 0 &&
              opt.datapath < 0 && opt.clk_hz == 0
          ? eskin::fpga::slower_engine_hint(board, scene, r)
          : "";
  std::cerr << "eskin bitstream: " << board.name << " (" << board.device << "): " << r.failure
            << (engine_hint.empty() ? "" : "\n  " + engine_hint) << "\n  "
            << (r.core == eskin::fpga::Core::Dtmf
                    ? eskin::fpga::fit_hint(read_scale_table(source_dir() + "/docs/scale_table.csv"),
                                            board.name, board.device, r.spec.sample_hz)
                    : std::string("docs/hall_fpga.md (Area) lists what each Hall build needs "
                                  "on each FPGA"))
            << "\n";
  return eskin::exit_code(eskin::Exit::failure);
}

std::function<int()> setup_bitstream(CLI::App& app) {
  auto args = std::make_shared<BitstreamArgs>();
  CLI::App* sub = app.add_subcommand(
      "bitstream",
      "Build a scene's FPGA bitstream for a board (Yosys, nextpnr, icepack/ecppack) and report "
      "utilisation and Fmax; or measure the scale table");
  sub->add_option("--board", args->board, "icebreaker (iCE40 UP5K) or ulx3s (ECP5)");
  sub->add_option("--scene", args->scene, "Scene YAML (default scenes/neuroskin2.yaml)");
  sub->add_option("--out", args->out,
                  "Output directory (default build/bitstream/BOARD; scale table: "
                  "build/bitstream/scale); under /tmp too (the ECP5 tools get its folder "
                  "mounted)");
  sub->add_option("--seed", args->seed, "nextpnr placer seed (the first one tried)")
      ->capture_default_str();
  sub->add_option("--seeds", args->seeds,
                  "Placer seeds to try: a build that fits but misses timing is placed again "
                  "at the next seed, up to this many runs (the report names the seed; the "
                  "scale table's probes too, its CSV has a seed column)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  sub->add_option("--device", args->device, "ulx3s: ECP5 size 25k, 45k or 85k (default 85k)");
  sub->add_option("--clk-mhz", args->clk_mhz,
                  "Core clock (default: the slowest the board makes at which the skin's core "
                  "keeps up; Hall sensors only: 12 MHz, the iCEBreaker's oscillator, or the "
                  "ULX3S's 30 MHz; Hall sensors need a whole number of MHz)");
  sub->add_option("--engine-load", args->engine_load,
                  "What the clock must carry: scene (the scene's longest frame) or stress (the "
                  "stress signals' longest frame + the longest command); the scale table uses "
                  "stress")
      ->check(CLI::IsMember({"scene", "stress"}))
      ->capture_default_str()
      ->each([args](const std::string&) { args->engine_load_given = true; });
  sub->add_option("--engine-shifter", args->engine_shifter,
                  "The frame engine's shifter: serial (one bit per clock, the smallest) or "
                  "barrel (any shift in one clock: fewer engine clocks a frame, ~1000 "
                  "logic cells more); default: the board's (ulx3s barrel; icebreaker serial unless "
                  "the core needs more than 18 MHz: see --neurons)")
      ->check(CLI::IsMember({"serial", "barrel"}));
  sub->add_option("--neurons", args->neurons,
                  "Where the Izhikevich neuron updates run: engine (the frame engine's "
                  "microcode, no extra logic), unit (the hardware neuron unit, "
                  "rtl/izhikevich_layer.v: 14 (level input) to 20 (change input) engine clocks a "
                  "neuron instead of about 120 with the barrel shifter or 210 without) or lanes "
                  "(units that keep the neurons' state, rtl/izhikevich_lanes.v: 3 engine clocks "
                  "a neuron, skins up to 1024 taxels); default: the board's (ulx3s lanes; "
                  "icebreaker engine unless the core needs more than 18 MHz: then the first of "
                  "barrel, serial + unit, barrel + unit that keeps up at 18 MHz, else the "
                  "fastest)")
      ->check(CLI::IsMember({"engine", "unit", "lanes"}));
  sub->add_option("--datapath", args->datapath,
                  "What does each frame's work after the DFT: engine (the frame engine's "
                  "microcode alone) or streaming (rtl/dtmf_chain.v, one taxel a clock, the "
                  "engine its control plane; bin-centred carriers only, its own neuron layers: "
                  "not with --neurons unit or lanes); default: the board's (ulx3s: of the two "
                  "that keep up with their static bound, the one at the slower clock, the engine "
                  "on a tie; icebreaker engine)")
      ->check(CLI::IsMember({"engine", "streaming"}));
  sub->add_flag("--scale-table", args->scale_table,
                "Measure the scale table (all boards; hours) into docs/scale_table.csv");
  sub->add_option("--sizes", args->scale.sizes,
                  "Scale table: the n of the n x n skins to search, ascending "
                  "(default 2,3,4,6,8,12,16,24,32,48,64)")
      ->delimiter(',');
  sub->add_option("--targets", args->scale.targets,
                  "Scale table: up5k, ecp5-25k, ecp5-85k (default all); the rows of the "
                  "targets and rates measured replace theirs in docs/scale_table.csv")
      ->delimiter(',');
  sub->add_option("--rates", args->scale.rates,
                  "Scale table: sample rates in S/s (default 35000,1000000)")
      ->delimiter(',');
  return [args] { return run_bitstream(*args); };
}

}  // namespace

ESKIN_COMMAND("bitstream", setup_bitstream);
