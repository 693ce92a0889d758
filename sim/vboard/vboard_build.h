// The virtual board executable for an FPGA build (docs/vboard.md, "Which
// FPGA build a scene needs"). The default scene's board is prebuilt
// (eskin-vboard); any other build is made the first time a scene needs it:
// it is added to the build tree's list of boards (build/vboard/builds.cmake,
// read by sim/vboard/CMakeLists.txt) and built by CMake, i.e. Verilator's
// SystemC model of rtl/dtmf_top.v at the build's parameters plus
// vboard_main.cpp (of rtl/hall_top.v plus vboard_hall_main.cpp for a Hall
// build). That takes minutes once; later runs find it up to date
// (and rebuilt if the RTL changed).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "sim/vboard/fpga_params.h"
#include "sim/vboard/hall_build.h"
#include "sim/vboard/mixed_build.h"

namespace eskin::vboard {

// The board executable for `b`, built first when needed. `note` gets one
// line before a build starts (it takes minutes). Throws std::runtime_error
// naming the log and quoting its tail when CMake fails.
std::string board_executable(const FpgaBuild& b,
                             const std::function<void(const std::string&)>& note);
// The same for a Hall scene's build (rtl/hall_top.v, vboard_hall_main.cpp).
std::string board_executable(const HallBuild& b,
                             const std::function<void(const std::string&)>& note);
// The same for a scene with both (rtl/mixed_top.v, vboard_mixed_main.cpp).
std::string board_executable(const MixedBuild& b,
                             const std::function<void(const std::string&)>& note);

// The cycle level's board (vboard_cycle_main.cpp): one executable for
// every build it models, built with the project.
std::string cycle_board_executable();

// The default scene's board built with other Verilator options
// (sim/vboard/CMakeLists.txt's vboard_variants, for `eskin bench sim-speed
// --verilator`): their names, and a variant's executable, built first
// when needed (std::invalid_argument for a name that is not one).
std::vector<std::string> verilator_variants();
std::string variant_executable(const std::string& name,
                               const std::function<void(const std::string&)>& note);

}  // namespace eskin::vboard
