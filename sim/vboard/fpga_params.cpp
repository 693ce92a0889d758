#include "sim/vboard/fpga_params.h"

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <cstring>
#include <stdexcept>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include "eskin/fnv1a.h"
#include "eskin/skin_config.h"
#include "ucode/dtmf_ucode.h"
#include "sim/dtmf_top_spec.h"

#include "eskin/source_tree.h"  // the default scene: scenes/neuroskin2.yaml

namespace eskin::vboard {
namespace {

hls::DtmfTopPlan plan_of(const sim::Scene& scene, long clk_hz, long baud = 3000000,
                         EngineOptions engine = {}) {
  try {
    hls::DtmfTopSpec spec = sim::dtmf_top_spec(scene, clk_hz);
    spec.baud = baud;
    spec.engine_fast_shift = engine.fast_shift;
    spec.neuron_unit = engine.neuron_unit;
    return hls::make_dtmf_top_plan(spec);
  } catch (const std::invalid_argument& e) {
    // "skin.rows/cols: expected ..." -> a ConfigError on that field.
    const std::string what = e.what();
    const size_t colon = what.find(": ");
    if (colon == std::string::npos) throw ConfigError("skin", what);
    throw ConfigError(what.substr(0, colon), what.substr(colon + 2));
  }
}

// The integer parameters (everything but the files) as "name=value;".
std::string integer_params(const hls::DtmfTopPlan& plan) {
  std::string s;
  const auto image = hls::dtmf_engine_image(plan);
  for (const auto& p : hls::dtmf_top_params(plan, image, "", ""))
    if (p.name != "UCODE_HEX" && p.name != "KROM_HEX") s += p.name + "=" + p.value + ";";
  return s;
}

}  // namespace

std::vector<std::string> FpgaBuild::verilator_args() const {
  std::vector<std::string> a;
  for (const auto& p : params) a.push_back("-G" + p.name + "=" + p.value);
  return a;
}

FpgaBuild fpga_build_for(const sim::Scene& scene, const std::string& dir, long clk_hz,
                         long baud, EngineOptions engine) {
  FpgaBuild b;
  b.plan = plan_of(scene, clk_hz, baud, engine);
  const std::string mine = integer_params(b.plan);
  static const std::string defaults = integer_params(
      plan_of(sim::load_scene(eskin::source_dir() + "/scenes/neuroskin2.yaml"), hls::kDtmfTopClkHz));
  if (mine == defaults) {
    b.key = "default";
  } else {
    const uint64_t h = fnv1a(mine);
    char buf[20];
    std::snprintf(buf, sizeof buf, "p%016llx", (unsigned long long)h);
    b.key = buf;
  }
  if (dir.empty()) {
    b.params = hls::dtmf_top_params(b.plan, hls::dtmf_engine_image(b.plan), "", "");
  } else {
    std::filesystem::create_directories(dir);
    b.params = hls::write_dtmf_top_build(b.plan, std::filesystem::absolute(dir).string(), b.key);
  }
  return b;
}

RunFiles::RunFiles(const sim::Scene& scene, long clk_hz, long baud, EngineOptions engine)
    : dir_(user_cache_dir() + "/vboard", "run"),
      build_(fpga_build_for(scene, dir_.path(), clk_hz, baud, engine)) {}

std::vector<std::string> RunFiles::plusargs() const {
  const std::string stem = dir_.path() + "/" + build_.key;
  return {"+UCODE_HEX=" + stem + ".ucode.hex", "+KROM_HEX=" + stem + ".krom.hex"};
}

BuildLock::BuildLock(const std::string& dir, const std::string& key) {
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/" + key + ".lock";
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw std::runtime_error(path + ": cannot open: " + std::strerror(errno));
  while (::flock(fd_, LOCK_EX) != 0)
    if (errno != EINTR) throw std::runtime_error(path + ": cannot lock: " + std::strerror(errno));
}

BuildLock::~BuildLock() {
  if (fd_ >= 0) ::close(fd_);  // closing releases the flock
}

}  // namespace eskin::vboard
