// The exit codes: docs/guide.md's table is common/eskin/exit_codes.h's list,
// `eskin --help` prints it, and the real CLI ends with the documented code
// for each kind of outcome (CLI11 would return its own 105, 106, 109, ...
// for parse errors; the table says 2). Codes 3 and 4 are checked by
// tests/stream/config_cli_test.cpp, 5 and 6 by the stream tests.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "eskin/exit_codes.h"
#include "eskin/process.h"

namespace fs = std::filesystem;

namespace {

struct CliRun {
  int code;
  std::string out;
};

std::string slurp(const fs::path& p) {
  std::ifstream f(p);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

fs::path scratch() {
  const fs::path d = fs::temp_directory_path() /
                     ("eskin_exit_codes_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

// `eskin ARGS` from an argument vector; stdout and stderr together.
CliRun run(std::vector<std::string> args) {
  args.insert(args.begin(), ESKIN_BIN);
  const fs::path log = scratch() / "log.txt";
  const int st = eskin::run_logged(args, log.string());
  return {WIFEXITED(st) ? WEXITSTATUS(st) : -1, slurp(log)};
}

struct Row {
  int code;
  std::string meaning;
};

std::vector<Row> header_rows() {
  std::vector<Row> rows;
#define ESKIN_EXIT_TEST_ROW(name, code, meaning) rows.push_back({code, meaning});
  ESKIN_EXIT_CODES(ESKIN_EXIT_TEST_ROW)
#undef ESKIN_EXIT_TEST_ROW
  return rows;
}

}  // namespace

TEST(ExitCodes, GuideTableIsTheHeadersList) {
  const std::string guide = slurp(fs::path(ESKIN_SOURCE_DIR) / "docs/guide.md");
  const size_t a = guide.find("<!--exit-codes-->"), b = guide.find("<!--/exit-codes-->");
  ASSERT_NE(a, std::string::npos) << "docs/guide.md: no <!--exit-codes--> table";
  ASSERT_NE(b, std::string::npos);
  std::istringstream table(guide.substr(a, b - a));
  std::vector<Row> doc;
  const std::regex row(R"(^\| (\d+) \| (.+) \|$)");
  for (std::string line; std::getline(table, line);) {
    std::smatch m;
    if (std::regex_match(line, m, row)) doc.push_back({std::stoi(m[1]), m[2]});
  }
  const std::vector<Row> want = header_rows();
  ASSERT_EQ(doc.size(), want.size()) << "docs/guide.md's exit code table has another length";
  for (size_t i = 0; i < want.size(); ++i) {
    EXPECT_EQ(doc[i].code, want[i].code) << "row " << i;
    EXPECT_EQ(doc[i].meaning, want[i].meaning) << "row " << i;
  }
}

TEST(ExitCodes, HelpPrintsTheTableAndExitsZero) {
  const CliRun r = run({"--help"});
  EXPECT_EQ(r.code, 0) << r.out;
  for (const Row& w : header_rows())
    EXPECT_NE(r.out.find("  " + std::to_string(w.code) + "  " + w.meaning), std::string::npos)
        << "eskin --help lacks exit code " << w.code << "\n" << r.out;
  EXPECT_EQ(run({"simulate", "--help"}).code, 0);
}

TEST(ExitCodes, CommandLineErrorsAreUsageErrors) {
  const int usage = eskin::exit_code(eskin::Exit::usage);
  // No subcommand, an unknown one, an unknown option, a missing positional,
  // a value that fails its check, an extra positional.
  const std::vector<std::vector<std::string>> bad = {
      {},
      {"no-such-command"},
      {"world", "--no-such-option", "x.yaml"},
      {"world"},
      {"stream", "--port", "/dev/null", "--flush-ms", "1"},
      {"golden", "a.yaml", "b.yaml", "c.yaml"},
  };
  for (const auto& args : bad) {
    const CliRun r = run(args);
    std::string line;
    for (const auto& s : args) line += " " + s;
    EXPECT_EQ(r.code, usage) << "eskin" << line << "\n" << r.out;
    EXPECT_FALSE(r.out.empty()) << "eskin" << line << " said nothing";
  }
}

TEST(ExitCodes, BadScenesAndArgumentValuesAreUsageErrors) {
  const int usage = eskin::exit_code(eskin::Exit::usage);
  const fs::path d = scratch();
  const fs::path scene = d / "bad_scene.yaml";
  std::ofstream(scene) << "skin:\n  rows: -3\n";
  for (const std::string cmd : {"world", "golden"}) {
    const CliRun r = run({cmd, scene.string()});
    EXPECT_EQ(r.code, usage) << "eskin " << cmd << " on a bad scene\n" << r.out;
    EXPECT_NE(r.out.find(scene.string()), std::string::npos)
        << "the error does not name the file\n" << r.out;
  }
  const CliRun unknown = run({"config", "--port", "/dev/null", "no-such-config-command"});
  EXPECT_EQ(unknown.code, usage) << unknown.out;
  EXPECT_NE(unknown.out.find("no-such-config-command"), std::string::npos) << unknown.out;
}

TEST(ExitCodes, AFailedRunIsFailure) {
  // The scene is fine; the output file cannot be written (its directory is
  // a regular file, which stops root too).
  const fs::path d = scratch();
  const fs::path file = d / "not_a_dir";
  std::ofstream(file) << "x";
  const CliRun r = run({"world", std::string(ESKIN_SOURCE_DIR) + "/scenes/neuroskin2.yaml",
                       "--csv", (file / "out.csv").string()});
  EXPECT_EQ(r.code, eskin::exit_code(eskin::Exit::failure)) << r.out;
  EXPECT_NE(r.out.find((file / "out.csv").string()), std::string::npos) << r.out;
}
