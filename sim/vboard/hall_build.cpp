#include "sim/vboard/hall_build.h"

#include <cstdio>

#include "eskin/fnv1a.h"
#include "eskin/skin_config.h"

namespace eskin::vboard {

HallBuild hall_build_for(const sim::Scene& scene, long clk_hz, long baud) {
  if (!scene.has_hall) throw ConfigError("hall", "expected a hall: section for the Hall top");
  HallBuild b;
  b.clk_hz = clk_hz;
  b.baud = baud;
  b.spec = sim::hall_top_spec(scene.hall.config, double(clk_hz));
  b.params = {"-GCLK_HZ=" + std::to_string(clk_hz), "-GBAUD=" + std::to_string(b.baud)};
  for (const auto& p : b.spec.verilog_params()) b.params.push_back(p);
  for (const auto& p : b.spec.decode_params()) b.params.push_back(p);
  std::string all;
  for (const auto& p : b.params) all += p + ";";
  char key[20];
  std::snprintf(key, sizeof key, "h%016llx", (unsigned long long)fnv1a(all));
  b.key = key;
  return b;
}

}  // namespace eskin::vboard
