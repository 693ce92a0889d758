#include "host/stream/recorder.h"

#include <cerrno>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace eskin::stream {

namespace {

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const std::string& x : v) s += (s.empty() ? "" : " ") + x;
  return s;
}

// A CSV field: quoted, with quotes doubled, when it needs to be.
std::string csv_text(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

}  // namespace

const std::vector<const char*>& command_columns() {
  static const std::vector<const char*> c = {"host_ms", "samples", "command", "args",
                                             "ack",     "message", "cmd_type", "seq"};
  return c;
}

std::string command_ndjson(const CommandRecord& c) {
  // Keys in command_columns() order, args as an array of strings.
  nlohmann::ordered_json j = {{"type", "command"},   {"host_ms", c.host_ms},
                              {"samples", c.samples}, {"command", c.command},
                              {"args", c.args},       {"ack", c.ack},
                              {"message", c.message}, {"cmd_type", c.cmd_type},
                              {"seq", c.seq}};
  return j.dump();
}

void NdjsonRecorder::check() {
  if (failed_ || out_) return;
  failed_ = true;
  error_ = errno;  // set by the write that failed (EPIPE: the reader went away)
}

void NdjsonRecorder::write(const PacketKind& kind, const std::vector<Row>& rows) {
  if (failed_) return;
  for (const Row& r : rows) out_ << ndjson_line(kind, r) << '\n';
  check();
}

void NdjsonRecorder::command(const CommandRecord& c) {
  if (failed_) return;
  out_ << command_ndjson(c) << '\n';
  check();
}

void NdjsonRecorder::flush() {
  if (failed_) return;
  out_.flush();
  check();
}

CsvRecorder::CsvRecorder(const std::string& dir) : dir_(dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw std::runtime_error("--csv " + dir + ": cannot create directory: " + ec.message());
}

void CsvRecorder::write(const PacketKind& kind, const std::vector<Row>& rows) {
  for (const Row& r : rows) {
    auto it = tables_.find(kind.table);
    if (it == tables_.end()) {
      const std::string path = dir_ + "/" + kind.table + ".csv";
      Table t;
      t.f.open(path);
      if (!t.f) throw std::runtime_error(path + ": cannot create");
      t.width = r.values.size();
      for (size_t i = 0; i < kind.scalars.size(); ++i) t.f << (i ? "," : "") << kind.scalars[i];
      for (size_t i = 0; kind.vector_name && i < t.width; ++i) t.f << ',' << kind.vector_name << i;
      t.f << '\n';
      it = tables_.emplace(kind.table, std::move(t)).first;
    }
    Table& t = it->second;
    if (r.values.size() != t.width) {
      ++rejected_;
      continue;
    }
    for (size_t i = 0; i < r.scalars.size(); ++i) t.f << (i ? "," : "") << r.scalars[i];
    for (int64_t v : r.values) t.f << ',' << v;
    t.f << '\n';
  }
}

void CsvRecorder::command(const CommandRecord& c) {
  if (!commands_.is_open()) {
    const std::string path = dir_ + "/commands.csv";
    commands_.open(path);
    if (!commands_) throw std::runtime_error(path + ": cannot create");
    for (size_t i = 0; i < command_columns().size(); ++i)
      commands_ << (i ? "," : "") << command_columns()[i];
    commands_ << '\n';
  }
  commands_ << c.host_ms << ',' << c.samples << ',' << csv_text(c.command) << ','
            << csv_text(joined(c.args)) << ',' << csv_text(c.ack) << ',' << csv_text(c.message)
            << ',' << c.cmd_type << ',' << c.seq << '\n';
}

void CsvRecorder::flush() {
  for (auto& [name, t] : tables_) t.f.flush();
  if (commands_.is_open()) commands_.flush();
}

bool RecorderSet::write(const link::Packet& p) {
  const PacketKind* kind = find_kind(p.type);
  if (!kind) return false;
  for (auto& r : recorders_) r->packet(p);
  for (Recorder* r : borrowed_) r->packet(p);
  rows_.clear();
  kind->rows(p, rows_);
  for (auto& r : recorders_) r->write(*kind, rows_);
  for (Recorder* r : borrowed_) r->write(*kind, rows_);
  return true;
}

void RecorderSet::command(const CommandRecord& c) {
  for (auto& r : recorders_) r->command(c);
  for (Recorder* r : borrowed_) r->command(c);
}

void RecorderSet::flush() {
  for (auto& r : recorders_) r->flush();
  for (Recorder* r : borrowed_) r->flush();
}

void check_new_recording(const std::string& hdf5_file, const std::string& csv_dir, bool force) {
  if (force) return;
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!hdf5_file.empty() && fs::exists(fs::symlink_status(hdf5_file, ec)))
    throw std::invalid_argument("--hdf5 " + hdf5_file +
                                ": the file exists (an earlier recording?); pass --force to "
                                "overwrite it, or name a new file");
  if (csv_dir.empty()) return;
  std::vector<std::string> tables = {"commands"};
  for (const PacketKind& k : packet_kinds()) tables.push_back(k.table);
  std::string found;
  for (const std::string& t : tables) {
    const fs::path f = fs::path(csv_dir) / (t + ".csv");
    if (fs::exists(fs::symlink_status(f, ec))) found += (found.empty() ? "" : ", ") + f.string();
  }
  if (!found.empty())
    throw std::invalid_argument("--csv " + csv_dir + ": holds an earlier recording (" + found +
                                "); pass --force to overwrite it, or name a new directory");
}

}  // namespace eskin::stream
