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

// mkdir -p PATH, each directory it creates 0700; the directories from
// index `own_from` on (eskin's own, e.g. ".../eskin") are checked to be
// directories and set to 0700 if this user owns them.
void make_private_dirs(const std::string& path, size_t own_from) {
  for (size_t at = 1; at <= path.size(); ++at) {
    if (at < path.size() && path[at] != '/') continue;
    const std::string part = path.substr(0, at);
    if (::mkdir(part.c_str(), 0700) != 0 && errno != EEXIST)
      throw std::runtime_error(part + ": cannot create eskin's per-user directory: " +
                               std::strerror(errno));
    if (at >= own_from) {
      struct stat st {};
      if (::stat(part.c_str(), &st) != 0 || !S_ISDIR(st.st_mode))
        throw std::runtime_error(part + ": not a directory (eskin's per-user directory)");
      if ((st.st_mode & 0777) != 0700 && st.st_uid == ::getuid()) ::chmod(part.c_str(), 0700);
    }
  }
}

// An XDG variable, or "" when unset or relative (the XDG spec says to
// ignore a relative one).
std::string abs_env(const char* name) {
  const char* v = std::getenv(name);
  return v && v[0] == '/' ? v : "";
}

}  // namespace

std::string user_cache_dir() {
  std::string cache = abs_env("XDG_CACHE_HOME");
  if (cache.empty()) {
    const std::string home = abs_env("HOME");
    if (home.empty())
      throw std::runtime_error("neither $XDG_CACHE_HOME nor $HOME is an absolute path: eskin "
                               "keeps its per-user files there");
    cache = home + "/.cache";
  }
  const std::string dir = cache + "/eskin";
  make_private_dirs(dir, cache.size() + 1);
  return dir;
}

std::string user_runtime_dir() {
  const std::string run = abs_env("XDG_RUNTIME_DIR");
  if (run.empty()) {
    const std::string dir = user_cache_dir() + "/run";
    make_private_dirs(dir, dir.size());
    return dir;
  }
  const std::string dir = run + "/eskin";
  make_private_dirs(dir, dir.size());
  return dir;
}

ScratchDir::ScratchDir(const std::string& parent, const std::string& prefix) {
  make_private_dirs(parent, parent.size());
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
