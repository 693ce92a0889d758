// hls/ purity: every synthesizable kernel header is free of heap allocation,
// exceptions, RTTI and floating point (the rules of docs/fpga.md, "The HLS
// kernels' rules", and the data path contract). Three independent layers,
// each with its own negative control below, so each can fail:
//
// A. Instantiated code, -mgeneral-regs-only. The generated unit
//    (hls/CMakeLists.txt: #include of every hls/*.h except the kernels'
//    *_config.h configuration builders, then
//    the explicit instantiations of tests/hls/hls_purity_uses.h) is compiled
//    with -O2 -fno-exceptions -fno-rtti -mgeneral-regs-only. With general
//    registers only, GCC rejects ANY floating-point value in emitted code
//    (x87 and SSE are both off: "SSE register return with SSE disabled"), so
//    float use is a compile error at the offending line — more robust than
//    pattern-matching instructions, which the optimiser may reshape.
//    -fno-exceptions / -fno-rtti make throw/try/typeid/dynamic_cast compile
//    errors. Then `nm -C` must show no reference to allocation (operator
//    new/delete, malloc, calloc, realloc, free), exception runtime (__cxa_*,
//    _Unwind_*, std::__throw_*), RTTI (typeinfo, __dynamic_cast) or libm /
//    soft-float helpers (sqrt, sin, __adddf3, ...).
// B. Non-template inline code. A kernel's plain inline functions are not
//    emitted unless used, so the same unit is compiled again with
//    -fkeep-inline-functions (every inline function emitted; without
//    -mgeneral-regs-only, which the standard headers' own float helpers
//    would trip). `objdump -d -r -C` is parsed into functions; from every
//    function in namespace eskin, all functions it reaches in the object
//    (through call/relocation targets) must contain no floating-point
//    instruction (scalar/packed SSE arithmetic, conversions, x87) and
//    reference no forbidden symbol (list of A).
// C. Source scan of each kernel header (comments and literals stripped):
//    no float/double, floating literals, new/delete, malloc/free, throw/try/
//    catch, typeid/dynamic_cast, virtual, and no #include of <cmath>,
//    containers, <string>, <memory>, streams, <stdexcept>...; quoted includes
//    only of other kernel headers "hls/NAME.h" (not *_config.h). This is the
//    only layer that sees templates nobody instantiates.
// The negative controls (impure snippets written and compiled the same way)
// assert that each layer detects the violations it is responsible for.
// New kernels are covered automatically: the configure-time glob lists them,
// and a header added after cmake last ran is appended at run time
// (purity_unit.cpp), so even a stale build tree checks every kernel. To get
// a new template's code emitted (layer A), add a guarded instantiation block
// to tests/hls/hls_purity_uses.h; without one the test prints a note and the
// header is still compiled (B, with its inline functions) and scanned (C).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

struct RunResult {
  int status = 0;
  std::string out;
};

RunResult run(const std::string& cmd) {
  RunResult r;
  FILE* p = popen((cmd + " 2>&1").c_str(), "r");
  if (!p) return {-1, "popen failed: " + cmd};
  std::array<char, 4096> buf;
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) r.out.append(buf.data(), n);
  r.status = pclose(p);
  return r;
}

std::string quote(const std::string& s) { return "'" + s + "'"; }

const char* const kCommonFlags = "-std=c++17 -O2 -fno-exceptions -fno-rtti -w";

// Compiles `tu` to `obj`; `extra` adds the layer's flags.
RunResult compile(const std::string& tu, const std::string& obj, const std::string& extra,
                  const std::string& include_dir) {
  return run(std::string(quote(ESKIN_PURITY_CXX)) + " " + kCommonFlags + " " + extra + " -I" +
             quote(ESKIN_SOURCE_DIR) + " -I" + quote(include_dir) + " -c " + quote(tu) + " -o " +
             quote(obj));
}

// ---- forbidden symbols (demangled names) ----------------------------------
std::string forbidden_symbol(std::string s) {
  s = std::regex_replace(s, std::regex("[+-]0x[0-9a-f]+$"), "");
  static const std::regex alloc(
      "^(operator new|operator delete)|^(malloc|calloc|realloc|free|aligned_alloc|"
      "posix_memalign|memalign|valloc|strdup)$");
  static const std::regex exc("^(__cxa_|_Unwind_|std::__throw_|__gxx_personality)");
  static const std::regex rtti("^(typeinfo for|typeinfo name for|__dynamic_cast)");
  static const std::regex libm(
      "^(std::)?(sin|cos|tan|asin|acos|atan|atan2|sinh|cosh|tanh|exp|exp2|expm1|log|log2|"
      "log10|log1p|pow|sqrt|cbrt|hypot|floor|ceil|trunc|round|lround|llround|rint|lrint|"
      "llrint|nearbyint|fmod|remainder|fabs|frexp|ldexp|modf|fma|fmin|fmax|copysign|"
      "sincos)[fl]?$");
  static const std::regex softfloat("^__[a-z]+(sf|df|tf|xf)[0-9]?$");
  if (std::regex_search(s, alloc)) return "allocation: " + s;
  if (std::regex_search(s, exc)) return "exceptions: " + s;
  if (std::regex_search(s, rtti)) return "RTTI: " + s;
  if (std::regex_search(s, libm) || std::regex_search(s, softfloat)) return "float library: " + s;
  return "";
}

// ---- floating-point instructions (AT&T mnemonics) -------------------------
bool float_instruction(const std::string& m) {
  static const std::regex re(
      "^v?(add|sub|mul|div|sqrt|min|max|rcp|rsqrt|round|hadd|hsub|dp)(ss|sd|ps|pd)$|"
      "^v?u?comis[sd]$|^v?cmp[a-z]*(ss|sd|ps|pd)$|^v?cvt[a-z0-9]+$|^v?movs[sd]$|"
      "^vfn?m(add|sub)[a-z0-9]+$|"
      "^f(ld|ild|st|ist|add|sub|mul|div|sqrt|abs|chs|xch|ucom|com|prem|rnd|sin|cos|patan|"
      "ptan|scale|xtract|2xm1|yl2x)[a-z0-9]*$");
  return std::regex_match(m, re);
}

// Layer A: nm of the -mgeneral-regs-only object.
std::vector<std::string> check_symbols(const std::string& obj) {
  std::vector<std::string> bad;
  const RunResult r = run(std::string(quote(ESKIN_PURITY_NM)) + " -C " + quote(obj));
  if (r.status != 0) return {"nm failed: " + r.out};
  std::istringstream in(r.out);
  std::string line;
  static const std::regex sym("^\\s*(?:[0-9a-f]+\\s+)?([A-Za-z])\\s+(.+)$");
  std::smatch m;
  while (std::getline(in, line)) {
    if (!std::regex_match(line, m, sym)) continue;
    const std::string why = forbidden_symbol(m[2]);
    if (!why.empty()) bad.push_back(why + " (nm " + m[1].str() + ")");
  }
  return bad;
}

// Layer B: functions of the -fkeep-inline-functions object reachable from
// namespace eskin.
std::vector<std::string> check_disassembly(const std::string& obj) {
  const RunResult r = run(std::string(quote(ESKIN_PURITY_OBJDUMP)) +
                          " -d -r -C -w --no-show-raw-insn " + quote(obj));
  if (r.status != 0) return {"objdump failed: " + r.out};
  struct Fn {
    std::set<std::string> refs;
    std::vector<std::string> float_insns;
  };
  std::map<std::string, Fn> fns;
  static const std::regex label("^[0-9a-f]+ <(.+)>:$");
  static const std::regex insn("^\\s+[0-9a-f]+:\\s+(\\S+)(.*)$");
  static const std::regex reloc("\\s[0-9a-f]+: R_[A-Z0-9_]+\\s+(.+)$");
  static const std::regex target("<([^>]+)>");
  static const std::set<std::string> prefixes = {"rep", "repz", "repe", "repnz", "repne",
                                                 "lock", "bnd", "notrack", "data16", "cs", "ds"};
  std::istringstream in(r.out);
  std::string line, cur;
  std::smatch m;
  while (std::getline(in, line)) {
    if (std::regex_match(line, m, label)) {
      cur = m[1];
      fns[cur];
      continue;
    }
    if (cur.empty() || !std::regex_match(line, m, insn)) continue;
    std::string mnem = m[1], rest = m[2];
    std::istringstream words(line.substr(line.find(':') + 1));
    for (std::string w; words >> w;) {
      if (prefixes.count(w)) continue;
      mnem = w;
      break;
    }
    if (float_instruction(mnem)) fns[cur].float_insns.push_back(mnem);
    std::smatch rm;
    if (std::regex_search(line, rm, reloc))
      fns[cur].refs.insert(std::regex_replace(rm[1].str(), std::regex("[+-]0x[0-9a-f]+$"), ""));
    if (mnem.rfind("call", 0) == 0 || mnem.rfind("jmp", 0) == 0) {
      std::smatch tm;
      if (std::regex_search(rest, tm, target))
        fns[cur].refs.insert(std::regex_replace(tm[1].str(), std::regex("\\+0x[0-9a-f]+$"), ""));
    }
  }
  std::vector<std::string> bad;
  std::set<std::string> seen;
  std::vector<std::string> todo;
  for (const auto& [name, fn] : fns)
    if (name.find("eskin::") != std::string::npos) todo.push_back(name), seen.insert(name);
  while (!todo.empty()) {
    const std::string name = todo.back();
    todo.pop_back();
    const Fn& fn = fns[name];
    if (!fn.float_insns.empty())
      bad.push_back("floating-point instruction " + fn.float_insns.front() + " in " + name);
    for (const std::string& ref : fn.refs) {
      const std::string why = forbidden_symbol(ref);
      if (!why.empty()) bad.push_back(why + " referenced by " + name);
      if (fns.count(ref) && !seen.count(ref)) seen.insert(ref), todo.push_back(ref);
    }
  }
  return bad;
}

// Layer C: source tokens.
std::vector<std::string> check_source(const std::string& text, const std::string& file) {
  std::vector<std::string> bad;
  // Includes, from the raw lines.
  static const std::regex inc("^\\s*#\\s*include\\s*([<\"])([^>\"]+)[>\"]");
  static const std::set<std::string> denied = {
      "cmath", "math.h", "cfloat", "float.h", "complex", "valarray", "random", "vector",
      "string", "string_view", "map", "unordered_map", "set", "unordered_set", "list",
      "forward_list", "deque", "queue", "stack", "memory", "memory_resource", "functional",
      "any", "stdexcept", "exception", "typeinfo", "iostream", "istream", "ostream", "sstream",
      "fstream", "cstdio", "stdio.h", "cstdlib", "stdlib.h", "thread", "mutex", "regex", "new"};
  {
    std::istringstream in(text);
    std::string line;
    std::smatch m;
    for (int ln = 1; std::getline(in, line); ++ln) {
      if (!std::regex_search(line, m, inc)) continue;
      const std::string what = m[2];
      const std::string where = file + ":" + std::to_string(ln) + ": ";
      if (m[1] == "<" && denied.count(what)) bad.push_back(where + "#include <" + what + ">");
      if (m[1] == "\"" && !std::regex_match(what, std::regex("hls/[A-Za-z0-9_]+\\.h")))
        bad.push_back(where + "#include \"" + what + "\" (only hls/NAME.h kernels)");
      if (m[1] == "\"" && std::regex_search(what, std::regex("_config\\.h$")))
        bad.push_back(where + "#include \"" + what + "\" (configuration builder)");
    }
  }
  // Tokens, with comments, string and character literals skipped.
  static const std::set<std::string> words = {"float", "double", "new", "delete", "throw",
                                              "try", "catch", "typeid", "dynamic_cast",
                                              "virtual"};
  static const std::set<std::string> calls = {"malloc", "calloc", "realloc", "free"};
  const size_t n = text.size();
  int ln = 1;
  std::string prev_tok;
  auto next_nonspace = [&](size_t i) {
    while (i < n && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
    return i < n ? text[i] : '\0';
  };
  for (size_t i = 0; i < n;) {
    const char c = text[i];
    if (c == '\n') { ++ln; ++i; continue; }
    if (c == '/' && i + 1 < n && text[i + 1] == '/') {
      while (i < n && text[i] != '\n') ++i;
      continue;
    }
    if (c == '/' && i + 1 < n && text[i + 1] == '*') {
      i += 2;
      while (i + 1 < n && !(text[i] == '*' && text[i + 1] == '/')) ln += text[i++] == '\n';
      i += 2;
      continue;
    }
    if (c == '"' || c == '\'') {
      for (++i; i < n && text[i] != c; ++i) {
        if (text[i] == '\\') ++i;
        else if (text[i] == '\n') ++ln;
      }
      ++i;
      prev_tok = "literal";
      continue;
    }
    if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
      size_t j = i;
      while (j < n && (std::isalnum(static_cast<unsigned char>(text[j])) || text[j] == '_')) ++j;
      const std::string w = text.substr(i, j - i);
      const std::string where = file + ":" + std::to_string(ln) + ": ";
      if (words.count(w) && !(w == "delete" && prev_tok == "="))
        bad.push_back(where + "'" + w + "'");
      if (calls.count(w) && next_nonspace(j) == '(') bad.push_back(where + "'" + w + "('");
      prev_tok = w;
      i = j;
      continue;
    }
    const bool dot_num = c == '.' && i + 1 < n && std::isdigit(static_cast<unsigned char>(text[i + 1]));
    if (std::isdigit(static_cast<unsigned char>(c)) || dot_num) {
      size_t j = i;
      while (j < n) {
        const char d = text[j];
        if (std::isalnum(static_cast<unsigned char>(d)) || d == '.' || d == '\'' || d == '_') {
          ++j;
        } else if ((d == '+' || d == '-') && j > i &&
                   std::string("eEpP").find(text[j - 1]) != std::string::npos) {
          ++j;
        } else {
          break;
        }
      }
      const std::string num = text.substr(i, j - i);
      const bool hex = num.size() > 1 && num[0] == '0' && (num[1] == 'x' || num[1] == 'X');
      const bool is_float = hex ? num.find_first_of("pP.") != std::string::npos
                                : num.find_first_of(".eE") != std::string::npos;
      if (is_float) bad.push_back(file + ":" + std::to_string(ln) + ": literal " + num);
      prev_tok = num;
      i = j;
      continue;
    }
    if (!std::isspace(static_cast<unsigned char>(c))) prev_tok = std::string(1, c);
    ++i;
  }
  return bad;
}

std::string read_file(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

std::vector<fs::path> kernel_headers() {
  std::vector<fs::path> v;
  for (const auto& e : fs::directory_iterator(fs::path(ESKIN_SOURCE_DIR) / "hls")) {
    const std::string name = e.path().filename().string();
    if (e.path().extension() == ".h" &&
        !std::regex_search(name, std::regex("_config\\.h$")))
      v.push_back(e.path());
  }
  std::sort(v.begin(), v.end());
  return v;
}

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += "  " + x + "\n";
  return s;
}

const fs::path kDir = ESKIN_PURITY_DIR;

// The unit the compile layers use: the configure-time unit, plus an include
// of any kernel header added since cmake last ran (so a stale build tree
// still checks every kernel), before the uses file.
std::string purity_unit(std::vector<std::string>* added = nullptr) {
  std::string tu = read_file(ESKIN_PURITY_TU);
  const std::string uses_inc = "#include \"tests/hls/hls_purity_uses.h\"";
  std::string extra;
  for (const auto& h : kernel_headers()) {
    const std::string inc = "#include \"hls/" + h.filename().string() + "\"";
    if (tu.find(inc) == std::string::npos) {
      extra += inc + "\n";
      if (added) added->push_back(h.filename().string());
    }
  }
  const size_t at = tu.find(uses_inc);
  tu.insert(at == std::string::npos ? tu.size() : at, extra);
  fs::create_directories(kDir);
  const std::string path = (kDir / "purity_unit.cpp").string();
  std::ofstream(path) << tu;
  return path;
}

// hls/ is the kernels and their configuration, nothing else: every file is
// a kernel header NAME.h, the configuration builder NAME_config.h of a
// kernel NAME.h beside it, or the CMakeLists.txt that lists them. Host
// tools (the frame engine's toolchain, the board planner) live elsewhere
// (ucode/, common/eskin/).
TEST(HlsPurity, HlsHoldsOnlyKernelsAndTheirConfiguration) {
  const fs::path hls = fs::path(ESKIN_SOURCE_DIR) / "hls";
  int kernels = 0;
  for (const auto& e : fs::directory_iterator(hls)) {
    const std::string name = e.path().filename().string();
    if (name == "CMakeLists.txt") continue;
    EXPECT_TRUE(e.is_regular_file() && e.path().extension() == ".h")
        << "hls/" << name << ": not a kernel header";
    std::smatch m;
    if (std::regex_match(name, m, std::regex("(.+)_config\\.h")))
      EXPECT_TRUE(fs::exists(hls / (m[1].str() + ".h")))
          << "hls/" << name << ": a configuration without its kernel hls/" << m[1] << ".h";
    else
      ++kernels;
  }
  EXPECT_GE(kernels, 10);
}

TEST(HlsPurity, GeneratedUnitCoversKernelHeaders) {
  const std::string tu = read_file(ESKIN_PURITY_TU);
  const std::string uses = read_file(fs::path(ESKIN_SOURCE_DIR) / "tests/hls/hls_purity_uses.h");
  const auto headers = kernel_headers();
  ASSERT_GE(headers.size(), 1u);
  // Every header the configure-time glob listed still exists, host-side
  // builders are excluded, and the uses come last.
  static const std::regex inc_re("#include \"(hls/[^\"]+)\"");
  int listed = 0;
  for (std::sregex_iterator it(tu.begin(), tu.end(), inc_re), end; it != end; ++it, ++listed) {
    const std::string rel = (*it)[1];
    EXPECT_TRUE(fs::exists(fs::path(ESKIN_SOURCE_DIR) / rel)) << rel << " listed but gone";
    EXPECT_FALSE(std::regex_search(rel, std::regex("_config\\.h$"))) << rel;
  }
  EXPECT_GE(listed, 1);
  EXPECT_GT(tu.find("tests/hls/hls_purity_uses.h"), tu.rfind("#include \"hls/"));
  std::vector<std::string> added;
  purity_unit(&added);
  for (const auto& h : added)
    std::printf("note: hls/%s is newer than the configured unit; checked via purity_unit.cpp "
                "(re-run cmake to list it)\n", h.c_str());
  // Not a failure (such kernels are still compiled and scanned); a reminder.
  for (const auto& h : headers) {
    const std::string inc = "\"hls/" + h.filename().string() + "\"";
    if (uses.find("__has_include(" + inc + ")") == std::string::npos)
      std::printf("note: hls/%s has no instantiation block in tests/hls/hls_purity_uses.h\n",
                  h.filename().string().c_str());
  }
}

TEST(HlsPurity, SourceScanOfKernelHeaders) {
  for (const auto& h : kernel_headers()) {
    const auto bad = check_source(read_file(h), "hls/" + h.filename().string());
    EXPECT_TRUE(bad.empty()) << "impure source:\n" << join(bad);
  }
}

TEST(HlsPurity, InstantiatedKernelsGeneralRegistersOnly) {
  fs::create_directories(kDir);
  const std::string obj = (kDir / "purity_a.o").string();
  const RunResult c = compile(purity_unit(), obj, "-mgeneral-regs-only", kDir.string());
  ASSERT_EQ(c.status, 0) << "kernel code does not compile without float registers, "
                            "exceptions or RTTI:\n" << c.out;
  const auto bad = check_symbols(obj);
  EXPECT_TRUE(bad.empty()) << "forbidden references:\n" << join(bad);
  // The object really holds kernel code (instantiation worked).
  const RunResult nm = run(std::string(quote(ESKIN_PURITY_NM)) + " -C --defined-only " + quote(obj));
  EXPECT_NE(nm.out.find("eskin::hls::CarrierMagnitude<24, 16, 8>::magnitude"), std::string::npos)
      << nm.out;
}

TEST(HlsPurity, InlineFunctionsDisassembly) {
  fs::create_directories(kDir);
  const std::string obj = (kDir / "purity_b.o").string();
  const RunResult c = compile(purity_unit(), obj, "-fkeep-inline-functions", kDir.string());
  ASSERT_EQ(c.status, 0) << c.out;
  const auto bad = check_disassembly(obj);
  EXPECT_TRUE(bad.empty()) << "impure code reachable from eskin::\n" << join(bad);
}

// ---- negative controls ----------------------------------------------------
struct Control {
  const char* name;
  const char* header;  // written as NAME.h, included by a one-line unit
  bool by_a, by_b, by_c;  // layers that must detect it
};

const Control kControls[] = {
    {"new_in_template",
     "#include <cstdint>\nnamespace eskin::hls {\ntemplate <int N> struct K {\n"
     "  int32_t* f() const { return new int32_t[N]; }\n};\ntemplate struct K<4>;\n}\n",
     true, true, true},
    {"malloc_free",
     "#include <cstdlib>\nnamespace eskin::hls {\ntemplate <int N> struct K {\n"
     "  int f() const { void* p = malloc(N); free(p); return p != nullptr; }\n};\n"
     "template struct K<8>;\n}\n",
     true, true, true},
    {"vector_in_unused_inline",
     "#include <vector>\nnamespace eskin::hls {\n"
     "inline int f(int n) { std::vector<int> v(n); return int(v.size()); }\n}\n",
     false, true, true},
    {"throw_in_template",
     "namespace eskin::hls {\ntemplate <int N> struct K {\n"
     "  int f(int x) const { if (x > N) throw x; return x; }\n};\ntemplate struct K<1>;\n}\n",
     true, true, true},
    {"typeid_in_template",
     "#include <typeinfo>\nnamespace eskin::hls {\ntemplate <class T> struct K {\n"
     "  const char* f() const { return typeid(T).name(); }\n};\ntemplate struct K<int>;\n}\n",
     true, true, true},
    {"float_in_template",
     "namespace eskin::hls {\ntemplate <int N> struct K {\n"
     "  int f(int x) const { float y = float(x) / N; return int(y * y); }\n};\n"
     "template struct K<3>;\n}\n",
     true, true, true},
    {"libm_on_integers",
     "#include <cmath>\nnamespace eskin::hls {\ntemplate <int N> struct K {\n"
     "  int f(int x) const { return int(std::sqrt(x)) + N; }\n};\ntemplate struct K<2>;\n}\n",
     true, true, true},
    {"float_literal_uninstantiated",
     "namespace eskin::hls {\ntemplate <int N> struct K {\n"
     "  int f(int x) const { return int(x * 0.5) + N; }\n};\n}\n",
     false, false, true},
    {"float_in_unused_inline",
     "namespace eskin::hls {\ninline int half(int x) { return int(x * 0.5f); }\n}\n",
     false, true, true},
};

TEST(HlsPurity, NegativeControlsAreDetected) {
  const fs::path dir = kDir / "controls";
  fs::create_directories(dir);
  for (const Control& ctl : kControls) {
    const std::string base = ctl.name;
    const fs::path hdr = dir / (base + ".h"), tu = dir / (base + ".cpp");
    std::ofstream(hdr) << ctl.header;
    std::ofstream(tu) << "#include \"" << base << ".h\"\n";
    // Layer A: compile error or forbidden symbol.
    const std::string obj_a = (dir / (base + "_a.o")).string();
    const RunResult ca = compile(tu.string(), obj_a, "-mgeneral-regs-only", dir.string());
    const bool a = ca.status != 0 || !check_symbols(obj_a).empty();
    // Layer B: compile error or disassembly finding.
    const std::string obj_b = (dir / (base + "_b.o")).string();
    const RunResult cb = compile(tu.string(), obj_b, "-fkeep-inline-functions", dir.string());
    const bool b = cb.status != 0 || !check_disassembly(obj_b).empty();
    // Layer C: source scan.
    const bool c = !check_source(ctl.header, base + ".h").empty();
    std::printf("control %-30s detected by A:%d B:%d C:%d\n", ctl.name, a, b, c);
    if (ctl.by_a) {
      EXPECT_TRUE(a) << base << " not detected by layer A (nm / general regs)";
    }
    if (ctl.by_b) {
      EXPECT_TRUE(b) << base << " not detected by layer B (disassembly)";
    }
    if (ctl.by_c) {
      EXPECT_TRUE(c) << base << " not detected by layer C (source scan)";
    }
  }
}

// A pure control: integer-only kernel code (64-bit multiply, shifts,
// division, static arrays, deleted copy) passes all three layers, so the
// checks do not reject what the contract allows.
TEST(HlsPurity, PureControlPasses) {
  const fs::path dir = kDir / "controls";
  fs::create_directories(dir);
  const char* header =
      "#include <cstdint>\nnamespace eskin::hls {\n"
      "inline int64_t mul_round(int64_t a, int32_t b, int s) {\n"
      "  return (a * b + (int64_t(1) << (s - 1))) >> s;  // round half up\n}\n"
      "template <int N> struct K {\n  K() = default;\n  K(const K&) = delete;\n"
      "  int32_t buf[N] = {};\n  uint32_t idx = 0x1fu;\n"
      "  int32_t push(int32_t x) { buf[idx % N] = x; ++idx; int64_t s = 0;\n"
      "    for (int i = 0; i < N; ++i) s += mul_round(buf[i], 3, 1);\n"
      "    return int32_t(s / 7); }\n};\ntemplate struct K<16>;\n}\n";
  const fs::path hdr = dir / "pure.h", tu = dir / "pure.cpp";
  std::ofstream(hdr) << header;
  std::ofstream(tu) << "#include \"pure.h\"\n";
  const std::string obj_a = (dir / "pure_a.o").string(), obj_b = (dir / "pure_b.o").string();
  const RunResult ca = compile(tu.string(), obj_a, "-mgeneral-regs-only", dir.string());
  ASSERT_EQ(ca.status, 0) << ca.out;
  EXPECT_TRUE(check_symbols(obj_a).empty()) << join(check_symbols(obj_a));
  const RunResult cb = compile(tu.string(), obj_b, "-fkeep-inline-functions", dir.string());
  ASSERT_EQ(cb.status, 0) << cb.out;
  EXPECT_TRUE(check_disassembly(obj_b).empty()) << join(check_disassembly(obj_b));
  EXPECT_TRUE(check_source(header, "pure.h").empty()) << join(check_source(header, "pure.h"));
}

}  // namespace
