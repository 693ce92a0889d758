#include "host/stream/recorder.h"

#include <filesystem>
#include <stdexcept>

namespace eskin::stream {

void NdjsonRecorder::write(const PacketKind& kind, const std::vector<Row>& rows) {
  for (const Row& r : rows) out_ << ndjson_line(kind, r) << '\n';
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

void CsvRecorder::flush() {
  for (auto& [name, t] : tables_) t.f.flush();
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

void RecorderSet::flush() {
  for (auto& r : recorders_) r->flush();
  for (Recorder* r : borrowed_) r->flush();
}

}  // namespace eskin::stream
