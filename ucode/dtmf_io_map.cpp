#include "ucode/dtmf_io_map.h"

#include <cstdio>

namespace eskin::hls {

std::string dtmf_io_map_verilog() {
  std::string v =
      "// The frame engine's IO map in rtl/dtmf_top.v, generated from\n"
      "// ucode/dtmf_io_map.h by `eskin ucode io-map`: do not edit\n"
      "// (DtmfIoMap.VerilogIncludeIsGenerated fails when it differs).\n"
      "// A module includes it inside its body; it uses only some of them.\n"
      "/* verilator lint_off UNUSEDPARAM */\n";
  char line[160];
  for (const auto& e : kDtmfIoPorts) {
    std::snprintf(line, sizeof line, "localparam [15:0] %s = 16'h%04X;  // %s\n", e.symbol,
                  unsigned(e.value), e.what);
    v += line;
  }
  int bit = 0;
  for (const auto& e : kDtmfEvents) {
    while ((1u << bit) < e.value) ++bit;
    std::snprintf(line, sizeof line, "localparam integer %s_BIT = %d;  // %s\n", e.symbol, bit,
                  e.what);
    v += line;
  }
  v += "/* verilator lint_on UNUSEDPARAM */\n";
  return v;
}

}  // namespace eskin::hls
