#include "eskin/user_dirs.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <vector>

namespace eskin {
namespace {

// PATH and its missing parents, each new one 0700.
void make_private_dirs(const std::string& path, const std::string& from) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return;
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  if (!parent.empty() && parent != path) make_private_dirs(parent.string(), from);
  if (::mkdir(path.c_str(), 0700) != 0 && errno != EEXIST)
    throw std::runtime_error(path + " (" + from + "): cannot create: " + std::strerror(errno));
}

std::string env(const char* name) {
  const char* v = std::getenv(name);
  return v && *v ? v : "";
}

}  // namespace

std::string user_cache_dir() {
  std::string dir, from;
  if (!(dir = env("XDG_CACHE_HOME")).empty()) {
    from = "$XDG_CACHE_HOME";
  } else if (!(dir = env("HOME")).empty()) {
    dir += "/.cache";
    from = "$HOME/.cache";
  } else {
    throw std::runtime_error("neither $XDG_CACHE_HOME nor $HOME is set: eskin keeps its per-user "
                             "files there");
  }
  dir += "/eskin";
  make_private_dirs(dir, from);
  return dir;
}

std::string user_runtime_dir() {
  const std::string run = env("XDG_RUNTIME_DIR");
  if (run.empty()) {
    const std::string dir = user_cache_dir() + "/run";
    make_private_dirs(dir, "$XDG_RUNTIME_DIR unset: the cache");
    return dir;
  }
  make_private_dirs(run + "/eskin", "$XDG_RUNTIME_DIR");
  return run + "/eskin";
}

ScratchDir::ScratchDir(const std::string& parent, const std::string& prefix) {
  make_private_dirs(parent, "scratch");
  std::string tmpl = parent + "/" + prefix + "-XXXXXX";
  std::vector<char> buf(tmpl.begin(), tmpl.end());
  buf.push_back('\0');
  if (!::mkdtemp(buf.data()))
    throw std::runtime_error(tmpl + ": cannot create: " + std::strerror(errno));
  path_ = buf.data();
}

ScratchDir::~ScratchDir() {
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

}  // namespace eskin
