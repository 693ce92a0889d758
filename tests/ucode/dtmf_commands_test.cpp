// Each DTMF command's payload has one definition (common/eskin/dtmf_commands.h):
// docs/protocol.md's table, the microcode's length table and the host
// link's encoder and decoder all agree with it.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>

#include "eskin/dtmf_commands.h"
#include "host/link/link_decoder.h"
#include "host/link/link_encoder.h"
#include "sim/dtmf_top_spec.h"
#include "sim/scene.h"
#include "ucode/dtmf_engine_image.h"

namespace {

using namespace eskin;

// Section 5's table rows: | 0xTT | NAME | payload | accepted when | effect |
TEST(DtmfCommands, ProtocolTableIsTheDefinition) {
  std::ifstream f(std::string(ESKIN_SOURCE_DIR) + "/docs/protocol.md");
  ASSERT_TRUE(f) << "docs/protocol.md";
  const std::regex row(R"(^\| 0x(8[0-9A-Fa-f]) \| ([A-Z_]+) \| ([^|]+?) \|)");
  std::map<int, std::pair<std::string, std::string>> doc;
  std::string line;
  for (int ln = 1; std::getline(f, line); ++ln) {
    std::smatch m;
    if (std::regex_search(line, m, row)) {
      const int type = std::stoi(m[1], nullptr, 16);
      EXPECT_TRUE(doc.emplace(type, std::make_pair(m[2].str(), m[3].str())).second)
          << "docs/protocol.md:" << ln << ": type 0x" << std::hex << type << " twice";
    }
  }
  EXPECT_EQ(doc.size(), size_t(kDtmfCommandCount));
  for (const DtmfCommand& c : kDtmfCommands) {
    auto it = doc.find(c.type);
    ASSERT_NE(it, doc.end()) << c.name << " is not in docs/protocol.md's command table";
    EXPECT_EQ(it->second.first, c.name);
    EXPECT_EQ(it->second.second, dtmf_command_payload_text(c)) << c.name;
  }
}

// The microcode checks a command's length against KC_CLEN, indexed by
// type - CMD_FIRST below NCMD.
TEST(DtmfCommands, MicrocodeLengthTableIsTheDefinition) {
  const auto sc = sim::load_scene(std::string(ESKIN_SOURCE_DIR) + "/scenes/neuroskin2.yaml");
  const hls::EngineImage im = hls::dtmf_engine_image(hls::make_dtmf_top_plan(sim::dtmf_top_spec(sc)));
  EXPECT_EQ(im.symbol("CMD_FIRST"), 0x81);
  EXPECT_EQ(im.symbol("NCMD"), 9);
  const int64_t at = im.symbol("KC_CLEN");
  // The lengths docs/protocol.md gives by field (u8 + u32 = 5, ...).
  const int want[9] = {5, 3, 5, 1, 3, 0, 0, 3, 4};
  for (int t = 0; t < 9; ++t) EXPECT_EQ(im.krom.at(size_t(at + t)), uint32_t(want[t])) << t;
}

// Each encoder function writes its fields at the definition's widths, and
// the decoder reads them back; a payload one byte short is refused.
TEST(DtmfCommands, EncoderAndDecoderFollowTheDefinition) {
  link::LinkEncoder enc;
  link::LinkDecoder dec;
  const std::vector<std::vector<uint8_t>> frames = {
      enc.set_carrier_inc(4, 0x12345678u), enc.set_threshold(3, 0xBEEF), enc.set_neuron(0x13, -5),
      enc.set_output_mask(0x1F),           enc.set_decimation(2, 7),     enc.request_status(),
      enc.clear_counters(),                enc.set_weight(8, -300),      enc.set_demix_coef(0x0102, -2)};
  for (const auto& b : frames) dec.feed(b);
  link::Packet p;
  int i = 0;
  const uint32_t value[9] = {0x12345678u, 0xBEEF, uint32_t(-5), 0x1F, 7, 0, 0, uint16_t(-300),
                             0x0102u | uint32_t(uint16_t(-2)) << 16};
  const uint8_t index[9] = {4, 3, 0x13, 0, 2, 0, 0, 8, 0x02};
  while (dec.pop(p)) {
    ASSERT_LT(i, 9);
    const DtmfCommand& c = kDtmfCommands[i];
    EXPECT_EQ(p.type, c.type);
    EXPECT_EQ(p.payload.size(), size_t(c.payload_bytes())) << c.name;
    EXPECT_EQ(p.cmd_index, index[i]) << c.name;
    EXPECT_EQ(p.cmd_value, value[i]) << c.name;
    ++i;
  }
  EXPECT_EQ(i, 9);
  link::LinkDecoder short_dec;
  short_dec.feed(enc.frame(dtmf_cmd::kSetDecimation, 0, {1, 2}));
  EXPECT_FALSE(short_dec.pop(p));
  EXPECT_THROW(enc.command(0x80, 0, 0), std::invalid_argument);
}

}  // namespace
