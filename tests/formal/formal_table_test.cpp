// The formal proofs' bookkeeping: docs/formal.csv (written by
// scripts/formal_table.sh, cited by docs/formal.md) names exactly the tasks
// of tests/formal/*.sby with their kinds and depths, each with the verdict
// it must have; every block the issue names has a proof, a cover task and
// a mutant whose text is still in its RTL. The proofs themselves run as
// ctest formal.MODULE.TASK; their times are a table, not a test (they
// depend on the machine's load).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
const fs::path kSrc = ESKIN_SOURCE_DIR;

std::string read_text(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  EXPECT_TRUE(f) << p << ": cannot be read";
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out(1);
  for (char c : s) {
    if (c == sep) out.emplace_back();
    else out.back().push_back(c);
  }
  return out;
}

struct Task {
  std::string mode, depth;
};

// The tasks of one .sby and each one's mode and depth (sby's default
// depth is 20), from its [tasks] and [options] sections.
std::map<std::string, Task> sby_tasks(const fs::path& sby) {
  std::map<std::string, Task> tasks;
  std::string section;
  std::vector<std::pair<std::string, std::string>> options;  // (tag or "", "key value")
  for (const auto& l : lines_of(read_text(sby))) {
    if (l.empty() || l[0] == '#') continue;
    if (l[0] == '[') {
      section = l;
      continue;
    }
    if (section == "[tasks]") tasks[l] = Task{"", "20"};
    if (section == "[options]") {
      const auto colon = l.find(": ");
      if (colon == std::string::npos) options.emplace_back("", l);
      else options.emplace_back(l.substr(0, colon), l.substr(colon + 2));
    }
  }
  for (auto& [name, t] : tasks)
    for (const auto& [tag, kv] : options) {
      if (!tag.empty() && tag != name) continue;
      const auto f = split(kv, ' ');
      if (f.size() == 2 && f[0] == "mode") t.mode = f[1];
      if (f.size() == 2 && f[0] == "depth") t.depth = f[1];
    }
  return tasks;
}

std::vector<fs::path> sby_files() {
  std::vector<fs::path> v;
  for (const auto& e : fs::directory_iterator(kSrc / "tests/formal"))
    if (e.path().extension() == ".sby") v.push_back(e.path());
  return v;
}

TEST(FormalTable, NamesEveryTaskWithItsKindDepthAndVerdict) {
  std::map<std::string, std::vector<std::string>> rows;  // module/task -> row
  bool header = false;
  for (const auto& l : lines_of(read_text(kSrc / "docs/formal.csv"))) {
    if (l.empty() || l[0] == '#') continue;
    const auto f = split(l, ',');
    if (!header) {
      EXPECT_EQ(l, "module,task,mode,depth,seconds,verdict") << "docs/formal.csv: header";
      header = true;
      continue;
    }
    ASSERT_EQ(f.size(), 6u) << "docs/formal.csv: " << l;
    EXPECT_TRUE(rows.emplace(f[0] + "/" + f[1], f).second) << "docs/formal.csv: twice: " << l;
  }
  size_t tasks = 0;
  for (const auto& sby : sby_files()) {
    const std::string module = sby.stem();
    for (const auto& [name, t] : sby_tasks(sby)) {
      ++tasks;
      const auto it = rows.find(module + "/" + name);
      if (it == rows.end()) {
        ADD_FAILURE() << "docs/formal.csv has no row for " << module << " " << name
                      << ": run scripts/formal_table.sh";
        continue;
      }
      const auto& r = it->second;
      EXPECT_EQ(r[2], t.mode) << module << " " << name << ": the table's mode is not the .sby's";
      EXPECT_EQ(r[3], t.depth) << module << " " << name << ": the table's depth is not the .sby's";
      const bool mutant = name.rfind("mutant", 0) == 0;
      EXPECT_EQ(r[5], mutant ? "FAIL" : "PASS") << module << " " << name;
      EXPECT_TRUE(t.mode == "prove" || t.mode == "bmc" || t.mode == "cover") << module << " " << name;
      if (mutant) {
        EXPECT_NE(t.mode, "cover") << module << ": a mutant must break a proof";
      }
    }
  }
  EXPECT_EQ(rows.size(), tasks) << "docs/formal.csv has rows for tasks no .sby has";
}

// Every block of issue 33 is proven, covered, and its proof shown able
// to fail; the mutant's text is still a line of its RTL (run_sby.sh
// would fail on a stale one, this says so before any proof runs).
TEST(FormalTable, EveryBlockHasAProofACoverAndALiveMutant) {
  const std::set<std::string> want = {"byte_fifo",  "link_framer", "cmd_decoder",
                                      "packet_arbiter", "stream_cdc", "uart_tx",
                                      "uart_rx", "i2c_master", "adc_ad7476"};
  std::set<std::string> have;
  for (const auto& sby : sby_files()) {
    const std::string module = sby.stem();
    have.insert(module);
    bool proof = false, cover = false, mutant = false;
    for (const auto& [name, t] : sby_tasks(sby)) {
      if (name.rfind("mutant", 0) == 0) mutant = true;
      else if (t.mode == "cover") cover = true;
      else proof = true;
    }
    EXPECT_TRUE(proof && cover && mutant) << sby << ": needs a proof, a cover and a mutant task";
    const fs::path spec = sby.parent_path() / (module + ".mutant");
    ASSERT_TRUE(fs::exists(spec)) << spec;
    std::string file, from, to;
    for (const auto& l : lines_of(read_text(spec))) {
      if (l.rfind("file ", 0) == 0) file = l.substr(5);
      if (l.rfind("from ", 0) == 0) from = l.substr(5);
      if (l.rfind("to ", 0) == 0) to = l.substr(3);
    }
    ASSERT_FALSE(file.empty() || from.empty() || to.empty()) << spec << ": file, from, to";
    EXPECT_NE(from, to) << spec;
    int hits = 0;
    for (const auto& l : lines_of(read_text(kSrc / "rtl" / file)))
      if (l.find(from) != std::string::npos) ++hits;
    EXPECT_EQ(hits, 1) << spec << ": its 'from' text is on " << hits << " lines of rtl/" << file;
    // The properties live in the module, under FORMAL.
    const std::string rtl = read_text(kSrc / "rtl" / (module + ".v"));
    EXPECT_NE(rtl.find("`ifdef FORMAL"), std::string::npos) << "rtl/" << module << ".v";
  }
  for (const auto& m : want) EXPECT_TRUE(have.count(m)) << "no proof of " << m;
}

}  // namespace
