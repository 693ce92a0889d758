// Subcommand registry of the eskin CLI: each host/cli/cmd_*.cpp registers
// itself with a static ESKIN_COMMAND, so commands stay in their own files.
#pragma once

#include <CLI/CLI.hpp>

#include <functional>
#include <vector>

namespace eskin::cli {

// Adds a subcommand to `app`; returns the function that runs it (called
// after parsing, returns the process exit code).
using CommandSetup = std::function<std::function<int()>(CLI::App& app)>;

struct CommandEntry {
  const char* name;
  CommandSetup setup;
};

inline std::vector<CommandEntry>& command_registry() {
  static std::vector<CommandEntry> r;
  return r;
}

struct CommandRegistrar {
  CommandRegistrar(const char* name, CommandSetup setup) {
    command_registry().push_back({name, std::move(setup)});
  }
};

}  // namespace eskin::cli

#define ESKIN_CONCAT2(a, b) a##b
#define ESKIN_CONCAT(a, b) ESKIN_CONCAT2(a, b)
#define ESKIN_COMMAND(name, setup_fn) \
  static ::eskin::cli::CommandRegistrar ESKIN_CONCAT(eskin_cmd_, __LINE__)(name, setup_fn)
