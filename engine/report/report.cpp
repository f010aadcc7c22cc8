#include "engine/report/report.h"

#include <algorithm>
#include <cstring>
#include <map>
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
  auto log = read_flight_log(tlog_path, {}, options.field_plots);
  if (!log) return log.error();
  log->generator = options.generator;
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
  // gnuplot draws the static page's plots, and the interactive page's that are not against time;
  // a plot the log has no data for says so in its place.
  const auto svg_plots = plots_of(*log, {2500, 1e-4, true});
  std::vector<Plot> to_draw;
  for (const auto& p : svg_plots)
    if (!p.series.empty() && (!library || !p.time_axis)) to_draw.push_back(p);
  std::vector<std::string> failed;
  auto drawn_svgs = render_svgs(to_draw, time_marks(*log), {}, &failed);
  if (!drawn_svgs) return drawn_svgs.error();
  std::map<std::string, std::string> svg_of;  // plot id -> its SVG ("" : gnuplot could not draw it)
  for (std::size_t i = 0; i < to_draw.size(); ++i) svg_of[to_draw[i].id] = (*drawn_svgs)[i];
  // What a damaged log had that the page does not show: set aside while reading, or not drawn.
  for (const auto& f : failed) log->skipped.push_back("the plot " + f);
  std::vector<Plot> plots;
  std::vector<std::string> svgs;
  auto keep = [&](Plot p) {
    if (p.series.empty()) {
      plots.push_back(std::move(p)), svgs.emplace_back();
    } else if (library && p.time_axis) {
      round_times_to_ms(p);
      plots.push_back(std::move(p)), svgs.emplace_back();
    } else if (!svg_of[p.id].empty()) {
      svgs.push_back(svg_of[p.id]), plots.push_back(std::move(p));
    }
  };
  if (library) {
    const std::size_t points = interactive_points_per_series(svg_plots);
    for (auto& p : plots_of(*log, {points, 0.0, true})) keep(p.time_axis ? std::move(p) : *std::find_if(svg_plots.begin(), svg_plots.end(), [&](const Plot& q) { return q.id == p.id; }));
    html = interactive_html(*log, plots, svgs, *library);
  } else {
    for (const auto& p : svg_plots) keep(p);
    html = report_html(*log, plots, svgs);
  }
  for (const auto& p : plots) figures += p.series.empty() ? 0 : 1;
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
