#include "eskin/source_tree.h"

#include <cstdlib>

#if !defined(ESKIN_SOURCE_DIR) || !defined(ESKIN_BUILD_DIR)
#error "ESKIN_SOURCE_DIR and ESKIN_BUILD_DIR: the trees this library is built from (CMakeLists.txt)"
#endif

namespace eskin {

namespace {
std::string env_or(const char* name, const char* built) {
  const char* e = std::getenv(name);
  return e && *e ? e : built;
}
}  // namespace

std::string source_dir() { return env_or("ESKIN_SOURCE_DIR", ESKIN_SOURCE_DIR); }
std::string build_dir() { return env_or("ESKIN_BUILD_DIR", ESKIN_BUILD_DIR); }

std::string in_build_dir(const std::string& built_path) {
  const std::string built = ESKIN_BUILD_DIR;
  if (built_path.compare(0, built.size(), built) != 0) return built_path;
  return build_dir() + built_path.substr(built.size());
}

}  // namespace eskin
