#include "ucode/dtmf_ucode.h"

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <system_error>

#include <unistd.h>

#include "dtmf_chain_fe.h"  // generated: kDtmfChainFe, the source text
#include "ucode/frame_engine_asm.h"

namespace eskin::hls {

const std::string& dtmf_ucode_source() {
  static const std::string s(kDtmfChainFe);
  return s;
}

namespace {
fe_asm::Program assemble_for(const EngineImage& image) {
  fe_asm::Options o;
  for (const auto& [name, value] : image.symbols) o.symbols[name] = value;
  o.imem_words = kDtmfImemWords;
  // The program is built into the binary, which may run far from a source
  // tree: an .include must not read whatever file is at that path. Embed
  // an included file beside kDtmfChainFe and answer it here.
  o.read_include = [](const std::string&, std::string&) { return false; };
  return fe_asm::assemble(dtmf_ucode_source(), "rtl/ucode/dtmf_chain.fe", o);
}
}  // namespace

std::vector<uint32_t> dtmf_ucode_words(const EngineImage& image) {
  return assemble_for(image).words;
}

fe_asm::Program dtmf_ucode_program(const EngineImage& image) { return assemble_for(image); }

std::vector<std::string> dtmf_ucode_routines(const EngineImage& image) {
  const fe_asm::Program prog = assemble_for(image);
  std::vector<std::string> routine(prog.words.size(), "?");
  std::string current = "?";
  for (const auto& l : prog.listing) {
    // "; ====...==== NAME ==": the name is the last word before the closing "==".
    const std::string& t = l.text;
    if (t.rfind("; ====", 0) == 0 && t.size() > 3 && t.compare(t.size() - 3, 3, " ==") == 0) {
      const size_t end = t.size() - 3, begin = t.rfind(' ', end - 1) + 1;
      current = t.substr(begin, end - begin);
    }
    if (l.has_word && l.addr < routine.size()) routine[l.addr] = current;
  }
  return routine;
}

std::vector<VerilogParam> write_dtmf_top_build(const DtmfTopPlan& plan, const std::string& dir,
                                               const std::string& name) {
  const EngineImage image = dtmf_engine_image(plan);
  const std::string ucode = dir + "/" + name + ".ucode.hex", krom = dir + "/" + name + ".krom.hex";
  // Written beside and renamed over: a model being constructed reads either
  // the old file or the new one, never half of one.
  auto write = [](const std::string& path, const std::vector<uint32_t>& words) {
    const std::string tmp = path + ".tmp" + std::to_string(::getpid());
    {
      std::ofstream f(tmp);
      f << fe_asm::readmemh_text(words);
      if (!f.flush()) throw std::runtime_error(tmp + ": cannot write");
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) throw std::runtime_error(path + ": cannot replace: " + ec.message());
  };
  write(ucode, dtmf_ucode_words(image));
  write(krom, image.krom);
  return dtmf_top_params(plan, image, ucode, krom);
}

}  // namespace eskin::hls
