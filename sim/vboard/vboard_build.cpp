#include "sim/vboard/vboard_build.h"


#include "eskin/process.h"
#include "eskin/source_tree.h"

#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <deque>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#if !defined(ESKIN_VBOARD_VARIANTS)
#error "sim/vboard/CMakeLists.txt lists the default board's Verilator variants"
#endif
#if !defined(ESKIN_BINARY_DIR) || !defined(ESKIN_CMAKE_COMMAND) || !defined(ESKIN_VBOARD_DIR) || \
    !defined(ESKIN_VBOARD_BIN_DIR)
#error "sim/vboard/CMakeLists.txt defines where the build tree, cmake and the boards are"
#endif

namespace eskin::vboard {
namespace {

std::string read_text(const std::string& path) {
  std::ifstream f(path);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

std::string tail(const std::string& path, size_t lines) {
  std::ifstream f(path);
  std::deque<std::string> last;
  for (std::string l; std::getline(f, l);) {
    last.push_back(l);
    if (last.size() > lines) last.pop_front();
  }
  std::string s;
  for (const auto& l : last) s += "  " + l + "\n";
  return s;
}

// Runs `argv` (no shell) with stdout and stderr appended to `log`.
void run_step(const std::vector<std::string>& argv, const std::string& log, const std::string& what) {
  const int st = eskin::run_logged(argv, log, eskin::LogMode::Append);
  if (st != 0 || !WIFEXITED(st))
    throw std::runtime_error(what + " failed (" + log + "), its last lines:\n" + tail(log, 15));
}

// The board `target`: listed in builds.cmake by `cmake_call` the first
// time, then built (CMake finds it up to date when nothing changed).
std::string ensure_board(const std::string& target, const std::string& key,
                         const std::string& cmake_call, const std::string& what,
                         const std::function<void(const std::string&)>& note) {
  const std::string dir = in_build_dir(ESKIN_VBOARD_DIR), bin = in_build_dir(ESKIN_VBOARD_BIN_DIR);
  const std::string exe = bin + "/" + target, list = dir + "/builds.cmake";
  BuildLock lock(dir, "builds");  // one writer of the list, one CMake run at a time
  const bool listed = read_text(list).find("(" + target + " ") != std::string::npos;
  if (!listed) {
    std::ofstream f(list, std::ios::app);
    if (!std::filesystem::exists(list) || std::filesystem::file_size(list) == 0)
      f << "# Virtual boards that `eskin simulate` built for scenes (sim/vboard/vboard_build.h).\n";
    f << cmake_call << "\n";
    if (!f) throw std::runtime_error(list + ": cannot append the board " + target);
  }
  const std::string log = dir + "/" + key + ".build.log";
  if (!listed || !std::filesystem::exists(exe)) {
    note("building the virtual board " + target + " for " + what +
         " (Verilator and C++, a few minutes, once; log " + log + ")");
    std::ofstream(log, std::ios::trunc);
  }
  const std::string cmake = ESKIN_CMAKE_COMMAND, tree = in_build_dir(ESKIN_BINARY_DIR);
  if (!listed) run_step({cmake, tree}, log, "configuring the build tree for " + target);
  run_step({cmake, "--build", tree, "--target", target}, log, "building " + target);
  return exe;
}

}  // namespace

std::vector<std::string> verilator_variants() {
  std::vector<std::string> v;
  std::stringstream ss(ESKIN_VBOARD_VARIANTS);
  for (std::string name; std::getline(ss, name, ',');) v.push_back(name);
  return v;
}

std::string variant_executable(const std::string& name,
                               const std::function<void(const std::string&)>& note) {
  const std::vector<std::string> all = verilator_variants();
  if (std::find(all.begin(), all.end(), name) == all.end()) {
    std::string names;
    for (const auto& n : all) names += (names.empty() ? "" : ", ") + n;
    throw std::invalid_argument("'" + name + "' is not a Verilator variant of the board (" +
                                names + ")");
  }
  const std::string target = "eskin-vboard-variant-" + name;
  const std::string dir = in_build_dir(ESKIN_VBOARD_DIR), log = dir + "/" + target + ".build.log";
  std::filesystem::create_directories(dir);
  BuildLock lock(dir, "builds");
  note("building " + target + " (Verilator and C++, a few minutes when out of date; log " + log +
       ")");
  std::ofstream(log, std::ios::trunc);
  run_step({ESKIN_CMAKE_COMMAND, "--build", in_build_dir(ESKIN_BINARY_DIR), "--target", target},
           log, "building " + target);
  return in_build_dir(ESKIN_VBOARD_BIN_DIR) + "/" + target;
}

std::string cycle_board_executable() {
  return in_build_dir(ESKIN_VBOARD_BIN_DIR) + "/eskin-vboard-cycle";
}

std::string board_executable(const FpgaBuild& b,
                             const std::function<void(const std::string&)>& note) {
  if (b.key == "default") return in_build_dir(ESKIN_VBOARD_BIN_DIR) + "/eskin-vboard";
  const std::string target = "eskin-vboard-" + b.key;
  std::string call = "eskin_vboard_target(" + target + " " + b.key + " " +
                     std::to_string(b.plan.spec.clk_hz) + " " + std::to_string(b.plan.spec.baud);
  for (const auto& p : b.params)
    if (p.name != "UCODE_HEX" && p.name != "KROM_HEX") call += " -G" + p.name + "=" + p.value;
  const std::string what = "a " + std::to_string(b.plan.R) + "x" + std::to_string(b.plan.C) +
                           " skin at " + std::to_string(b.plan.spec.clk_hz / 1000000) + " MHz";
  return ensure_board(target, b.key, call + ")", what, note);
}

std::string board_executable(const HallBuild& b,
                             const std::function<void(const std::string&)>& note) {
  const std::string target = "eskin-vboard-" + b.key;
  std::string call = "eskin_vboard_hall_target(" + target + " " + b.key + " " +
                     std::to_string(b.clk_hz) + " " + std::to_string(b.baud);
  for (const auto& p : b.params) call += " " + p;
  const std::string what = std::to_string(b.spec.nb) + " I2C bus(es) of " +
                           std::to_string(b.spec.nsb) + " MLX90393 at " +
                           std::to_string(b.clk_hz / 1000000) + " MHz";
  return ensure_board(target, b.key, call + ")", what, note);
}

std::string board_executable(const MixedBuild& b,
                             const std::function<void(const std::string&)>& note) {
  const std::string target = "eskin-vboard-" + b.key;
  std::string call = "eskin_vboard_mixed_target(" + target + " " + b.key + " " + b.dtmf.key + " " +
                     std::to_string(b.dtmf.plan.spec.clk_hz) + " " +
                     std::to_string(b.dtmf.plan.spec.baud);
  for (const auto& p : b.verilator_args()) call += " " + p;
  const std::string what = "a " + std::to_string(b.dtmf.plan.R) + "x" +
                           std::to_string(b.dtmf.plan.C) + " skin beside " +
                           std::to_string(b.hall.spec.nb) + " I2C bus(es) of " +
                           std::to_string(b.hall.spec.nsb) + " MLX90393 at " +
                           std::to_string(b.dtmf.plan.spec.clk_hz / 1000000) + " MHz";
  return ensure_board(target, b.key, call + ")", what, note);
}

}  // namespace eskin::vboard
