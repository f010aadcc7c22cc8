// Writing a report (engine/report) and saying so, for `hitl report` and the commands that write one
// after a flight (`--report PATH` on demo, sim -t and fly trajectory).
#pragma once

#include <string>

#include "cli/common_options.h"
#include "engine/report/report.h"

namespace hitl::cli {

/// "report.tlog" -> "report.html" (any other name: NAME.html).
std::string default_report_path(const std::string& tlog_path);

/// Writes the report of `tlog_path` to `html_path`; says on stderr what it wrote (plots, size,
/// time, what the log lacks; not with --json or -q) or why not (naming `command`). The caller
/// prints the path.
/// PX4's ULog merged as `report_options` say (by default the one PX4 left beside the recording under
/// hitl sim --px4; its path is said).
Expected<report::ReportResult> write_report_and_say(const GlobalOptions& options, const std::string& command,
                                                    const std::string& tlog_path, const std::string& html_path,
                                                    const report::ReportOptions& report_options = {});

/// The report's JSON: {"path", "bytes", "plots", "seconds", "interactive", "static_because", "lacks", "skipped", "ulog"} ("ulog": null
/// or {"path", "found", "version", "positions", "offset_m": {north, east, up, rms}, "lag_ms"}).
nlohmann::json report_json(const report::ReportResult& result);

}  // namespace hitl::cli
