// HDF5 recording of a stream run: one file per run.
//
//   /                      attributes: the run's configuration (endpoint,
//                          baud, start time, scene file and its YAML, ...)
//   /<table>/<column>      int64 [N]          one per scalar column
//   /<table>/<vector>      int64 [N, width]   the vector column, if any
// with <table> and the columns from packet_table.h (e.g. /amplitudes/t,
// /amplitudes/amp, /taxels/taxel, /spikes/neuron, /status/cmd_accepted).
//   /commands/<column>     [N] the commands sent during the run and their
//                          verdicts (recorder.h: command_columns()): int64
//                          host_ms, samples, cmd_type, seq; variable-length
//                          UTF-8 strings command, args, ack, message
//
// Datasets are chunked and extendible; rows are buffered and appended on
// flush() (the caller flushes regularly; at least every kFlushRows rows it
// happens anyway), which also flushes the file. The metadata cache never
// evicts between flushes, so the file on disk changes only inside flush():
// a run killed at any other moment leaves a file that opens and holds every
// row up to the last flush. Memory stays flat however long the run: the
// metadata cache evicts down to 256 KiB inside flush(), and each dataset's
// chunk cache holds two chunks (docs/bench.md, "Memory under a long stream").
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "host/stream/recorder.h"

namespace eskin::stream {

class Hdf5Recorder : public Recorder {
 public:
  static constexpr size_t kFlushRows = 65536;

  // Creates (truncates) `path`; attributes are written as string attributes
  // of the root group. Throws std::runtime_error naming the file.
  Hdf5Recorder(const std::string& path, const std::map<std::string, std::string>& attributes);
  ~Hdf5Recorder() override;
  Hdf5Recorder(const Hdf5Recorder&) = delete;
  Hdf5Recorder& operator=(const Hdf5Recorder&) = delete;

  void write(const PacketKind& kind, const std::vector<Row>& rows) override;
  void command(const CommandRecord& c) override;  // appended at the next flush()
  void flush() override;
  uint64_t rejected_rows() const { return rejected_; }  // vector width changed

 private:
  struct Table {
    int64_t group = -1;
    std::vector<int64_t> scalar_sets;  // hid_t per scalar column
    int64_t vector_set = -1;
    size_t width = 0;
    uint64_t rows_on_disk = 0;
    std::vector<std::vector<int64_t>> pending_scalars;  // per column
    std::vector<int64_t> pending_values;                // row-major
    size_t pending_rows = 0;
  };
  Table& table(const PacketKind& kind, size_t width);
  void append(const std::string& name, Table& t);  // throws when HDF5 refuses

  std::string path_;
  int64_t file_ = -1;
  std::map<std::string, Table> tables_;
  void append_commands();
  void set_evictions(bool on);  // the metadata cache's, inside flush() only
  int64_t commands_group_ = -1;
  std::vector<int64_t> command_sets_;  // hid_t per command_columns() entry
  uint64_t commands_on_disk_ = 0;
  std::vector<CommandRecord> pending_commands_;
  size_t pending_ = 0;
  uint64_t rejected_ = 0;
};

}  // namespace eskin::stream
