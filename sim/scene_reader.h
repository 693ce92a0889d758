// The YAML reading helpers of the scene loader (sim/scene.cpp) and of its
// Hall section (sim/hall_scene.cpp): typed values out of YAML nodes, every
// error located at FILE:LINE:COL with the field path and what was expected.
#pragma once

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "eskin/skin_config.h"
#include "sim/scene.h"

namespace eskin::sim::scene_detail {

inline std::string num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

inline size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<size_t> d(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) d[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diag = d[0];
    d[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      size_t up = d[j];
      d[j] = std::min({d[j] + 1, d[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return d[b.size()];
}

// Reads typed values out of YAML nodes, remembering where each field was so
// that errors found later (eskin::validate) still point at a line.
class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const YAML::Node& at, const std::string& field,
                         const std::string& what) const {
    int line = 0, col = 0;
    if (at.IsDefined()) {
      YAML::Mark m = at.Mark();
      if (!m.is_null()) line = m.line + 1, col = m.column + 1;
    }
    if (line == 0) {
      // Fall back to the closest enclosing field we saw.
      auto [l, c] = where(field);
      line = l, col = c;
    }
    throw SceneError(file_, line, col, field, what);
  }

  // The location of `field` or of its closest recorded parent.
  std::pair<int, int> where(std::string field) const {
    while (true) {
      auto it = marks_.find(field);
      if (it != marks_.end()) return it->second;
      size_t cut = field.find_last_of(".[");
      if (cut == std::string::npos || cut == 0) return {0, 0};
      field.resize(cut);
    }
  }

  void note(const YAML::Node& n, const std::string& field) {
    YAML::Mark m = n.Mark();
    if (!m.is_null()) marks_[field] = {m.line + 1, m.column + 1};
  }

  static std::string got(const YAML::Node& n) {
    if (!n.IsDefined() || n.IsNull()) return "nothing";
    if (n.IsSequence()) return "a list";
    if (n.IsMap()) return "a mapping";
    return "'" + n.Scalar() + "'";
  }

  // A mapping whose keys are all in `allowed` (typos are caught here).
  void mapping(const YAML::Node& n, const std::string& field,
               const std::vector<std::string>& allowed) {
    if (!n.IsMap()) fail(n, field, "expected a mapping, got " + got(n));
    note(n, field);
    std::vector<std::string> seen;
    for (const auto& kv : n) {
      std::string key = kv.first.IsScalar() ? kv.first.Scalar() : "?";
      std::string path = field.empty() ? key : field + "." + key;
      if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
        std::string list, best;
        size_t best_d = 3;
        for (const auto& a : allowed) {
          list += (list.empty() ? "" : ", ") + a;
          size_t d = edit_distance(key, a);
          if (d < best_d) best_d = d, best = a;
        }
        fail(kv.first, path,
             "expected one of " + list + (best.empty() ? "" : " (did you mean '" + best + "'?)") +
                 ", got unknown key '" + key + "'");
      }
      if (std::find(seen.begin(), seen.end(), key) != seen.end())
        fail(kv.first, path, "expected each key once, got a second '" + key + "'");
      seen.push_back(key);
      note(kv.second, path);
    }
  }

  double number(const YAML::Node& n, const std::string& field) {
    double v = 0;
    if (!n.IsScalar() || !YAML::convert<double>::decode(n, v) || !std::isfinite(v))
      fail(n, field, "expected a number, got " + got(n));
    return v;
  }

  long long integer(const YAML::Node& n, const std::string& field) {
    long long v = 0;
    if (!n.IsScalar() || !YAML::convert<long long>::decode(n, v))
      fail(n, field, "expected an integer, got " + got(n));
    return v;
  }

  bool boolean(const YAML::Node& n, const std::string& field) {
    bool v = false;
    if (!n.IsScalar() || !YAML::convert<bool>::decode(n, v))
      fail(n, field, "expected true or false, got " + got(n));
    return v;
  }

  std::string text(const YAML::Node& n, const std::string& field) {
    if (!n.IsScalar()) fail(n, field, "expected text, got " + got(n));
    return n.Scalar();
  }

  // A number in [lo, hi] (inclusive unless open_lo / open_hi).
  double ranged(const YAML::Node& n, const std::string& field, double lo, double hi,
                bool open_lo = false, const std::string& range = "") {
    double v = number(n, field);
    bool ok = (open_lo ? v > lo : v >= lo) && v <= hi;
    if (!ok) {
      std::string r = range;
      if (r.empty())
        r = std::isinf(hi) ? (open_lo ? "> " : ">= ") + num(lo)
                           : (open_lo ? "(" : "[") + num(lo) + ", " + num(hi) + "]";
      fail(n, field, "expected " + r + ", got " + num(v));
    }
    return v;
  }

  int int_ranged(const YAML::Node& n, const std::string& field, long long lo, long long hi) {
    long long v = integer(n, field);
    if (v < lo || v > hi)
      fail(n, field, "expected an integer in " + std::to_string(lo) + ".." + std::to_string(hi) +
                         ", got " + std::to_string(v));
    return int(v);
  }

  std::vector<double> numbers(const YAML::Node& n, const std::string& field) {
    if (!n.IsSequence()) fail(n, field, "expected a list of numbers, got " + got(n));
    std::vector<double> v;
    for (size_t i = 0; i < n.size(); ++i) {
      std::string f = field + "[" + std::to_string(i) + "]";
      note(n[i], f);
      v.push_back(number(n[i], f));
    }
    return v;
  }

  // A two-element list [a, b].
  std::pair<YAML::Node, YAML::Node> pair(const YAML::Node& n, const std::string& field,
                                         const std::string& shape) {
    if (!n.IsSequence() || n.size() != 2) fail(n, field, "expected " + shape + ", got " + got(n));
    return {n[0], n[1]};
  }

  // Converts a ConfigError from eskin::validate into a located SceneError.
  [[noreturn]] void rethrow(const ConfigError& e) const {
    std::string what = e.what();
    const std::string head = e.field() + ": ";
    if (what.compare(0, head.size(), head) == 0) what = what.substr(head.size());
    auto [line, col] = where(e.field());
    throw SceneError(file_, line, col, e.field(), what);
  }

  const std::string& file() const { return file_; }

 private:
  std::string file_;
  std::map<std::string, std::pair<int, int>> marks_;
};

inline YAML::Node parse_yaml(const std::string& text, const std::string& file) {
  try {
    return YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw SceneError(file, e.mark.line + 1, e.mark.column + 1, "(syntax)",
                     "expected valid YAML, got: " + e.msg);
  }
}

inline std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path, 0, 0, "(file)", std::string("cannot open: ") + std::strerror(errno));
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The `hall:` section (sim/hall_scene.cpp); stimuli must end by duration_s.
HallScene read_hall(Reader& r, const YAML::Node& n, double duration_s);

}  // namespace eskin::sim::scene_detail
