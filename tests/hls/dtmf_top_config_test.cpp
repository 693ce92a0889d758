// hls/dtmf_top_config.h: the top's parameters derived from the default
// scene equal the defaults written in rtl/dtmf_top.v (which the RTL system
// test proves bit-exact against hls/dtmf_chain.h), read from the Verilog
// source itself; bad specs are rejected naming the field.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "hls/dtmf_top_config.h"
#include "sim/dtmf_top_spec.h"
#include "sim/scene.h"

namespace {

std::string slurp(const std::string& path) {
  std::ifstream f(path);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// "parameter integer NAME = VALUE" / "parameter [..] NAME = VALUE" of the top.
std::string verilog_default(const std::string& src, const std::string& name) {
  std::smatch m;
  const std::regex re("parameter[^;=]*\\b" + name + "\\s*=\\s*([^,\\n]+?)\\s*(,|\\n|\\))");
  if (!std::regex_search(src, m, re)) return "<missing>";
  return m[1].str();
}

// Numeric value of a Verilog literal: 16'd35, 35, 12_000_000, -5.
long long literal_value(std::string v) {
  v.erase(std::remove(v.begin(), v.end(), '_'), v.end());
  const auto q = v.find('\'');
  if (q == std::string::npos) return std::stoll(v);
  const char base = char(std::tolower(v[q + 1]));
  return std::stoll(v.substr(q + 2), nullptr, base == 'h' ? 16 : base == 'b' ? 2 : 10);
}

TEST(DtmfTopConfig, DefaultSceneReproducesTheTopsDefaults) {
  const auto sc = eskin::sim::load_scene(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml");
  const auto plan = eskin::hls::make_dtmf_top_plan(eskin::sim::dtmf_top_spec(sc));
  const std::string src = slurp(ESKIN_SOURCE_DIR "/rtl/dtmf_top.v");
  int checked = 0;
  for (const auto& p : eskin::hls::dtmf_top_params(plan)) {
    if (p.name == "CARRIER_INC") {
      // The default is written as a concatenation of 32'd values, highest k first.
      std::string want;
      std::smatch m;
      std::string rest = src.substr(src.find("CARRIER_INC ="));
      rest = rest.substr(0, rest.find("}"));
      std::regex d("32'd(\\d+)");
      std::vector<long long> incs;
      for (auto it = std::sregex_iterator(rest.begin(), rest.end(), d); it != std::sregex_iterator(); ++it)
        incs.push_back(std::stoll((*it)[1].str()));
      ASSERT_EQ(incs.size(), plan.carrier_inc.size());
      for (size_t k = 0; k < incs.size(); ++k)
        EXPECT_EQ(incs[incs.size() - 1 - k], plan.carrier_inc[k]) << "carrier " << k;
      ++checked;
      continue;
    }
    const std::string dv = verilog_default(src, p.name);
    ASSERT_NE(dv, "<missing>") << p.name;
    EXPECT_EQ(literal_value(dv), literal_value(p.value)) << p.name << ": top " << dv
                                                         << ", generated " << p.value;
    ++checked;
  }
  EXPECT_GE(checked, 20);
}

TEST(DtmfTopConfig, RejectsBadSpecsNamingTheField) {
  eskin::hls::DtmfTopSpec s;
  s.carrier_hz = {1900, 3300, 5000, 7140, 8300};  // one missing
  try {
    eskin::hls::make_dtmf_top_plan(s);
    FAIL() << "accepted 5 carriers for a 3x3 skin";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("skin.carriers"), std::string::npos) << e.what();
  }
  s.carrier_hz.push_back(10000);
  s.adc_bits = 14;
  EXPECT_THROW(eskin::hls::make_dtmf_top_plan(s), std::invalid_argument);
}

TEST(DtmfTopConfig, WrapperAndVerilatorArgumentsCarryEveryParameter) {
  const auto sc = eskin::sim::load_scene(ESKIN_SOURCE_DIR "/scenes/staggered10x10.yaml");
  const auto ps = eskin::hls::dtmf_top_params(
      eskin::hls::make_dtmf_top_plan(eskin::sim::dtmf_top_spec(sc)));
  const auto args = eskin::hls::verilator_g_args(ps);
  const std::string w = eskin::hls::dtmf_top_wrapper(ps, "top_10x10");
  ASSERT_EQ(args.size(), ps.size());
  for (size_t i = 0; i < ps.size(); ++i) {
    EXPECT_EQ(args[i], "-G" + ps[i].name + "=" + ps[i].value);
    EXPECT_NE(w.find("." + ps[i].name + "(" + ps[i].value + ")"), std::string::npos) << ps[i].name;
  }
  EXPECT_NE(w.find("module top_10x10"), std::string::npos);
}

}  // namespace
