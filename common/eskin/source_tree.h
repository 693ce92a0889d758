// Where a tool finds, at run time, the source tree (scripts, rtl/, scenes,
// baselines) and the build tree (the libraries and the CMake tree that the
// Verilator builds made at run time link and extend). Each is the
// environment's ESKIN_SOURCE_DIR / ESKIN_BUILD_DIR when set, so that an
// installed or moved binary can be pointed at a tree; else the trees it was
// built from.
#pragma once

#include <string>

namespace eskin {

std::string source_dir();
std::string build_dir();
// A path in the build tree as built (a compiled-in library path): the same
// path under build_dir().
std::string in_build_dir(const std::string& built_path);

}  // namespace eskin
