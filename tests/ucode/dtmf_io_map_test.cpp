// The frame engine's IO map has one definition (ucode/dtmf_io_map.h): the
// Verilog include rtl/dtmf_top.v decodes its bus with is generated from it,
// the RTL names no address of its own, and the map itself is consistent.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "ucode/dtmf_engine_image.h"
#include "ucode/dtmf_io_map.h"
#include "sim/dtmf_top_spec.h"
#include "sim/scene.h"

namespace {

using namespace eskin::hls;

std::string read(const std::string& rel) {
  std::ifstream f(std::string(ESKIN_SOURCE_DIR) + "/" + rel, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

TEST(DtmfIoMap, VerilogIncludeIsGenerated) {
  const std::string tree = read("rtl/dtmf_io_map.vh");
  ASSERT_FALSE(tree.empty()) << "rtl/dtmf_io_map.vh missing";
  EXPECT_EQ(tree, dtmf_io_map_verilog())
      << "rtl/dtmf_io_map.vh is stale: run `eskin ucode io-map`";
}

// Each entry in the include is the enumerator's value (the include is
// parsed back, not compared with the text the same function writes).
TEST(DtmfIoMap, IncludeHoldsEveryPortAndEvent) {
  const std::string vh = read("rtl/dtmf_io_map.vh");
  std::map<std::string, long> got;
  const std::regex port(R"(localparam \[15:0\] (\w+) = 16'h([0-9A-F]{4});)");
  const std::regex bit(R"(localparam integer (\w+)_BIT = (\d+);)");
  for (std::sregex_iterator it(vh.begin(), vh.end(), port), end; it != end; ++it)
    got[(*it)[1]] = std::stol((*it)[2], nullptr, 16);
  for (std::sregex_iterator it(vh.begin(), vh.end(), bit), end; it != end; ++it)
    got[(*it)[1]] = 1L << std::stol((*it)[2]);
  EXPECT_EQ(got.at("IO_OUT_BYTE"), kIoOutByte);
  EXPECT_EQ(got.at("IO_OUT_WORD"), kIoOutWord);
  EXPECT_EQ(got.at("IO_IZ_CFG"), kIoIzCfg);
  EXPECT_EQ(got.at("IO_IZ_EVN"), kIoIzEvN);
  EXPECT_EQ(got.at("EV_IZ_DONE"), kEvIzDone);
  EXPECT_EQ(got.size(), std::size(kDtmfIoPorts) + std::size(kDtmfEvents));
}

// rtl/dtmf_top.v decodes the bus by the include's names only: no 16-bit
// hex literal in the 0x200 register block, and every write port it
// decodes is named.
TEST(DtmfIoMap, TopNamesNoAddressOfItsOwn) {
  const std::string top = read("rtl/dtmf_top.v");
  ASSERT_NE(top.find("`include \"dtmf_io_map.vh\""), std::string::npos);
  std::smatch m;
  EXPECT_FALSE(std::regex_search(top, m, std::regex(R"(16'h0?2[0-9A-Fa-f]{2})"))) << m.str();
  EXPECT_FALSE(std::regex_search(top, m, std::regex(R"(4'h[0-9A-Fa-f]\s*:\s*io_reg)"))) << m.str();
  for (const char* w : {"IO_OUT_BYTE", "IO_OUT_WORD", "IO_FRAME_DONE", "IO_CMD_POP", "IO_SDFT_K",
                        "IO_SDFT_INC", "IO_CLEAR", "IO_IZ_X", "IO_IZ_GO", "IO_IZ_UGO", "IO_IZ_CFG",
                        "IO_IZ_N", "IO_IZ_XGO", "IO_IZ_SV", "IO_IZ_SU", "EV_FRAME_PENDING_BIT",
                        "EV_CMD_AVAIL_BIT", "EV_IZ_DONE_BIT"})
    EXPECT_NE(top.find(w), std::string::npos) << w;
}

// Reads and writes are separate maps: within each, no two ports share an
// address; events are distinct single bits.
TEST(DtmfIoMap, NoTwoPortsShareAnAddressInOneDirection) {
  std::map<char, std::set<uint16_t>> seen;
  for (const auto& e : kDtmfIoPorts) {
    const std::string what = e.what;
    const bool r = what.rfind("r:", 0) == 0, w = what.rfind("w:", 0) == 0 ||
                                                 what.find("; w:") != std::string::npos;
    ASSERT_TRUE(r || w) << e.symbol;
    if (r) {
      EXPECT_TRUE(seen['r'].insert(e.value).second) << e.symbol << " (read)";
    }
    if (w) {
      EXPECT_TRUE(seen['w'].insert(e.value).second) << e.symbol << " (write)";
    }
  }
  uint16_t bits = 0;
  for (const auto& e : kDtmfEvents) {
    EXPECT_EQ(e.value & (e.value - 1), 0) << e.symbol;
    EXPECT_EQ(bits & e.value, 0) << e.symbol;
    bits |= e.value;
  }
}

// The write ports that take a block of addresses (a base + word: the
// layers' 32 constant words each, the nine synapse weights) overlap no
// other write port: a weight at 0x230 once also wrote layer 0's constant
// words 16..24 (IO_IZ_CFG's block), and layer 1 spiked differently.
TEST(DtmfIoMap, AddressBlocksOverlapNoOtherWritePort) {
  const std::map<uint16_t, int> blocks = {{kIoIzCfg, 32}, {kIoIzCfg1, 32}, {kIoWeight, 16}};
  for (const auto& e : kDtmfIoPorts) {
    const std::string what = e.what;
    if (!(what.rfind("w:", 0) == 0 || what.find("; w:") != std::string::npos)) continue;
    for (const auto& [base, n] : blocks)
      if (e.value != base) {
        EXPECT_FALSE(e.value >= base && e.value < base + n)
            << e.symbol << " at " << e.value << " falls in the block at " << base;
      }
  }
}

// The microcode's symbols for the ports are the map's.
TEST(DtmfIoMap, MicrocodeSymbolsAreTheMap) {
  const auto sc = eskin::sim::load_scene(std::string(ESKIN_SOURCE_DIR) + "/scenes/neuroskin2.yaml");
  const DtmfTopPlan p = make_dtmf_top_plan(eskin::sim::dtmf_top_spec(sc));
  const EngineImage im = dtmf_engine_image(p);
  for (const auto& e : kDtmfIoPorts) EXPECT_EQ(im.symbol(e.symbol), e.value) << e.symbol;
  for (const auto& e : kDtmfEvents) EXPECT_EQ(im.symbol(e.symbol), e.value) << e.symbol;
}

}  // namespace
