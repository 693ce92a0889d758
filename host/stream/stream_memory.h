// The streaming path's memory under a long stream: the real `eskin stream`
// process reads a real pty, into whose master N packets are written in the
// mix a DTMF board sends, and its resident set (/proc/PID/status VmRSS,
// VmHWM) is sampled as the packets go through. A stream that keeps
// something per packet (an unbounded queue, a growing table) shows as RSS
// growing with the packet count once the buffers are warm; a flat stream
// does not. `eskin bench memory` (docs/bench.md) and
// tests/stream/stream_memory_test.cpp run it.
//
// The mix, per frame, the packet types a DTMF board sends
// (docs/protocol.md §6) at a small skin's sizes: AMPLITUDES (16 values),
// TAXELS dense 4x4 and SPIKES (1..3 events), and a STATUS every 1000
// frames, with the encoder's sequence numbers (host/link/link_encoder.h).
// What the measurement needs is the packet count and every type's path
// through the stream and the recorder, not one build's exact sizes. The stream is ended by closing the master
// (a pty that hangs up ends `eskin stream`) once the child has read every
// byte, so its final count must be exactly N.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace eskin::stream {

struct MemoryOptions {
  std::string eskin_bin;        // the eskin executable to run as `eskin stream`
  uint64_t packets = 10000000;  // packets written into the pty
  // RSS sample period in packets (0: min(10^6, packets / 10)).
  uint64_t sample_every = 0;
  int baud = 3000000;           // --baud for the stream (a pty takes any rate)
  bool hdf5 = false;            // record --hdf5 into a temporary file (removed after)
  // A run that makes no progress (the child stops reading) for this long fails.
  double stall_s = 60;
};

struct MemorySample {
  uint64_t packets = 0;   // packets written into the pty when sampled
  uint64_t rss_kib = 0;   // VmRSS of `eskin stream`
  uint64_t hwm_kib = 0;   // VmHWM (its peak RSS so far)
  double seconds = 0;     // since the first packet was written
};

struct MemoryResult {
  std::vector<std::string> argv;      // the `eskin stream` command run
  bool hdf5 = false;                  // it recorded --hdf5
  uint64_t packets_written = 0;
  uint64_t wire_bytes = 0;
  std::vector<MemorySample> samples;  // at 0, every sample_every, and at the end
  uint64_t sample_every = 0;
  int exit_code = -1;                 // of `eskin stream` (128 + signal if killed; -1 none)
  bool counted = false;               // its final "N packets; link {...}" line was found
  uint64_t packets_counted = 0;       // N of that line
  uint64_t frames_ok = 0, lost_packets = 0, corrupt_frames = 0;  // its link statistics
  uint64_t hdf5_bytes = 0;            // size of the recording (hdf5 runs)
  double wall_s = 0;                  // first packet written .. child exited
  std::string error;                  // why the run could not complete ("" if it did)
  std::string child_stderr;

  // The first sample after warm-up (packets == sample_every) and the last.
  const MemorySample& warm() const;
  const MemorySample& last() const { return samples.back(); }
  int64_t growth_kib() const { return int64_t(last().rss_kib) - int64_t(warm().rss_kib); }
  // The run completed, exit 0, every packet counted once, none lost or corrupt.
  bool delivered_all() const;
};

// Runs the measurement. Throws std::runtime_error when the pty or the
// child cannot be set up; a child that fails or stalls is reported in
// MemoryResult (error, exit_code), not thrown.
MemoryResult measure_stream_memory(const MemoryOptions& o);

// A readable table of the samples and the verdict's figures.
std::string memory_text(const MemoryResult& r);
// The docs table: `name,value,unit,source` rows under a comment header that
// names `command` (docs/stream_memory.csv).
std::string memory_csv(const MemoryResult& r, const std::string& command);

}  // namespace eskin::stream
