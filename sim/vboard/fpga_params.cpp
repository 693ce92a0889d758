#include "sim/vboard/fpga_params.h"

#include <cstdint>
#include <cstdio>
#include <stdexcept>

#include "eskin/skin_config.h"
#include "sim/dtmf_top_spec.h"

#ifndef ESKIN_SOURCE_DIR
#error "ESKIN_SOURCE_DIR: where scenes/neuroskin2.yaml (the default scene) is"
#endif

namespace eskin::vboard {
namespace {

std::vector<hls::VerilogParam> params_of(const sim::Scene& scene, hls::DtmfTopPlan* plan) {
  try {
    hls::DtmfTopPlan p = hls::make_dtmf_top_plan(sim::dtmf_top_spec(scene));
    auto params = hls::dtmf_top_params(p);
    if (plan) *plan = std::move(p);
    return params;
  } catch (const std::invalid_argument& e) {
    // "skin.rows/cols: expected ..." -> a ConfigError on that field.
    const std::string what = e.what();
    const size_t colon = what.find(": ");
    if (colon == std::string::npos) throw ConfigError("skin", what);
    throw ConfigError(what.substr(0, colon), what.substr(colon + 2));
  }
}

bool same(const std::vector<hls::VerilogParam>& a, const std::vector<hls::VerilogParam>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (a[i].name != b[i].name || a[i].value != b[i].value) return false;
  return true;
}

}  // namespace

std::vector<std::string> FpgaBuild::verilator_args() const {
  std::vector<std::string> a;
  for (const auto& p : params) a.push_back("-G" + p.name + "=" + p.value);
  return a;
}

FpgaBuild fpga_build_for(const sim::Scene& scene) {
  FpgaBuild b;
  b.params = params_of(scene, &b.plan);
  static const auto defaults =
      params_of(sim::load_scene(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml"), nullptr);
  if (same(b.params, defaults)) {
    b.key = "default";
    return b;
  }
  uint64_t h = 1469598103934665603ull;  // FNV-1a over "name=value;"
  for (const auto& p : b.params)
    for (char c : p.name + "=" + p.value + ";") h = (h ^ uint8_t(c)) * 1099511628211ull;
  char buf[20];
  std::snprintf(buf, sizeof buf, "p%016llx", (unsigned long long)h);
  b.key = buf;
  return b;
}

}  // namespace eskin::vboard
