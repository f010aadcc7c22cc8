#include "engine/report/report.h"

#include <cstring>
#include <fstream>

#include "base/common/clock.h"
#include "engine/report/flight_log.h"
#include "engine/report/gnuplot.h"
#include "engine/report/html.h"
#include "engine/report/interactive.h"
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
  std::string html;
  std::size_t figures = 0;
  std::string static_because;
  std::optional<DygraphsLibrary> library;
  if (!options.static_page) {
    auto loaded = load_dygraphs(options.dygraphs_dir);
    if (loaded) library = std::move(*loaded);
    else static_because = loaded.error().message;
  }
  // gnuplot draws the static page's plots, and the interactive page's that are not against time.
  const auto svg_plots = plots_of(*log);
  std::vector<Plot> to_draw;
  for (const auto& p : svg_plots)
    if (!library || !p.time_axis) to_draw.push_back(p);
  std::vector<std::string> failed;
  auto drawn_svgs = render_svgs(to_draw, event_markers(*log), {}, &failed);
  if (!drawn_svgs) return drawn_svgs.error();
  for (const auto& f : failed) log->skipped.push_back("the plot " + f);
  // What a damaged log had that the page does not show: set aside while reading, or not drawn.
  std::vector<Plot> plots;
  std::vector<std::string> svgs;
  if (library) {
    std::size_t next_svg = 0;
    const std::size_t points = interactive_points_per_series(svg_plots);
    for (auto& p : plots_of(*log, {points, 0.0})) {
      if (p.time_axis) {
        round_times_to_ms(p);
        plots.push_back(std::move(p));
        svgs.emplace_back();
        continue;
      }
      const std::string& svg = (*drawn_svgs)[next_svg];
      if (!svg.empty()) plots.push_back(to_draw[next_svg]), svgs.push_back(svg);
      ++next_svg;
    }
    html = interactive_html(*log, plots, svgs, *library);
  } else {
    for (std::size_t i = 0; i < to_draw.size(); ++i)
      if (!(*drawn_svgs)[i].empty()) plots.push_back(to_draw[i]), svgs.push_back((*drawn_svgs)[i]);
    html = report_html(*log, plots, svgs);
  }
  figures = plots.size();
  std::ofstream out(html_path, std::ios::binary | std::ios::trunc);
  if (!out) return Error::input("cannot write the report '" + html_path + "': " + std::strerror(errno));
  out << html;
  if (!out.flush()) return Error::failed("writing the report '" + html_path + "' failed: " + std::strerror(errno));
  ReportResult r{html_path, html.size(), figures, monotonic_s() - start_s, log->missing, log->skipped, "", false, std::nullopt,
                 library.has_value(), static_because};
  if (log->px4) r.ulog_path = log->px4->path, r.ulog_found = found, r.px4 = log->px4;
  return r;
}

}  // namespace hitl::report
