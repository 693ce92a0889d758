// The line soak (docs/vboard.md, "Line faults: the soak"): a long DTMF
// scene on the virtual board (the default FPGA build) with faults on the
// serial line both ways, read through host/stream as eskin simulate reads
// it, and every packet the host delivered judged against what the FPGA
// sent (line_report.h). The host keeps the line busy both ways: for each
// AMPLITUDES packet it receives it sends `status_requests` REQUEST_STATUS
// commands, whose STATUS replies add to the packets the FPGA sends. Their
// timing follows the host's reading, so two runs differ a little in what
// is sent; the faults come from the seed.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "host/link/link_decoder.h"
#include "host/simulate/line_report.h"
#include "sim/vboard/line_faults.h"

namespace eskin::simulate {

struct SoakOptions {
  std::string scene;               // a DTMF scene of the default FPGA build
  vboard::LineFaultOptions line;   // the faults
  int status_requests = 4;         // REQUEST_STATUS per AMPLITUDES packet received
  std::string out = "eskin-soak";  // directory: the tap file, soak.json, report.html
};

struct SoakResult {
  LineReport line;
  uint64_t commands_sent = 0;     // REQUEST_STATUS written to the port
  uint64_t status_received = 0;   // STATUS packets delivered
  link::StatusBlock last_status;  // the board's counters, as the last STATUS delivered says
  double sim_s = 0, wall_s = 0, cpu_s = 0;
};

// Throws std::invalid_argument for a scene that is not a DTMF scene of the
// default build (naming it), std::runtime_error when the run fails.
SoakResult run_soak(const SoakOptions& o);

// The table: one row per figure, name,value,unit,source (docs/soak.csv,
// cited by the docs as <!--fig:soak/NAME-->).
std::string soak_csv(const SoakResult& r, const SoakOptions& o, const std::string& command);
std::string soak_text(const SoakResult& r);
// The table as {figure, value} rows, and the HTML report of them
// (run_soak writes OUT/report.html).
std::vector<std::vector<std::string>> soak_rows(const SoakResult& r);
void write_soak_report(const SoakResult& r, const SoakOptions& o, const std::string& path);

}  // namespace eskin::simulate
