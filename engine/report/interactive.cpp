#include "engine/report/interactive.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "engine/report/html.h"
#include "engine/report/page_script.h"

namespace hitl::report {
namespace {

const char* style_name(SeriesStyle style) {
  switch (style) {
    case SeriesStyle::Setpoint: return "setpoint";
    case SeriesStyle::Truth: return "truth";
    case SeriesStyle::Estimate: return "estimate";
    case SeriesStyle::Plain: return "plain";
    case SeriesStyle::Reference: return "reference";
  }
  return "plain";
}

int64_t whole_ms(double t_s) { return static_cast<int64_t>(std::llround(t_s * 1e3)); }

/// A value to 1e-4 (what the page shows under the cursor); not finite: null (a gap).
nlohmann::json compact(double v) {
  if (!std::isfinite(v)) return nullptr;
  return std::round(v * 1e4) / 1e4;
}

nlohmann::json series_json(const PlotSeries& s) {
  nlohmann::json t = nlohmann::json::array(), y = nlohmann::json::array();
  int64_t last_ms = 0;
  for (std::size_t i = 0; i < s.x.size(); ++i) {
    const int64_t ms = whole_ms(s.x[i]);
    t.push_back(ms - last_ms);
    last_ms = ms;
    y.push_back(compact(s.y[i]));
  }
  return {{"title", s.title}, {"style", style_name(s.style)}, {"t", std::move(t)}, {"y", std::move(y)}};
}

/// The page's data as JSON that can sit inside <script> (script_safe_json).
std::string data_json(const FlightLog& log, const std::vector<Plot>& plots) {
  nlohmann::json plot_list = nlohmann::json::array();
  std::string time_label;
  for (const auto& p : plots) {
    if (!p.time_axis || p.series.empty()) continue;
    if (time_label.empty()) time_label = p.x_label;
    nlohmann::json series = nlohmann::json::array();
    for (const auto& s : p.series) series.push_back(series_json(s));
    plot_list.push_back({{"id", p.id}, {"title", p.title}, {"y_label", p.y_label}, {"series", std::move(series)}});
  }
  const TimeMarks marks = time_marks(log);
  nlohmann::json events = nlohmann::json::array();
  for (const auto& m : marks.events) events.push_back({{"t", compact(m.t_s)}, {"severity", to_string(m.severity)}});
  nlohmann::json faults = nlohmann::json::array(), modes = nlohmann::json::array();
  for (const auto& f : marks.faults) faults.push_back({{"label", f.label}, {"t0", compact(f.start_s)}, {"t1", compact(f.end_s)}});
  for (const auto& m : marks.modes) modes.push_back({{"mode", m.label}, {"t0", compact(m.start_s)}, {"t1", compact(m.end_s)}});
  nlohmann::json j = {{"time_label", time_label},
                      {"x_range", {compact(log.start_s), compact(log.start_s + log.duration_s)}},
                      {"plots", std::move(plot_list)},
                      {"events", std::move(events)},
                      {"faults", std::move(faults)},
                      {"modes", std::move(modes)}};
  return script_safe_json(j);
}

constexpr const char* kInteractiveStyle = R"(figure.time-plot .graph{width:100%;height:300px}
.values{font-size:12px;min-height:18px;margin:2px 0 4px}.values b{margin-right:12px}
.values .series{display:inline-block;margin-right:14px;cursor:pointer;user-select:none}
.values .series i{display:inline-block;width:14px;height:3px;margin-right:4px;vertical-align:middle}
.values .series.off{color:#aaa;text-decoration:line-through}
.dygraph-title{font-size:14px;font-weight:bold}.dygraph-label{font-size:12px}.how{font-size:12px;color:#555}
)";

}  // namespace

std::size_t interactive_points_per_series(const std::vector<Plot>& plots) {
  std::size_t series = 0;
  for (const auto& p : plots)
    if (p.time_axis) series += p.series.size();  // a lacking plot has none
  return series == 0 ? kInteractiveMaxPoints : std::clamp<std::size_t>(kInteractivePointBudget / series, 100, kInteractiveMaxPoints);
}

void round_times_to_ms(Plot& plot) {
  for (auto& s : plot.series) {
    std::size_t kept = 0;
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      const double t_s = static_cast<double>(whole_ms(s.x[i])) * 1e-3;
      if (kept > 0 && whole_ms(s.x[kept - 1]) == whole_ms(t_s)) continue;
      s.x[kept] = t_s;
      s.y[kept] = s.y[i];
      ++kept;
    }
    s.x.resize(kept);
    s.y.resize(kept);
  }
}

std::string interactive_html(const FlightLog& log, const std::vector<Plot>& plots, const std::vector<std::string>& svgs,
                             const DygraphsLibrary& library) {
  std::ostringstream h;
  h << page_start(log, std::string("<style>") + library.stylesheet + kInteractiveStyle + "</style>") << summary_sections(log);
  h << "<h2>Plots</h2>\n<p class=\"how\">Time plots: drag to zoom, shift+drag to pan, double-click to zoom out, the range "
       "selector under the first plot to choose a window; every time plot follows. The values under the cursor are above "
       "each plot; click a series' name there to hide or show it. Dotted lines: events (green info, blue notice, orange "
       "warning, red error); red bands: fault windows; tinted bands: the vehicle's flight modes.</p>\n";
  for (std::size_t i = 0; i < plots.size(); ++i) {
    if (plots[i].series.empty()) {
      h << lacking_figure(plots[i]);
    } else if (plots[i].time_axis) {
      h << figure_html(plots[i], "<div class=\"values\"></div><div class=\"graph\"></div>", "time-plot");
    } else if (i < svgs.size() && !svgs[i].empty()) {
      h << svg_figure(plots[i], svgs[i]);
    }
  }
  h << events_section(log) << parameters_section(log);
  h << "<script type=\"application/json\" id=\"hitl-data\">" << data_json(log, plots) << "</script>\n";
  h << "<script>" << library.script << "</script>\n<script>" << library.synchronizer << "</script>\n<script>" << kPageScript
    << "</script>\n</body></html>\n";
  return h.str();
}

}  // namespace hitl::report
