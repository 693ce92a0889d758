// Runs the built eskin CLI (ESKIN_BIN) as a user would, for the system tests.
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

struct CliResult {
  int status;       // exit code (-1: did not exit normally)
  std::string out;  // stdout and stderr together
};

// `eskin ARGS` through the shell.
inline CliResult run_eskin(const std::string& args) {
  const std::string cmd = std::string(ESKIN_BIN) + " " + args + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  CliResult r{-1, ""};
  if (!p) return r;
  std::array<char, 4096> buf;
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) r.out.append(buf.data(), n);
  const int st = pclose(p);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return r;
}
