#include "engine/report/report.h"

#include <cstring>
#include <fstream>

#include "base/common/clock.h"
#include "engine/report/flight_log.h"
#include "engine/report/gnuplot.h"
#include "engine/report/html.h"
#include "engine/report/plots.h"
#include "engine/report/px4_estimate.h"

namespace hitl::report {

Expected<ReportResult> write_report(const std::string& tlog_path, const std::string& html_path, const ReportOptions& options) {
  const double start_s = monotonic_s();
  auto log = read_flight_log(tlog_path);
  if (!log) return log.error();
  std::string ulog_path = options.ulog_path;
  const bool found = ulog_path.empty() && options.find_ulog;
  if (found) ulog_path = find_px4_ulog(tlog_path).value_or("");
  if (!ulog_path.empty()) {
    auto px4 = read_px4_estimate(ulog_path, *log);
    if (px4) log->px4 = std::move(*px4);
    else if (!found) return px4.error();
    else log->missing.push_back("PX4's ULog found beside the recording (" + px4.error().message + ")");
  }
  const auto all_plots = plots_of(*log);
  std::vector<std::string> failed;
  auto all_svgs = render_svgs(all_plots, event_markers(*log), {}, &failed);
  if (!all_svgs) return all_svgs.error();
  // What a damaged log had that the page does not show: set aside while reading, or not drawn.
  std::vector<Plot> plots;
  std::vector<std::string> svgs;
  for (std::size_t i = 0; i < all_plots.size(); ++i)
    if (!(*all_svgs)[i].empty()) plots.push_back(all_plots[i]), svgs.push_back((*all_svgs)[i]);
  for (const auto& f : failed) log->skipped.push_back("the plot " + f);
  const std::string html = report_html(*log, plots, svgs);
  std::ofstream out(html_path, std::ios::binary | std::ios::trunc);
  if (!out) return Error::input("cannot write the report '" + html_path + "': " + std::strerror(errno));
  out << html;
  if (!out.flush()) return Error::failed("writing the report '" + html_path + "' failed: " + std::strerror(errno));
  ReportResult r{html_path, html.size(), plots.size(), monotonic_s() - start_s, log->missing, log->skipped, "", false, std::nullopt};
  if (log->px4) r.ulog_path = log->px4->path, r.ulog_found = found, r.px4 = log->px4;
  return r;
}

}  // namespace hitl::report
