#include "hls/dtmf_ucode.h"

#include <fstream>
#include <stdexcept>

#include "dtmf_chain_fe.h"  // generated: kDtmfChainFe, the source text
#include "hls/frame_engine_asm.h"

namespace eskin::hls {

const std::string& dtmf_ucode_source() {
  static const std::string s(kDtmfChainFe);
  return s;
}

std::vector<uint32_t> dtmf_ucode_words(const EngineImage& image) {
  fe_asm::Options o;
  for (const auto& [name, value] : image.symbols) o.symbols[name] = value;
  o.imem_words = kDtmfImemWords;
  return fe_asm::assemble(dtmf_ucode_source(), "rtl/ucode/dtmf_chain.fe", o).words;
}

std::vector<VerilogParam> write_dtmf_top_build(const DtmfTopPlan& plan, const std::string& dir,
                                               const std::string& name) {
  const EngineImage image = dtmf_engine_image(plan);
  const std::string ucode = dir + "/" + name + ".ucode.hex", krom = dir + "/" + name + ".krom.hex";
  auto write = [](const std::string& path, const std::vector<uint32_t>& words) {
    std::ofstream f(path);
    f << fe_asm::readmemh_text(words);
    if (!f) throw std::runtime_error(path + ": cannot write");
  };
  write(ucode, dtmf_ucode_words(image));
  write(krom, image.krom);
  return dtmf_top_params(plan, image, ucode, krom);
}

}  // namespace eskin::hls
