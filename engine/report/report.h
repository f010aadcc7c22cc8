// `hitl report`: a recording to one self-contained HTML page (docs/report.md).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "base/common/expected.h"

namespace hitl::report {

struct ReportResult {
  std::string html_path;
  uint64_t bytes = 0;                  ///< the page's size
  std::size_t plots = 0;
  double seconds = 0;                  ///< wall time to read, draw and write
  std::vector<std::string> missing;    ///< what the log lacks (FlightLog::missing)
  std::vector<std::string> skipped;    ///< what a damaged log had that is not drawn (FlightLog::skipped, plots gnuplot could not draw)
};

/// Reads `tlog_path`, draws it and writes the page to `html_path`.
Expected<ReportResult> write_report(const std::string& tlog_path, const std::string& html_path);

}  // namespace hitl::report
