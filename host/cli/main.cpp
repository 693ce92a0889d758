// eskin: one program, one subcommand per task (see `eskin --help`).
#include <algorithm>
#include <exception>
#include <iostream>
#include <string>

#include "cli/command.h"
#include "eskin/exit_codes.h"
#include "eskin/skin_config.h"
#include "sim/scene.h"

namespace {

// The table under `eskin --help`, from eskin/exit_codes.h.
std::string exit_code_footer() {
  std::string s = "\nExit codes:";
#define ESKIN_EXIT_ROW(name, code, meaning) s += "\n  " + std::to_string(code) + "  " + meaning;
  ESKIN_EXIT_CODES(ESKIN_EXIT_ROW)
#undef ESKIN_EXIT_ROW
  return s + "\n";
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"eskin: FPGA/HLS DSP pipeline for tactile skins (simulate, decode, verify)"};
  app.require_subcommand(1);
  app.footer(exit_code_footer());
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
    // CLI11 prints the message (and --help / --version), but its own codes
    // (105, 106, ...) are not ours: a parse error is a usage error.
    const int cli11 = app.exit(e);
    return cli11 == 0 ? exit_code(eskin::Exit::ok) : exit_code(eskin::Exit::usage);
  }
  try {
    for (auto& [sub, run] : runners)
      if (sub->parsed()) return run();
  } catch (const eskin::ConfigError& e) {  // a configuration file
    std::cerr << "eskin: error: " << e.what() << "\n";
    return exit_code(eskin::Exit::usage);
  } catch (const eskin::sim::SceneError& e) {  // a scene file
    std::cerr << "eskin: error: " << e.what() << "\n";
    return exit_code(eskin::Exit::usage);
  } catch (const std::invalid_argument& e) {  // an argument's value
    std::cerr << "eskin: error: " << e.what() << "\n";
    return exit_code(eskin::Exit::usage);
  } catch (const std::exception& e) {
    std::cerr << "eskin: error: " << e.what() << "\n";
    return exit_code(eskin::Exit::failure);
  }
  return exit_code(eskin::Exit::failure);
}
