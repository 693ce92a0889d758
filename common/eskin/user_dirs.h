// Where eskin keeps a user's own state, never in the source or build tree
// (which may belong to another user, e.g. root who built it):
//   cache    ${XDG_CACHE_HOME:-$HOME/.cache}/eskin      (the virtual board's
//            per-run files)
//   runtime  ${XDG_RUNTIME_DIR}/eskin, else CACHE/run   (port locks, control
//            sockets: things that live as long as a process)
// Both are created 0700 on first use; the error names the variable and the
// path when that fails.
#pragma once

#include <string>

namespace eskin {

std::string user_cache_dir();
std::string user_runtime_dir();

// A fresh directory PARENT/PREFIX-XXXXXX (mkdtemp, 0700), removed with
// everything in it when this is destroyed.
class ScratchDir {
 public:
  ScratchDir(const std::string& parent, const std::string& prefix);
  ~ScratchDir();
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace eskin
