// frame_engine_asm: the two-pass assembler (see the header).
#include "ucode/frame_engine_asm.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <utility>

#include "ucode/frame_engine.h"

namespace eskin::hls::fe_asm {
namespace {

using namespace eskin::hls::fe;
using namespace eskin::hls::fe_asm::names;


std::string trim(const std::string& s) {
  size_t b = 0, e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  return s.substr(b, e - b);
}

bool is_ident_start(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool is_ident_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

// Register names: never symbols.
int xreg_index(const std::string& s) {
  if (s.size() == 2 && (s[0] == 'x' || s[0] == 'X') && s[1] >= '0' && s[1] <= '3') return s[1] - '0';
  return -1;
}
bool reserved(const std::string& s) {
  return xreg_index(s) >= 0 || s == "a" || s == "A" || s == "p" || s == "P";
}

// Characters of a symbol after its first: a local label's scope is joined
// to its name by '@' ("main@loop"), which no source text can spell.
bool is_sym_char(char c) { return is_ident_char(c) || c == '@'; }

// The mnemonics, which no macro may take.
bool is_mnemonic(const std::string& s) {
  for (const char* n : kDataNames)
    if (n && s == n) return true;
  for (const char* n : kCtlNames)
    if (s == n) return true;
  for (const char* n : {"j", "nop", "ldi", "addi", "lpac", "apac", "spac", "lta", "shlm", "shrm", "rndm"})
    if (s == n) return true;
  return false;
}

// The first white-space separated word of s, and the rest trimmed.
std::pair<std::string, std::string> first_word(const std::string& s) {
  size_t n = 0;
  while (n < s.size() && !std::isspace(static_cast<unsigned char>(s[n]))) ++n;
  return {s.substr(0, n), trim(s.substr(n))};
}

struct Macro {
  std::string name, file;  // where it is defined
  int line = 0;            // of its .macro
  std::vector<std::string> params;
  std::vector<std::pair<int, std::string>> body;  // (line, text)
};

// The assembler's state for one source.
class Assembler {
 public:
  Assembler(const std::string& file, const Options& opt) : file_(file), opt_(opt) {
    for (const auto& [name, value] : opt.symbols) {
      if (!is_symbol_name(name))
        throw AsmError(file_ + ":0: predefined symbol '" + name + "': not a valid name");
      symbols_[name] = value;
    }
  }

  Program run(const std::string& source) {
    const std::vector<std::string> lines = split_lines(source);
    for (int pass = 1; pass <= 2; ++pass) {
      pass_ = pass;
      addr_ = 0;
      conds_.clear();
      macros_.clear();
      recording_.reset();
      expansions_ = 0;
      scope_.clear();
      Frame top;
      top.path = std::filesystem::path(file_).lexically_normal().generic_string();
      top.name = file_;
      stack_.assign(1, top);
      read_lines(lines);
      if (bound_line_) fail_where(bound_where_, ".bound: expected an instruction after it");
    }
    prog_.symbols = symbols_;
    prog_.file = file_;
    return prog_;
  }

 private:
  // One source being read: the top file, an included file or one macro's
  // expansion.
  struct Frame {
    std::string path;      // a file's normalised path (cycles, relative includes)
    int line = 0;          // the line being assembled, 1-based
    const Macro* macro = nullptr;  // an expansion: its macro (the lines are in macro->file)
    std::string scope;     // an expansion: the scope of its @labels
    size_t conds = 0;      // open .if blocks when it began
    std::string name;      // a file: its name as given (errors, listing)
    std::vector<std::string> args;  // an expansion: its arguments
  };
  // A place in the source, as errors print it: "FILE:LINE" and, inside a
  // macro's expansion or an included file, where that came from.
  struct Where {
    std::string at, context;
  };

  static std::vector<std::string> split_lines(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    std::string l;
    while (std::getline(in, l)) lines.push_back(l);
    return lines;
  }

  const std::string& frame_file(const Frame& f) const { return f.macro ? f.macro->file : f.name; }

  Where where() const {
    Where w;
    w.at = frame_file(stack_.back()) + ":" + std::to_string(stack_.back().line);
    for (size_t i = stack_.size() - 1; i > 0; --i) {
      const Frame& parent = stack_[i - 1];
      w.context += w.context.empty() ? " (" : ", ";
      w.context += stack_[i].macro ? "in macro " + stack_[i].macro->name + " expanded at "
                                   : std::string("included from ");
      w.context += frame_file(parent) + ":" + std::to_string(parent.line);
    }
    if (!w.context.empty()) w.context += ")";
    return w;
  }

  // The lines of the innermost frame, one statement each; then the checks
  // that nothing it opened is left open.
  void read_lines(const std::vector<std::string>& lines) {
    for (size_t i = 0; i < lines.size(); ++i) {
      stack_.back().line = int(i) + 1;
      text_ = lines[i];
      statement(lines[i]);
    }
    close_frame("the end of the file");
  }

  void close_frame(const std::string& end) {
    if (recording_ && recording_frame_ == stack_.size())
      fail_where(recording_where_, ".macro " + recording_->name + ": no .endm before " + end);
    if (conds_.size() > stack_.back().conds)
      fail_where(conds_.back().where, ".if: no .endif before " + end);
  }

  // ---- errors ---------------------------------------------------------------
  [[noreturn]] void fail_where(const Where& w, const std::string& msg) const {
    throw AsmError(w.at + ": " + msg + w.context);
  }
  [[noreturn]] void fail(const std::string& msg) const { fail_where(where(), msg); }

  static bool is_symbol_name(const std::string& s) {
    if (s.empty() || !is_ident_start(s[0])) return false;
    for (char c : s)
      if (!is_sym_char(c)) return false;
    return !reserved(s);
  }

  // ---- local labels -----------------------------------------------------------
  // "@name" -> "SCOPE@name": SCOPE is the expansion's own in a macro's
  // lines, else the last global label. A macro's arguments are scoped where
  // it is invoked (this runs on the invocation line first), so `@done`
  // passed in stays the caller's.
  std::string scope_locals(const std::string& s) const {
    std::string out;
    for (size_t i = 0; i < s.size();) {
      if (s[i] != '@' || (i > 0 && is_sym_char(s[i - 1]))) {
        out += s[i++];
        continue;
      }
      size_t e = i + 1;
      while (e < s.size() && is_ident_char(s[e])) ++e;
      const std::string name = s.substr(i, e - i);
      if (name.size() < 2 || !is_ident_start(name[1]))
        fail("local label: expected a name after '@' (a letter or '_' first), got '" + name + "'");
      const std::string& scope = stack_.back().macro ? stack_.back().scope : scope_;
      if (scope.empty()) fail("local label '" + name + "': no global label above it to scope it");
      out += scope + name;
      i = e;
    }
    return out;
  }

  // ---- one line -----------------------------------------------------------------
  void statement(const std::string& raw) {
    std::string s = trim(raw.substr(0, raw.find(';')));
    if (recording_) return record(s);
    if (conditional(s)) return;
    // Labels, each scoped before the next: in "g: j @x" @x is g's.
    for (;;) {
      size_t n = 0;
      while (n < s.size() && is_sym_char(s[n])) ++n;
      if (n == 0 || n >= s.size() || s[n] != ':' || !(is_ident_start(s[0]) || s[0] == '@')) break;
      define_label(scope_locals(s.substr(0, n)));
      s = trim(s.substr(n + 1));
    }
    s = scope_locals(s);
    if (s.empty()) {
      list_line();
      return;
    }
    const auto [op, rest] = first_word(s);
    if (op == ".equ") return equ(rest);
    if (op == ".org") return org(rest);
    if (op == ".word") return word_directive(rest);
    if (op == ".bound") return bound(rest);
    if (op == ".macro") return begin_macro(rest);
    if (op == ".endm") fail(".endm: no .macro before it");
    if (op == ".include") return include(rest);
    if (!op.empty() && op[0] == '.')
      fail("directive: expected .equ, .org, .word, .bound, .if, .else, .endif, .macro, .endm or .include, got " +
           op);
    const auto m = macros_.find(op);
    if (m != macros_.end()) return expand(m->second, rest);
    const uint32_t at = addr_;
    emit(instruction(op, rest));
    if (bound_line_ && pass_ == 2) prog_.bounds[at] = bound_;
    bound_line_ = 0;
  }

  // `.bound COUNT[, LOOP]`: a bound of the next instruction (seeing only the
  // symbols defined above it, as .equ).
  void bound(const std::string& rest) {
    if (bound_line_) fail(".bound: the .bound of line " + std::to_string(bound_line_) +
                          " has no instruction yet");
    strict_ = true;
    struct Relax { bool& f; ~Relax() { f = false; } } relax{strict_};
    const std::vector<std::string> items = split_commas(rest);
    if (rest.empty() || items.size() > 2) fail(".bound: expected COUNT or COUNT, LOOP");
    bound_ = {eval(items[0], ".bound"), -1};
    if (bound_.count < 0) fail(".bound: expected a count >= 0, got " + std::to_string(bound_.count));
    if (items.size() == 2) bound_.per = value_in(items[1], ".bound: loop", 0, opt_.imem_words - 1);
    bound_line_ = stack_.back().line;
    bound_where_ = where();
    list_line();
  }

  // ---- macros -----------------------------------------------------------------
  // .macro NAME p1, p2 ... .endm: the lines between are kept, not assembled,
  // until `NAME a1, a2` assembles them with `\p1` replaced by a1's text.
  // Defined in the order of the source, like .equ: a macro is used below
  // its definition.
  void begin_macro(const std::string& rest) {
    const auto [name, params_text] = first_word(rest);
    if (name.empty()) fail(".macro: expected a name");
    if (!is_symbol_name(name) || name.find('@') != std::string::npos)
      fail(".macro: expected a name (a letter or '_', then letters, digits, '_'), got '" + name + "'");
    if (is_mnemonic(name)) fail(".macro " + name + ": the name of an instruction");
    const auto old = macros_.find(name);
    if (old != macros_.end())
      fail(".macro " + name + ": already defined at " + old->second.file + ":" +
           std::to_string(old->second.line));
    auto m = std::make_unique<Macro>();
    m->name = name;
    m->file = frame_file(stack_.back());
    m->line = stack_.back().line;
    if (!params_text.empty()) {
      for (const std::string& p : split_commas(params_text)) {
        if (!is_symbol_name(p) || p.find('@') != std::string::npos)
          fail(".macro " + name + ": expected a parameter name, got '" + p + "'");
        for (const auto& q : m->params)
          if (q == p) fail(".macro " + name + ": parameter '" + p + "' twice");
        m->params.push_back(p);
      }
    }
    recording_ = std::move(m);
    recording_frame_ = stack_.size();
    recording_where_ = where();
    list_line();
  }

  // A line of the macro being defined: kept as it is, or its .endm.
  void record(const std::string& code) {
    const auto [op, rest] = first_word(code);
    if (op == ".macro")
      fail(".macro: inside the definition of " + recording_->name + " (line " +
           std::to_string(recording_->line) + "); expected its .endm first");
    if (op == ".endm") {
      if (!rest.empty()) fail(".endm: expected nothing after it, got '" + rest + "'");
      const std::string name = recording_->name;
      macros_.emplace(name, std::move(*recording_));
      recording_.reset();
    } else {
      recording_->body.emplace_back(stack_.back().line, text_);
    }
    list_line();
  }

  void expand(const Macro& m, const std::string& rest) {
    std::vector<std::string> args;
    if (!rest.empty()) args = split_commas(rest);
    if (args.size() != m.params.size()) {
      std::string names;
      for (const auto& p : m.params) names += (names.empty() ? "" : ", ") + p;
      fail(m.name + ": expected " + std::to_string(m.params.size()) + " argument" +
           (m.params.size() == 1 ? "" : "s") + (names.empty() ? "" : " (" + names + ")") + ", got " +
           std::to_string(args.size()));
    }
    for (size_t i = 0; i < args.size(); ++i)
      if (args[i].empty()) fail(m.name + ": argument " + std::to_string(i + 1) + " is empty");
    for (const Frame& f : stack_) {
      if (f.macro && f.macro->name == m.name) {
        std::string chain;
        for (const Frame& g : stack_)
          if (g.macro) chain += g.macro->name + " -> ";
        fail(m.name + ": a macro cannot expand itself (" + chain + m.name + ")");
      }
    }
    nest_check();
    list_line();
    Frame f;
    f.macro = &m;
    f.scope = m.name + "@" + std::to_string(++expansions_);
    f.conds = conds_.size();
    f.args = args;
    stack_.push_back(std::move(f));
    for (const auto& [line, text] : m.body) {
      stack_.back().line = line;
      const std::string code = substitute(text);
      text_ = code;
      statement(code);
    }
    close_frame("the end of macro " + m.name);
    stack_.pop_back();
  }

  // Expansions and includes inside each other: a bound, against a cycle
  // the checks above cannot see (one file under two names).
  static constexpr size_t kMaxNesting = 64;
  void nest_check() const {
    if (stack_.size() > kMaxNesting)
      fail("macros and .include nested more than " + std::to_string(kMaxNesting) + " deep");
  }

  // A macro line with its parameters replaced (in the code, not the comment).
  std::string substitute(const std::string& text) const {
    const Frame& f = stack_.back();
    const size_t semi = text.find(';');
    const std::string code = text.substr(0, semi);
    std::string out;
    for (size_t i = 0; i < code.size();) {
      if (code[i] != '\\') {
        out += code[i++];
        continue;
      }
      size_t e = i + 1;
      while (e < code.size() && is_ident_char(code[e])) ++e;
      const std::string name = code.substr(i + 1, e - i - 1);
      size_t k = 0;
      while (k < f.macro->params.size() && f.macro->params[k] != name) ++k;
      if (k == f.macro->params.size()) {
        std::string names;
        for (const auto& p : f.macro->params) names += (names.empty() ? "" : " ") + ("\\" + p);
        fail(f.macro->name + ": '\\" + name + "' is not a parameter" +
             (names.empty() ? " (it has none)" : " (expected one of " + names + ")"));
      }
      out += f.args[k];
      i = e;
    }
    return semi == std::string::npos ? out : out + text.substr(semi);
  }

  // ---- .include "FILE" ----------------------------------------------------------
  void include(const std::string& rest) {
    if (rest.size() < 2 || rest.front() != '"' || rest.back() != '"' ||
        rest.find('"', 1) != rest.size() - 1)
      fail(".include: expected \"FILE\", got '" + rest + "'");
    const std::string name = rest.substr(1, rest.size() - 2);
    if (name.empty()) fail(".include: expected a file name between the quotes");
    const Frame* file_frame = nullptr;  // the including file
    for (const Frame& f : stack_)
      if (!f.macro) file_frame = &f;
    namespace fs = std::filesystem;
    const fs::path base = fs::path(file_frame->path).parent_path();
    const std::string path = (fs::path(name).is_absolute() ? fs::path(name) : base / name)
                                 .lexically_normal().generic_string();
    std::string chain;
    bool cycle = false;
    for (const Frame& f : stack_) {
      if (f.macro) continue;
      if (f.path == path) cycle = true;
      if (cycle) chain += f.path + " -> ";
    }
    if (cycle) fail(".include: an include cycle (" + chain + path + ")");
    nest_check();
    auto cached = files_.find(path);
    if (cached == files_.end()) {
      std::string text;
      bool ok = false;
      if (opt_.read_include) {
        ok = opt_.read_include(path, text);
      } else {
        std::ifstream in(path, std::ios::binary);
        if (in) {
          std::stringstream ss;
          ss << in.rdbuf();
          text = ss.str();
          ok = bool(in) || in.eof();
        }
      }
      if (!ok) fail(".include: cannot read \"" + path + "\"");
      cached = files_.emplace(path, split_lines(text)).first;
    }
    list_line();
    Frame f;
    f.path = path;
    f.name = path;
    f.conds = conds_.size();
    stack_.push_back(std::move(f));
    read_lines(cached->second);
    stack_.pop_back();
  }

  // ---- conditional assembly: .if EXPR / .else / .endif, nested ------------------
  // EXPR sees only the symbols defined above it (as .equ does), so both
  // passes take the same branches. Lines in a branch not taken are neither
  // assembled nor listed: their labels do not exist. A block opened in an
  // included file or a macro closes there.
  struct Cond {
    Where where;     // of the .if
    std::string file;
    int line;
    bool outer;      // every enclosing branch is taken
    bool taken;      // this branch is taken
    bool seen_else;
  };
  bool active() const { return conds_.empty() || (conds_.back().outer && conds_.back().taken); }

  // True when s is a conditional directive or a line inside a branch not taken.
  bool conditional(const std::string& s) {
    const auto [op, rest] = first_word(s);
    if (op == ".if") {
      bool taken = false;
      if (active()) {
        strict_ = true;
        struct Relax { bool& f; ~Relax() { f = false; } } relax{strict_};
        if (rest.empty()) fail(".if: expected an expression");
        taken = eval(scope_locals(rest), ".if") != 0;
      }
      conds_.push_back({where(), frame_file(stack_.back()), stack_.back().line, active(), taken, false});
      return true;
    }
    if (op == ".else" || op == ".endif") {
      if (conds_.size() <= stack_.back().conds) fail(op + ": no .if before it");
      if (!rest.empty()) fail(op + ": expected nothing after it, got '" + rest + "'");
      if (op == ".endif") {
        conds_.pop_back();
      } else {
        const Cond& c = conds_.back();
        if (c.seen_else)
          fail(".else: a second .else for the .if of " +
               (c.file == frame_file(stack_.back()) ? "line " + std::to_string(c.line) : c.where.at));
        conds_.back().seen_else = true;
        conds_.back().taken = !conds_.back().taken;
      }
      return true;
    }
    return !active();
  }

  void define_label(const std::string& name) {
    if (!is_symbol_name(name)) fail("label '" + name + "': a register name cannot be a label");
    if (pass_ == 1) {
      if (symbols_.count(name)) fail("label '" + name + "': already defined");
      symbols_[name] = addr_;
    }
    if (name.find('@') == std::string::npos) scope_ = name;
  }

  void equ(const std::string& rest) {
    strict_ = true;  // .equ and .org see only the symbols defined above them
    struct Relax { bool& f; ~Relax() { f = false; } } relax{strict_};
    const size_t comma = rest.find(',');
    if (comma == std::string::npos) fail(".equ: expected NAME, expression");
    const std::string name = trim(rest.substr(0, comma));
    if (!is_symbol_name(name)) fail(".equ: expected a symbol name, got '" + name + "'");
    if (pass_ == 1) {
      if (symbols_.count(name)) fail(".equ: '" + name + "' already defined");
      symbols_[name] = eval(rest.substr(comma + 1), ".equ");
    }
    list_line();
  }

  void org(const std::string& rest) {
    strict_ = true;
    struct Relax { bool& f; ~Relax() { f = false; } } relax{strict_};
    const int64_t v = eval(rest, ".org");
    if (v < 0 || v >= int64_t(opt_.imem_words))
      fail(".org: expected an IMEM address 0.." + std::to_string(opt_.imem_words - 1) +
           ", got " + std::to_string(v));
    addr_ = uint32_t(v);
    list_line();
  }

  void word_directive(const std::string& rest) {
    std::vector<std::string> items = split_commas(rest);
    if (items.empty() || (items.size() == 1 && items[0].empty())) fail(".word: expected a value");
    bool first = true;
    for (const auto& it : items) {
      const int64_t v = pass_ == 1 ? 0 : eval(it, ".word");
      if (v < -(int64_t(1) << 31) || v > 0xFFFFFFFFll)
        fail(".word: expected a 32-bit value, got " + std::to_string(v));
      emit(uint32_t(uint64_t(v)), !first);
      first = false;
    }
  }

  static std::vector<std::string> split_commas(const std::string& s) {
    std::vector<std::string> out;
    int depth = 0;
    std::string cur;
    for (char c : s) {
      if (c == '(' || c == '[') ++depth;
      if (c == ')' || c == ']') --depth;
      if (c == ',' && depth == 0) {
        out.push_back(trim(cur));
        cur.clear();
      } else {
        cur += c;
      }
    }
    out.push_back(trim(cur));
    return out;
  }

  // ---- output ---------------------------------------------------------------
  void emit(uint32_t word, bool continuation = false) {
    if (addr_ >= opt_.imem_words)
      fail("program: address " + std::to_string(addr_) + " is beyond the IMEM (" +
           std::to_string(opt_.imem_words) + " words)");
    if (pass_ == 2) {
      if (prog_.words.size() <= addr_) {
        prog_.words.resize(addr_ + 1, 0);
        written_.resize(addr_ + 1, {"", 0});
      }
      const std::string& file = frame_file(stack_.back());
      const int line = stack_.back().line;
      if (written_[addr_].second)
        fail("address " + std::to_string(addr_) + " already holds the word of " +
             (written_[addr_].first == file ? "line " : written_[addr_].first + ":") +
             std::to_string(written_[addr_].second));
      written_[addr_] = {file, line};
      prog_.words[addr_] = word;
      list(true, word, continuation ? "" : text_);
    }
    ++addr_;
  }
  void list_line() {
    if (pass_ == 2) list(false, 0, text_);
  }
  void list(bool has_word, uint32_t word, const std::string& text) {
    ListingLine l;
    l.line = stack_.back().line;
    l.has_word = has_word;
    l.addr = addr_;
    l.word = word;
    l.text = text;
    l.file = frame_file(stack_.back());
    for (size_t i = stack_.size() - 1; i > 0 && stack_[i].macro; --i) {
      if (l.depth++ == 0)
        l.expanded_at = frame_file(stack_[i - 1]) + ":" + std::to_string(stack_[i - 1].line);
    }
    prog_.listing.push_back(std::move(l));
  }

  // ---- expressions ------------------------------------------------------------
  // Evaluates `s` entirely; `what` names the operand in errors.
  int64_t eval(const std::string& s, const std::string& what) {
    expr_ = s;
    pos_ = 0;
    what_ = what;
    skip();
    if (pos_ >= expr_.size()) fail(what + ": expected an expression, got nothing");
    const int64_t v = parse_or();
    skip();
    if (pos_ < expr_.size())
      fail(what + ": expected an operator or the end of the expression, got '" + expr_.substr(pos_) + "'");
    return v;
  }
  void skip() {
    while (pos_ < expr_.size() && std::isspace(static_cast<unsigned char>(expr_[pos_]))) ++pos_;
  }
  bool take(const char* tok) {
    skip();
    const size_t n = std::char_traits<char>::length(tok);
    if (expr_.compare(pos_, n, tok) != 0) return false;
    // `<` and `<<`, `>` and `>>` are distinct; a lone `<` is no operator here.
    pos_ += n;
    return true;
  }
  int64_t parse_or() {
    int64_t v = parse_and();
    while (take("|")) v |= parse_and();
    return v;
  }
  int64_t parse_and() {
    int64_t v = parse_shift();
    while (take("&")) v &= parse_shift();
    return v;
  }
  int64_t parse_shift() {
    int64_t v = parse_add();
    for (;;) {
      if (take("<<")) {
        const int64_t n = parse_add();
        check_shift(n);
        v = int64_t(uint64_t(v) << n);
      } else if (take(">>")) {
        const int64_t n = parse_add();
        check_shift(n);
        v >>= n;
      } else {
        return v;
      }
    }
  }
  void check_shift(int64_t n) const {
    if (n < 0 || n > 63) fail(what_ + ": shift count: expected 0..63, got " + std::to_string(n));
  }
  int64_t parse_add() {
    int64_t v = parse_mul();
    for (;;) {
      if (take("+")) v = int64_t(uint64_t(v) + uint64_t(parse_mul()));
      else if (take("-")) v = int64_t(uint64_t(v) - uint64_t(parse_mul()));
      else return v;
    }
  }
  int64_t parse_mul() {
    int64_t v = parse_unary();
    while (take("*")) v = int64_t(uint64_t(v) * uint64_t(parse_unary()));
    return v;
  }
  int64_t parse_unary() {
    if (take("-")) return int64_t(0 - uint64_t(parse_unary()));
    if (take("~")) return ~parse_unary();
    if (take("+")) return parse_unary();
    return parse_primary();
  }
  int64_t parse_primary() {
    skip();
    if (pos_ >= expr_.size()) fail(what_ + ": expected a value, got the end of the expression");
    const char c = expr_[pos_];
    if (c == '(') {
      ++pos_;
      const int64_t v = parse_or();
      if (!take(")")) fail(what_ + ": expected ')'");
      return v;
    }
    if (c == '.' && (pos_ + 1 >= expr_.size() || !is_ident_char(expr_[pos_ + 1]))) {
      ++pos_;
      return addr_;
    }
    if (std::isdigit(static_cast<unsigned char>(c))) return parse_number();
    if (is_ident_start(c)) {
      size_t e = pos_;
      while (e < expr_.size() && is_sym_char(expr_[e])) ++e;
      const std::string name = expr_.substr(pos_, e - pos_);
      pos_ = e;
      if (reserved(name)) fail(what_ + ": '" + name + "' is a register, expected a value");
      const auto it = symbols_.find(name);
      if (it == symbols_.end()) {
        if (pass_ == 1 && !strict_) return 0;  // a label defined further down
        fail(what_ + ": undefined symbol '" + name + "'" +
             (strict_ ? " (.equ and .org see only symbols defined above them)" : ""));
      }
      return it->second;
    }
    fail(what_ + ": expected a number, a symbol or '(', got '" + expr_.substr(pos_) + "'");
  }
  int64_t parse_number() {
    int base = 10;
    if (expr_.compare(pos_, 2, "0x") == 0 || expr_.compare(pos_, 2, "0X") == 0) base = 16, pos_ += 2;
    else if (expr_.compare(pos_, 2, "0b") == 0 || expr_.compare(pos_, 2, "0B") == 0) base = 2, pos_ += 2;
    uint64_t v = 0;
    size_t digits = 0;
    while (pos_ < expr_.size()) {
      const char c = char(std::tolower(static_cast<unsigned char>(expr_[pos_])));
      int d = -1;
      if (c >= '0' && c <= '9') d = c - '0';
      else if (c >= 'a' && c <= 'f') d = 10 + c - 'a';
      else if (c == '_') { ++pos_; continue; }
      if (d < 0 || d >= base) {
        if (is_ident_char(c)) fail(what_ + ": malformed number near '" + expr_.substr(pos_) + "'");
        break;
      }
      if (v > (~uint64_t(0) - uint64_t(d)) / uint64_t(base))
        fail(what_ + ": number too large");
      v = v * uint64_t(base) + uint64_t(d);
      ++digits;
      ++pos_;
    }
    if (digits == 0) fail(what_ + ": expected digits after the number prefix");
    return int64_t(v);
  }

  // A value in [lo, hi], else an error naming the operand and the range.
  int64_t value_in(const std::string& s, const std::string& what, int64_t lo, int64_t hi) {
    const int64_t v = eval(s, what);
    if (pass_ == 2 && (v < lo || v > hi))
      fail(what + ": expected " + std::to_string(lo) + ".." + std::to_string(hi) + ", got " +
           std::to_string(v));
    return v;
  }

  // ---- operands -------------------------------------------------------------
  struct Operand {
    enum Kind { kMemory, kAccWord, kPWord, kImmediate } kind = kImmediate;
    uint32_t space = kDmem, x = 0, addr = 0;
    std::string text;  // the immediate expression
  };

  Operand operand(const std::string& raw, const std::string& op) {
    const std::string s = trim(raw);
    if (s.empty()) fail(op + ": expected an operand");
    Operand o;
    if (s == "a" || s == "A") { o.kind = Operand::kAccWord; return o; }
    if (s == "p" || s == "P") { o.kind = Operand::kPWord; return o; }
    size_t open = std::string::npos;
    if (s[0] == '[') { open = 0; o.space = kDmem; }
    else if ((s[0] == 'k' || s[0] == 'K') && trim(s.substr(1)).rfind('[', 0) == 0) {
      open = s.find('['); o.space = kKrom;
    } else if (s.size() > 2 && (s.compare(0, 2, "io") == 0 || s.compare(0, 2, "IO") == 0) &&
               trim(s.substr(2)).rfind('[', 0) == 0) {
      open = s.find('['); o.space = kIo;
    }
    if (open == std::string::npos) {
      o.kind = Operand::kImmediate;
      o.text = s;
      return o;
    }
    if (s.back() != ']') fail(op + ": expected ']' at the end of the memory operand '" + s + "'");
    o.kind = Operand::kMemory;
    address(s.substr(open + 1, s.size() - open - 2), op, o);
    return o;
  }

  // "expr", "xN", "expr + xN", "xN + expr", "xN - expr": the address and index.
  void address(const std::string& inner, const std::string& op, Operand& o) {
    std::string rest;
    size_t i = 0;
    bool found = false;
    while (i < inner.size()) {
      if (is_ident_start(inner[i]) && (i == 0 || !is_sym_char(inner[i - 1]))) {
        size_t e = i;
        while (e < inner.size() && is_sym_char(inner[e])) ++e;
        const int xi = xreg_index(inner.substr(i, e - i));
        if (xi >= 0) {
          if (found) fail(op + ": address: expected at most one index register");
          // It must be added: nothing before it but '+' (or the start).
          const std::string before = trim(rest);
          if (!before.empty() && before.back() != '+')
            fail(op + ": address: the index register must be added (expr + " +
                 inner.substr(i, e - i) + ")");
          if (!before.empty()) rest = before.substr(0, before.size() - 1);
          o.x = uint32_t(xi);
          found = true;
          i = e;
          // "xN + expr": drop the '+' that follows.
          size_t j = i;
          while (j < inner.size() && std::isspace(static_cast<unsigned char>(inner[j]))) ++j;
          if (j < inner.size() && inner[j] == '+' && trim(rest).empty()) i = j + 1;
          continue;
        }
        rest += inner.substr(i, e - i);
        i = e;
        continue;
      }
      rest += inner[i++];
    }
    rest = trim(rest);
    if (rest.empty()) {
      if (!found) fail(op + ": address: expected an expression inside [ ]");
      o.addr = 0;
      return;
    }
    o.addr = uint32_t(value_in(rest, op + ": address", -32768, 65535)) & 0xFFFFu;
  }

  uint32_t field_code(const std::string& suffix, const std::string& op) const {
    for (uint32_t f = 0; f < 8; ++f)
      if (suffix == kFieldNames[f]) return f;
    fail(op + ": field: expected " + kFieldList + ", got ." + suffix);
  }

  uint32_t xreg(const std::string& s, const std::string& op) const {
    const int xi = xreg_index(trim(s));
    if (xi < 0) fail(op + ": expected an index register x0..x3, got '" + trim(s) + "'");
    return uint32_t(xi);
  }

  uint32_t target(const std::string& s, const std::string& op) {
    return uint32_t(value_in(s, op + ": target", 0, int64_t(opt_.imem_words) - 1));
  }

  // ---- instructions -----------------------------------------------------------
  uint32_t instruction(const std::string& op_raw, const std::string& rest) {
    std::string op = op_raw, suffix;
    const size_t dot = op_raw.find('.');
    if (dot != std::string::npos) {
      op = op_raw.substr(0, dot);
      suffix = op_raw.substr(dot + 1);
      if (suffix.empty()) fail(op + ": expected a suffix after '.'");
    }
    // Aliases of the first draft.
    if (op == "ldi" || op == "addi") {
      if (!suffix.empty()) fail(op + ": an immediate takes no field");
      return data(op == "ldi" ? kLd : kAdd, "", rest, op, /*need_imm=*/true);
    }
    if (op == "lpac" || op == "apac" || op == "spac") {
      if (!suffix.empty()) fail(op + ": expected no suffix");
      // The shifted forms (P << 8, 15, 16) are not in the hardware.
      if (!trim(rest).empty() && eval(rest, op + ": P shift") != 0 && pass_ == 2)
        fail(op + ": P shift: expected 0 (P is added unshifted; use the fields of p or shl), got " +
             trim(rest));
      return preg(op == "lpac" ? kLd : op == "apac" ? kAdd : kSub, kW);
    }
    if (op == "lta") {
      if (!trim(rest).empty()) fail("lta: expected no operand (the field is the suffix: lta.h15)");
      return data(kLt, suffix, "a", op, false);
    }
    if (op == "shlm" || op == "shrm" || op == "rndm")
      return data(op == "shlm" ? kShl : op == "shrm" ? kShr : kRnd, suffix, rest, op, false);
    for (uint32_t f = 0; f < 15; ++f)
      if (op == kDataNames[f]) return data(f, suffix, rest, op, false);
    if (op == "j") {
      uint32_t cond = kAlways;
      if (!suffix.empty()) {
        bool ok = false;
        for (uint32_t c = 1; c < 8; ++c)
          if (suffix == kCondNames[c]) cond = c, ok = true;
        if (!ok) fail("j: condition: expected one of .eq .ne .lt .ge .gt .le .nv, got ." + suffix);
      }
      return ctl(kJ, 0, cond, target(rest, "j"));
    }
    if (!suffix.empty()) fail(op + ": expected no suffix, got ." + suffix);
    const std::vector<std::string> args = split_commas(rest);
    auto nargs = [&](size_t n) {
      const size_t have = (args.size() == 1 && args[0].empty()) ? 0 : args.size();
      if (have != n)
        fail(op + ": expected " + std::to_string(n) + " operand" + (n == 1 ? "" : "s") + ", got " +
             std::to_string(have));
    };
    if (op == "djnz") {
      nargs(2);
      return ctl(kDjnz, xreg(args[0], op), 0, target(args[1], op));
    }
    if (op == "call") { nargs(1); return ctl(kCall, 0, 0, target(args[0], op)); }
    if (op == "ret") { nargs(0); return ctl(kRet, 0, 0, 0); }
    if (op == "wait") {
      nargs(1);
      return ctl(kWait, 0, 0, uint32_t(value_in(args[0], "wait: event mask", 1, 0xFFFF)));
    }
    if (op == "sqrt") { nargs(0); return ctl(kSqrt, 0, 0, 0); }
    if (op == "sqrtr") { nargs(0); return ctl(kSqrtr, 0, 0, 0); }
    if (op == "ldx" || op == "addx") {
      nargs(2);
      const uint32_t v = uint32_t(value_in(args[1], op + ": value", -32768, 65535)) & 0xFFFFu;
      return ctl(op == "ldx" ? kLdx : kAddx, xreg(args[0], op), 0, v);
    }
    if (op == "tax" || op == "txa") {
      nargs(1);
      return ctl(op == "tax" ? kTax : kTxa, xreg(args[0], op), 0, 0);
    }
    if (op == "nop") { nargs(0); return ctl(kNopCtl, 0, 0, 0); }
    fail("unknown instruction '" + op_raw + "'");
  }

  // A data instruction: function fn on the operand `rest`.
  uint32_t data(uint32_t fn, const std::string& suffix, const std::string& rest,
                const std::string& op, bool need_imm) {
    Operand o = operand(rest, op);
    if (need_imm && o.kind != Operand::kImmediate) fail(op + ": expected an immediate value");
    const bool field_ok = fn != kSt && fn != kOut;
    if (!suffix.empty() && (!field_ok || o.kind == Operand::kImmediate))
      fail(op + ": expected no field " + (field_ok ? "with an immediate" : "(st/out move A[31:0])") +
           ", got ." + suffix);
    const uint32_t f = suffix.empty() ? kW : field_code(suffix, op);
    if (fn == kSt && !(o.kind == Operand::kMemory && o.space == kDmem))
      fail("st: expected a DMEM operand [addr + xN]");
    if (fn == kOut && !(o.kind == Operand::kMemory && o.space == kIo))
      fail("out: expected an IO operand io[addr + xN]");
    switch (o.kind) {
      case Operand::kAccWord: return mem(fn, kAcc, 0, f, 0);
      case Operand::kPWord: return preg(fn, f);
      case Operand::kMemory: return mem(fn, o.space, o.x, (fn == kSt || fn == kOut) ? 0 : f, o.addr);
      case Operand::kImmediate: break;
    }
    int64_t lo = -(int64_t(1) << 25), hi = (int64_t(1) << 25) - 1;
    std::string what = op + ": immediate";
    if (fn == kShl || fn == kShr || fn == kRnd) lo = 0, hi = 63, what = op + ": shift count";
    if (fn == kLt || fn == kMpy) lo = -32768, hi = 65535, what = op + ": 16-bit immediate";
    return imm(fn, int32_t(value_in(o.text, what, lo, hi)));
  }

  std::string file_;
  Options opt_;
  std::map<std::string, int64_t> symbols_;
  Program prog_;
  std::vector<std::pair<std::string, int>> written_;  // file, line of each written address (0: free)
  int pass_ = 1;
  std::string text_;  // the line being assembled, as the listing shows it
  uint32_t addr_ = 0;
  std::string expr_, what_;
  size_t pos_ = 0;
  bool strict_ = false;  // pass 1 tolerates labels not yet seen (only pass 2 encodes)
  int bound_line_ = 0;   // a .bound waiting for its instruction (its line)
  Where bound_where_;    // and where it is, for the error at the end
  Program::Bound bound_;
  std::vector<Cond> conds_;  // the open .if blocks, innermost last
  std::vector<Frame> stack_;  // the top file, then each .include and expansion inside it
  std::map<std::string, Macro> macros_;
  std::unique_ptr<Macro> recording_;  // the macro being defined (between .macro and .endm)
  size_t recording_frame_ = 0;        // stack_.size() at its .macro
  Where recording_where_;
  int expansions_ = 0;                // numbers each expansion's scope
  std::string scope_;                 // the last global label: scope of @labels outside macros
  std::map<std::string, std::vector<std::string>> files_;  // included files, read once
};

}  // namespace

Program assemble(const std::string& source, const std::string& file, const Options& opt) {
  return Assembler(file, opt).run(source);
}

Program assemble_file(const std::string& path, const Options& opt) {
  std::ifstream in(path);
  if (!in) throw AsmError(path + ": cannot read the file");
  std::stringstream ss;
  ss << in.rdbuf();
  return assemble(ss.str(), path, opt);
}

}  // namespace eskin::hls::fe_asm
