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

// A command the stream carried out while it recorded, with its verdict:
// recorded beside the data (NDJSON {"type":"command",...}, commands.csv,
// the HDF5 /commands group), in the order the verdicts came.
struct CommandRecord {
  int64_t host_ms = 0;     // wall clock at the verdict, ms since the Unix epoch
  int64_t samples = -1;    // the FPGA's sample counter in the STATUS that decided
                           // it (compare the rows' t); -1: no verdict
  std::string command;     // "set-mask"
  std::vector<std::string> args;  // as given ("0x7")
  std::string ack;         // accepted, rejected, unknown, no_verdict, error (not sent)
  std::string message;     // "rejected: value out of range", ...
  int64_t cmd_type = 0;    // the wire type and seq it went out with
  int64_t seq = 0;
};

// The columns of the commands table, in order (CSV header, HDF5 datasets).
const std::vector<const char*>& command_columns();

class Recorder {
 public:
  virtual ~Recorder() = default;
  // Every packet, before its rows: for recorders that need a packet's
  // bounds (an empty TAXELS_SPARSE packet is a frame with no taxel on, but
  // has no rows).
  virtual void packet(const link::Packet&) {}
  virtual void write(const PacketKind& kind, const std::vector<Row>& rows) = 0;
  virtual void command(const CommandRecord&) {}
  virtual void flush() = 0;
};

// One JSON object per row and line (packet_table.h: ndjson_line). A
// failed write (stdout is a pipe whose reader went away: EPIPE, with
// SIGPIPE ignored) does not throw, so the other recorders still get every
// packet: output stops, failed() says so and error() gives the errno.
class NdjsonRecorder : public Recorder {
 public:
  explicit NdjsonRecorder(std::ostream& out) : out_(out) {}
  void write(const PacketKind& kind, const std::vector<Row>& rows) override;
  void command(const CommandRecord& c) override;
  void flush() override;
  bool failed() const { return failed_; }
  int error() const { return error_; }

 private:
  void check();
  std::ostream& out_;
  bool failed_ = false;
  int error_ = 0;
};

// The NDJSON line of a command (no newline).
std::string command_ndjson(const CommandRecord& c);

// DIR/<table>.csv, one per packet table, header line first: the scalar
// columns, then the vector column as NAME0..NAME(n-1) (n from the first
// row). A row whose vector length differs from the header is skipped and
// counted (rejected_rows), as the columns would no longer line up.
class CsvRecorder : public Recorder {
 public:
  explicit CsvRecorder(const std::string& dir);  // creates DIR; throws std::runtime_error
  void write(const PacketKind& kind, const std::vector<Row>& rows) override;
  // DIR/commands.csv (command_columns(); args joined by spaces; text quoted).
  void command(const CommandRecord& c) override;
  void flush() override;
  uint64_t rejected_rows() const { return rejected_; }

 private:
  struct Table {
    std::ofstream f;
    size_t width = 0;
  };
  std::string dir_;
  std::ofstream commands_;
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
  void command(const CommandRecord& c);
  void flush();

 private:
  std::vector<std::unique_ptr<Recorder>> recorders_;
  std::vector<Recorder*> borrowed_;
  std::vector<Row> rows_;
};

// Refuses to record over an earlier recording: throws std::invalid_argument
// naming the file and --force when `hdf5_file` exists, or when `csv_dir`
// holds a table file this run would write (<table>.csv, commands.csv),
// unless `force`. Empty names are not checked.
void check_new_recording(const std::string& hdf5_file, const std::string& csv_dir, bool force);

}  // namespace eskin::stream
