// `hitl report`: a recording to one self-contained HTML page (docs/report.md).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "base/common/expected.h"
#include "engine/report/dygraphs.h"
#include "engine/report/flight_log.h"

namespace hitl::report {

/// Which ULog of PX4 to merge (docs/report.md "PX4's ULog beside the truth") and which page.
struct ReportOptions {
  std::string ulog_path;   ///< --ulog: this one ("" : look beside the recording when find_ulog)
  bool find_ulog = true;   ///< the newest FILE.px4/log/**.ulg beside FILE.tlog, when there is one
  bool static_page = false;  ///< --static: gnuplot's SVGs, no script (else the interactive page, interactive.h)
  std::string dygraphs_dir = kDebianDygraphsDir;  ///< --dygraphs: where libjs-dygraphs' files are
  std::string generator;   ///< "hitl 0.1.0": said in the page's header ("" : not said)
  std::vector<FieldPlotSpec> field_plots;  ///< --plot: one plot each, after the report's own (field_expression.h)
};

struct ReportResult {
  std::string html_path;
  uint64_t bytes = 0;                  ///< the page's size
  std::size_t plots = 0;
  double seconds = 0;                  ///< wall time to read, draw and write
  std::vector<std::string> missing;    ///< what the log lacks (FlightLog::missing)
  std::vector<std::string> skipped;    ///< what a damaged log had that is not drawn (FlightLog::skipped, plots gnuplot could not draw)
  std::string ulog_path;               ///< PX4's ULog merged ("" : none)
  bool ulog_found = false;             ///< it was found beside the recording, not given
  std::optional<Px4Estimate> px4;      ///< what it gave (the offset against truth)
  bool interactive = false;            ///< the interactive page was written (else the static one)
  std::string static_because;          ///< why the static page was written when the interactive one was asked for ("" : it was not)
};

/// Reads `tlog_path` (and PX4's ULog as `options` say), draws it and writes the page to `html_path`:
/// the interactive page unless `options.static_page`, or the static one, said in `static_because`,
/// when dygraphs' files are missing.
/// A ULog given that cannot be merged is an Error; one found beside the recording that cannot be is
/// said in `missing` and left out.
Expected<ReportResult> write_report(const std::string& tlog_path, const std::string& html_path, const ReportOptions& options = {});

}  // namespace hitl::report
