#include "sim/vboard/mixed_build.h"

#include <cstdio>

#include "eskin/fnv1a.h"
#include "eskin/skin_config.h"

namespace eskin::vboard {

std::vector<std::string> MixedBuild::verilator_args() const {
  std::vector<std::string> a;
  for (const auto& p : dtmf.params)
    if (p.name != "UCODE_HEX" && p.name != "KROM_HEX") a.push_back("-G" + p.name + "=" + p.value);
  for (const auto& p : hall.params)
    if (p.rfind("-GCLK_HZ=", 0) != 0 && p.rfind("-GBAUD=", 0) != 0) a.push_back(p);
  return a;
}

MixedBuild mixed_build_for(const sim::Scene& scene, const FpgaBuild& dtmf) {
  if (!scene.has_skin) throw ConfigError("skin", "expected a skin: section for the mixed top");
  const long clk = dtmf.plan.spec.clk_hz;
  if (clk % 1000000 != 0)
    throw ConfigError("hall", "the Hall top shares the DTMF top's clock, " + std::to_string(clk) +
                                  " Hz, and needs a whole number of MHz (its µs time base)");
  MixedBuild m;
  m.dtmf = dtmf;
  m.hall = hall_build_for(scene, clk);  // names a bad hall: field
  m.hall.baud = dtmf.plan.spec.baud;     // one UART: mixed_top's BAUD is the DTMF build's
  std::string all;
  for (const auto& p : m.verilator_args()) all += p + ";";
  char key[20];
  std::snprintf(key, sizeof key, "m%016llx", (unsigned long long)fnv1a(all));
  m.key = key;
  return m;
}

}  // namespace eskin::vboard
