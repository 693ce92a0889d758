// Runs the built eskin CLI (ESKIN_BIN) from an argument vector, no shell:
// for tests whose arguments hold quotes, $(...) or ';' that must reach
// eskin as they are.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "eskin/process.h"
#include "host/bench/text_file.h"

struct ArgvResult {
  int status;       // exit code (-1: did not exit normally or could not start)
  std::string out;  // stdout and stderr together
};

// `eskin ARGS...` in `cwd` ("" : the test's own).
inline ArgvResult run_eskin_argv(const std::vector<std::string>& args, const std::string& cwd = "") {
  std::vector<std::string> argv{ESKIN_BIN};
  argv.insert(argv.end(), args.begin(), args.end());
  const std::string log = (std::filesystem::temp_directory_path() /
                           ("eskin_argv_" + std::to_string(::getpid()) + ".log")).string();
  eskin::RunContext ctx;
  ctx.cwd = cwd;
  const int st = eskin::run_logged(argv, log, eskin::LogMode::Truncate, ctx);
  ArgvResult r{st != -1 && WIFEXITED(st) ? WEXITSTATUS(st) : -1, eskin::bench::read_text(log)};
  std::filesystem::remove(log);
  return r;
}
