// eskin: one program, one subcommand per task (see `eskin --help`).
#include <algorithm>
#include <exception>
#include <iostream>
#include <string>

#include "cli/command.h"
#include "eskin/skin_config.h"

int main(int argc, char** argv) {
  CLI::App app{"eskin: FPGA/HLS DSP pipeline for tactile skins (simulate, decode, verify)"};
  app.require_subcommand(1);
  auto& reg = eskin::cli::command_registry();
  std::sort(reg.begin(), reg.end(),
            [](const auto& a, const auto& b) { return std::string(a.name) < b.name; });
  std::vector<std::pair<CLI::App*, std::function<int()>>> runners;
  for (auto& entry : reg) {
    size_t before = app.get_subcommands({}).size();
    auto run = entry.setup(app);
    auto subs = app.get_subcommands({});
    if (subs.size() > before) runners.push_back({subs.back(), run});
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
    for (auto& [sub, run] : runners)
      if (sub->parsed()) return run();
  } catch (const eskin::ConfigError& e) {
    std::cerr << "eskin: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "eskin: error: " << e.what() << "\n";
    return 1;
  }
  return 1;
}
