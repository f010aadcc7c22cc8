#include "engine/report/html.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <ctime>
#include <sstream>

#include "engine/report/fault_windows.h"
#include "engine/report/parameters.h"

namespace hitl::report {
namespace {

std::string fixed(double v, int decimals) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, v);
  return text;
}

/// The SVG document without its XML prolog, to sit inline in HTML.
std::string inline_svg(const std::string& svg) {
  const auto start = svg.find("<svg");
  return start == std::string::npos ? std::string{} : svg.substr(start);
}

constexpr const char* kStyle = R"(body{font-family:sans-serif;margin:24px auto;padding:0 16px;max-width:1100px;color:#222}
h1{font-size:22px}h2{font-size:17px;margin-top:28px}table{border-collapse:collapse;font-size:13px}
td,th{border:1px solid #ccc;padding:3px 8px;text-align:left}th{background:#f3f3f3}
figure{margin:18px 0;border:1px solid #ddd;padding:6px}figure svg{width:100%;height:auto}
figcaption{font-size:12px;color:#555}figcaption .from{color:#777;font-style:italic}
figure.lacking{color:#8a4b00;font-size:13px;padding:2px 10px}.lacks li{color:#8a4b00}.sev-warning{color:#b35900}.sev-error{color:#c00}
.legend span{display:inline-block;margin-right:14px;font-size:12px}.swatch{display:inline-block;width:14px;border-top:2px dotted;margin-right:4px;vertical-align:middle}
)";

}  // namespace

std::string html_escaped(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string script_safe_json(const nlohmann::json& data) {
  const std::string text = data.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    if (c == '<') out += "\\u003c";
    else out += c;
  }
  return out;
}

std::string page_start(const FlightLog& log, const std::string& extra_head) {
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>hitl report: " << html_escaped(log.path)
    << "</title>\n<style>" << kStyle << "</style>" << extra_head << "</head><body>\n";
  h << "<h1>hitl report: " << html_escaped(log.path) << "</h1>\n";
  return h.str();
}

std::string summary_sections(const FlightLog& log) {
  std::ostringstream h;
  // Summary.
  h << "<h2>Summary</h2>\n<table id=\"summary\">\n";
  auto row = [&](const std::string& name, const std::string& value) {
    h << "<tr><th>" << html_escaped(name) << "</th><td>" << html_escaped(value) << "</td></tr>\n";
  };
  if (log.first_unix_us) {
    const std::time_t t = static_cast<std::time_t>(*log.first_unix_us / 1'000'000);
    std::tm utc{};
    char when[40];
    if (gmtime_r(&t, &utc) != nullptr && std::strftime(when, sizeof when, "%Y-%m-%d %H:%M:%S UTC", &utc) > 0)
      row("recorded", std::string(when) + " (the first record's time)");
  }
  if (log.vehicle) {
    const auto& v = *log.vehicle;
    const std::string type = v.type == 2 ? "quadrotor" : "MAV_TYPE " + std::to_string(v.type);
    const std::string autopilot = v.autopilot == 12 ? "PX4" : "MAV_AUTOPILOT " + std::to_string(v.autopilot);
    row("vehicle", "system " + std::to_string(v.sysid) + ": " + type + ", autopilot " + autopilot + " (its first HEARTBEAT)");
  }
  if (!log.generator.empty()) row("drawn by", log.generator);
  row(log.simulated_time ? "simulated time" : "duration", fixed(log.duration_s, 1) + " s");
  row("wall time", fixed(log.wall_duration_s, 1) + " s");
  row("records / frames", std::to_string(log.records) + " / " + std::to_string(log.frames));
  if (log.tracking)
    row("tracking error against truth", "RMS " + fixed(log.tracking->rms_m, 2) + " m, max " + fixed(log.tracking->max_m, 2) +
                                            " m (" + std::to_string(log.tracking->samples) + " samples)");
  for (const auto& p : log.paths)
    row(p.name + " rate", fixed(p.mean_rate_hz, 0) + " Hz" + (p.expected_hz ? " (expected " + fixed(*p.expected_hz, 0) + " Hz)" : "") +
                              ", " + std::to_string(p.count) + " messages");
  if (log.late_ticks) row("late ticks", std::to_string(*log.late_ticks));
  if (log.lockstep) row("lockstep", *log.lockstep ? "yes" : "no");
  if (log.px4) {
    const auto& m = log.px4->mean_offset_NED_m;
    row("PX4's ULog", log.px4->path + (log.px4->version.empty() ? "" : " (PX4 " + log.px4->version + ")") + ": " +
                          std::to_string(log.px4->position.size()) + " positions; against truth: mean offset north " +
                          fixed(m[0], 3) + " m, east " + fixed(m[1], 3) + " m, up " + fixed(-m[2], 3) + " m, RMS " +
                          fixed(log.px4->rms_m, 3) + " m" +
                          (log.px4->lag_s ? ", lag " + fixed(*log.px4->lag_s * 1e3, 0) + " ms (fitted)" : ""));
    for (const auto& note : log.px4->notes) row("PX4's ULog", note);
  }
  for (const auto& f : log.faults) {
    const std::string args = named_fault_args(f.label());
    row("fault", f.name + (args.empty() ? "" : " (" + args + ")") + ": from " + fixed(f.start_s, 2) + " s " +
                     (f.end_s ? "to " + fixed(*f.end_s, 2) + " s (" + fixed(*f.end_s - f.start_s, 1) + " s)"
                              : "to the end of the log" + (f.duration_s ? " (meant to last " + fixed(*f.duration_s, 1) + " s)" : std::string())));
  }
  row("events", std::to_string(log.events.size()));
  if (log.skipped_bytes > 0 || log.parse_errors > 0)
    row("damage", std::to_string(log.skipped_bytes) + " bytes skipped, " + std::to_string(log.parse_errors) + " frames rejected");
  h << "</table>\n";
  if (!log.skipped.empty()) {
    h << "<h2>What this log had that is not drawn</h2>\n<ul class=\"lacks\" id=\"skipped\">\n";
    for (const auto& m : log.skipped) h << "<li>" << html_escaped(m) << "</li>\n";
    h << "</ul>\n";
  }
  if (!log.missing.empty()) {
    h << "<h2>What this log lacks</h2>\n<ul class=\"lacks\" id=\"lacks\">\n";
    for (const auto& m : log.missing) h << "<li>" << html_escaped(m) << "</li>\n";
    h << "</ul>\n";
  }
  return h.str();
}

std::string figure_html(const Plot& plot, const std::string& inner, const std::string& css_class) {
  nlohmann::json series = nlohmann::json::array();
  for (const auto& s : plot.series) series.push_back({{"title", s.title}, {"points", s.x.size()}, {"samples", s.samples}});
  std::string h = "<figure id=\"plot-" + plot.id + "\"" + (css_class.empty() ? "" : " class=\"" + css_class + "\"") +
                  " data-series=\"" + html_escaped(series.dump()) + "\">\n" + inner + "\n";
  if (!plot.note.empty() || !plot.sources.empty()) {
    h += "<figcaption>" + html_escaped(plot.note);
    if (!plot.sources.empty()) h += std::string(plot.note.empty() ? "" : "<br>") + "<span class=\"from\">from " + html_escaped(plot.sources) + "</span>";
    h += "</figcaption>\n";
  }
  return h + "</figure>\n";
}

std::string lacking_figure(const Plot& plot) {
  return "<figure id=\"lacks-" + plot.id + "\" class=\"lacking\"><p><b>" + html_escaped(plot.title) + "</b>: " +
         html_escaped(plot.lacks) + "</p></figure>\n";
}

std::string svg_figure(const Plot& plot, const std::string& svg) { return figure_html(plot, inline_svg(svg)); }

std::string events_section(const FlightLog& log) {
  std::ostringstream h;
  h << "<h2>Events</h2>\n<table id=\"events\"><tr><th>t (s)</th><th>from</th><th>severity</th><th>text</th></tr>\n";
  for (const auto& e : log.events)
    h << "<tr class=\"sev-" << to_string(e.severity) << "\"><td>" << fixed(e.t_s, 2) << "</td><td>" << html_escaped(e.source)
      << "</td><td>" << to_string(e.severity) << "</td><td>" << html_escaped(e.text) << "</td></tr>\n";
  h << "</table>\n";
  return h.str();
}

std::string parameters_section(const FlightLog& log) {
  const ParameterTable t = non_default_parameters(log);
  auto number = [](double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.7g", v);
    return std::string(text);
  };
  std::ostringstream h;
  h << "<h2>Parameters that differ from the defaults</h2>\n";
  if (t.values_from.empty()) {
    h << "<p id=\"parameters-none\" class=\"lacking\">no PARAM_VALUE in this log (hitl params show, a ground station or the "
         "session's own reads write them into a recording)</p>\n";
    return h.str();
  }
  h << "<p class=\"how\" id=\"parameters-from\">Values: " << html_escaped(t.values_from) << ". Defaults: " << html_escaped(t.defaults_from)
    << ". " << t.differ.size() << " of " << t.compared << " differ";
  if (t.without_default > 0) h << "; " << t.without_default << " without a known default, not compared";
  h << ".</p>\n<table id=\"parameters\"><tr><th>parameter</th><th>value</th><th>default</th></tr>\n";
  for (const auto& r : t.differ)
    h << "<tr><td>" << html_escaped(r.name) << "</td><td>" << number(r.value) << "</td><td>" << number(r.default_value) << "</td></tr>\n";
  h << "</table>\n";
  if (!t.changed.empty()) {
    h << "<p class=\"how\">Set during this log (its last PARAM_VALUE differs from its first):</p>\n<table id=\"parameters-changed\">"
         "<tr><th>parameter</th><th>value</th><th>first in this log</th></tr>\n";
    for (const auto& r : t.changed)
      h << "<tr><td>" << html_escaped(r.name) << "</td><td>" << number(r.value) << "</td><td>" << number(r.default_value) << "</td></tr>\n";
    h << "</table>\n";
  }
  return h.str();
}

std::string report_html(const FlightLog& log, const std::vector<Plot>& plots, const std::vector<std::string>& svgs) {
  std::ostringstream h;
  h << page_start(log, "") << summary_sections(log);
  // Plots.
  h << "<h2>Plots</h2>\n<p class=\"legend\">Events on the time axes: <span><i class=\"swatch\" style=\"border-color:#2ca02c\"></i>info</span>"
       "<span><i class=\"swatch\" style=\"border-color:#1f77b4\"></i>notice</span><span><i class=\"swatch\" "
       "style=\"border-color:#ff7f0e\"></i>warning</span><span><i class=\"swatch\" style=\"border-color:#d62728\"></i>error</span></p>\n";
  for (std::size_t i = 0; i < plots.size() && i < svgs.size(); ++i)
    h << (plots[i].series.empty() ? lacking_figure(plots[i]) : svg_figure(plots[i], svgs[i]));
  h << events_section(log) << parameters_section(log) << "</body></html>\n";
  return h.str();
}

}  // namespace hitl::report
