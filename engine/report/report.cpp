#include "engine/report/report.h"

#include <cstring>
#include <fstream>

#include "base/common/clock.h"
#include "engine/report/flight_log.h"
#include "engine/report/gnuplot.h"
#include "engine/report/html.h"
#include "engine/report/plots.h"

namespace hitl::report {

Expected<ReportResult> write_report(const std::string& tlog_path, const std::string& html_path) {
  const double start_s = monotonic_s();
  auto log = read_flight_log(tlog_path);
  if (!log) return log.error();
  const auto plots = plots_of(*log);
  auto svgs = render_svgs(plots, event_markers(*log));
  if (!svgs) return svgs.error();
  const std::string html = report_html(*log, plots, *svgs);
  std::ofstream out(html_path, std::ios::binary | std::ios::trunc);
  if (!out) return Error::input("cannot write the report '" + html_path + "': " + std::strerror(errno));
  out << html;
  if (!out.flush()) return Error::failed("writing the report '" + html_path + "' failed: " + std::strerror(errno));
  return ReportResult{html_path, html.size(), plots.size(), monotonic_s() - start_s, log->missing};
}

}  // namespace hitl::report
