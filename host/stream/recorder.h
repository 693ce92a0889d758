// Recorders: where decoded rows (packet_table.h) go. One interface for the
// NDJSON stream, the CSV directory and the HDF5 file, so `eskin stream` and
// `eskin simulate` fan packets out the same way. Recorders are written from
// one thread (the stream's reader); flush() makes what was written so far
// durable, so a run that is killed keeps everything up to the last flush.
#pragma once

#include <fstream>
#include <map>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "host/link/link_decoder.h"
#include "host/stream/packet_table.h"

namespace eskin::stream {

class Recorder {
 public:
  virtual ~Recorder() = default;
  // Every packet, before its rows: for recorders that need a packet's
  // bounds (an empty TAXELS_SPARSE packet is a frame with no taxel on, but
  // has no rows).
  virtual void packet(const link::Packet&) {}
  virtual void write(const PacketKind& kind, const std::vector<Row>& rows) = 0;
  virtual void flush() = 0;
};

// One JSON object per row and line (packet_table.h: ndjson_line).
class NdjsonRecorder : public Recorder {
 public:
  explicit NdjsonRecorder(std::ostream& out) : out_(out) {}
  void write(const PacketKind& kind, const std::vector<Row>& rows) override;
  void flush() override { out_.flush(); }

 private:
  std::ostream& out_;
};

// DIR/<table>.csv, one per packet table, header line first: the scalar
// columns, then the vector column as NAME0..NAME(n-1) (n from the first
// row). A row whose vector length differs from the header is skipped and
// counted (rejected_rows), as the columns would no longer line up.
class CsvRecorder : public Recorder {
 public:
  explicit CsvRecorder(const std::string& dir);  // creates DIR; throws std::runtime_error
  void write(const PacketKind& kind, const std::vector<Row>& rows) override;
  void flush() override;
  uint64_t rejected_rows() const { return rejected_; }

 private:
  struct Table {
    std::ofstream f;
    size_t width = 0;
  };
  std::string dir_;
  std::map<std::string, Table> tables_;
  uint64_t rejected_ = 0;
};

// Fans one packet out to every recorder (converting it to rows once).
class RecorderSet {
 public:
  void add(std::unique_ptr<Recorder> r) { recorders_.push_back(std::move(r)); }
  void add(Recorder* r) { borrowed_.push_back(r); }
  // Packets of types without a packet_table entry are ignored (false).
  bool write(const link::Packet& p);
  void flush();

 private:
  std::vector<std::unique_ptr<Recorder>> recorders_;
  std::vector<Recorder*> borrowed_;
  std::vector<Row> rows_;
};

}  // namespace eskin::stream
