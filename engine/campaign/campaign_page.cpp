// The campaign's page: every text from outside (trajectory names, reasons, messages, labels) goes
// through engine/report's html_escaped, the page's data through its script_safe_json; dygraphs is
// read and inlined as the report does it (report::load_dygraphs). The plots are drawn by the page's
// script (campaign_page_script.h) from that data.
#include "engine/campaign/campaign_page.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "engine/campaign/campaign_page_script.h"
#include "engine/campaign/criteria.h"
#include "engine/campaign/results.h"
#include "engine/report/html.h"

namespace hitl::campaign {

namespace {

using report::html_escaped;

std::string number_text(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", v);
  return text;
}

std::string seconds_text(double s) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f s", s);
  return text;
}

/// At most kPageMaxTextBytes of `text` (cut at a UTF-8 character's start), "…" when cut.
std::string bounded(const std::string& text) {
  if (text.size() <= kPageMaxTextBytes) return text;
  std::size_t end = kPageMaxTextBytes;
  while (end > 0 && (static_cast<unsigned char>(text[end]) & 0xC0) == 0x80) --end;
  return text.substr(0, end) + "\xE2\x80\xA6";
}

/// The outcome a page shows: "passed", "failed", "error" or "missing" (not flown).
std::string outcome_of(const std::optional<FlightResult>& r) { return r ? r->outcome : "missing"; }

/// A cell is coloured by its worst flight.
int severity(const std::string& outcome) {
  if (outcome == "passed") return 0;
  if (outcome == "missing") return 1;
  if (outcome == "failed") return 2;
  return 3;  // error
}

std::string outcome_words(const std::string& outcome) { return outcome == "missing" ? "not flown" : outcome; }

bool speeds_named(const Campaign& c) { return c.speeds.size() > 1 || (c.speeds.size() == 1 && c.speeds[0] != 0); }

/// The flight's name inside its cell: "seed 2", "seed 2 x10".
std::string label_in_cell(const Campaign& c, const Flight& f) {
  std::string label = "seed " + std::to_string(f.seed);
  if (speeds_named(c)) label += " x" + number_text(f.speed);
  return label;
}

/// What a flight broke, a line each: "tracking-rms: trajectory.rms_m = 2.1, limit <= 1.5", the
/// error's reason, or "not flown".
std::vector<std::string> broken_lines(const std::optional<FlightResult>& r) {
  std::vector<std::string> out;
  if (!r) {
    out.push_back("not flown");
    return out;
  }
  if (r->outcome == "error") out.push_back("error: " + bounded(r->reason));
  for (const auto& v : r->verdicts)
    if (!v.ok) out.push_back(bounded(v.criterion + ": " + v.message));
  return out;
}

/// The cells of the matrix: a row per trajectory, a column per fault case (by their places in the
/// file, so two trajectories of the same name stay two rows), each with its flights' indices.
struct Cells {
  std::size_t rows = 0, columns = 0;
  std::vector<std::vector<std::size_t>> flights;  ///< [row * columns + column] -> flight indices
  std::vector<std::string> names;                 ///< "square / gps-loss"
};

Cells cells_of(const Campaign& c, const std::vector<Flight>& flights) {
  Cells cells;
  cells.rows = c.trajectories.size();
  cells.columns = c.fault_cases.size();
  cells.flights.resize(cells.rows * cells.columns);
  for (const auto& t : c.trajectories)
    for (const auto& fc : c.fault_cases) cells.names.push_back(t.name + " / " + fc.name);
  for (const auto& f : flights) {
    const auto row = static_cast<std::size_t>(f.trajectory - c.trajectories.data());
    const auto column = static_cast<std::size_t>(f.fault_case - c.fault_cases.data());
    if (row < cells.rows && column < cells.columns) cells.flights[row * cells.columns + column].push_back(f.index);
  }
  return cells;
}

/// A criterion as the page lists it: flown, the file's criteria, its expectations.
struct PageCriterion {
  std::string name;
  std::string figure;
  std::string limit_text;
  std::optional<double> limit;  ///< a number limit (max, min, equals a number)
};

std::string limit_text_of(const Criterion& c) {
  const char* op = c.comparison == Comparison::AtMost ? "<= " : c.comparison == Comparison::AtLeast ? ">= " : "== ";
  if (c.equals_bool) return std::string(op) + (*c.equals_bool ? "true" : "false");
  if (c.equals_text) return std::string(op) + *c.equals_text;
  return op + number_text(c.limit);
}

std::vector<PageCriterion> page_criteria(const Campaign& c) {
  std::vector<PageCriterion> out;
  out.push_back({kFlownCriterion, "end", "== trajectory_done", std::nullopt});
  for (const auto& k : c.criteria) {
    const bool number = !k.equals_bool && !k.equals_text;
    out.push_back({k.name, k.figure, limit_text_of(k), number ? std::optional<double>(k.limit) : std::nullopt});
  }
  for (const auto& e : c.expectations)
    out.push_back({e.name, "events", std::string(to_string(e.kind)) + " " + e.pattern + (e.after_fault.empty() ? "" : " after " + e.after_fault),
                   std::nullopt});
  return out;
}

/// One criterion over one cell's flights.
struct Spread {
  std::size_t judged = 0;  ///< flights with a verdict on it
  std::size_t broken = 0;
  std::vector<double> values;  ///< the number figures, sorted
  double min() const { return values.front(); }
  double max() const { return values.back(); }
  double median() const {
    const std::size_t n = values.size();
    return n % 2 == 1 ? values[n / 2] : (values[n / 2 - 1] + values[n / 2]) / 2;
  }
};

Spread spread_of(const std::string& criterion, const std::vector<std::size_t>& indices,
                 const std::vector<std::optional<FlightResult>>& results) {
  Spread s;
  for (const auto i : indices) {
    if (i >= results.size() || !results[i]) continue;
    for (const auto& v : results[i]->verdicts) {
      if (v.criterion != criterion) continue;
      ++s.judged;
      if (!v.ok) ++s.broken;
      if (v.value.is_number() && std::isfinite(v.value.get<double>())) s.values.push_back(v.value.get<double>());
    }
  }
  std::sort(s.values.begin(), s.values.end());
  return s;
}

constexpr const char* kStyle = R"(body{font-family:sans-serif;margin:24px auto;padding:0 16px;max-width:1200px;color:#222}
h1{font-size:22px}h2{font-size:17px;margin-top:28px}table{border-collapse:collapse;font-size:13px}
td,th{border:1px solid #ccc;padding:3px 8px;text-align:left;vertical-align:top}th{background:#f3f3f3}
.how,.note{font-size:12px;color:#555}.counts span{margin-right:10px}
#matrix td{min-width:120px}#matrix a,#matrix span.flight{display:inline-block;margin:1px 6px 1px 0;padding:0 4px;border-radius:3px;color:#111;text-decoration:none}
#matrix a:hover{text-decoration:underline}
.passed{background:#d4f4d4}.failed{background:#f8c9c9}.error{background:#fbd9a8}.missing{background:#e4e4e4}
a.passed,span.passed{background:#8fd98f}a.failed,span.failed{background:#e66a6a}a.error,span.error{background:#f2a23c}a.missing,span.missing{background:#bdbdbd}
ul.broken{margin:3px 0 0;padding-left:16px;font-size:11px;color:#700}
.wide{overflow-x:auto}#distribution td,#distribution tr th:first-child{white-space:nowrap}#distribution th{min-width:80px}#distribution th small{font-weight:normal}
#distribution td.broken,#trends tr.regression td{background:#f8c9c9}
figure{margin:14px 0;border:1px solid #ddd;padding:6px}figure .graph{width:100%;height:260px}
figcaption{font-size:12px;color:#555}.values{font-size:12px;min-height:18px;margin:2px 0 4px}
.regression{color:#a00;font-weight:bold}
)";

std::string header_html(const PageInput& in) {
  const Campaign& c = *in.campaign;
  const Tally t = tally(*in.results);
  std::ostringstream h;
  auto row = [&](const std::string& name, const std::string& value_html) {
    h << "<tr><th>" << html_escaped(name) << "</th><td>" << value_html << "</td></tr>\n";
  };
  h << "<table id=\"run\">\n";
  row("campaign file", html_escaped(c.file));
  row("label", in.run.label.empty() ? "<i>none</i> (--label names the run)" : html_escaped(in.run.label));
  row("started", html_escaped(in.run.started_utc) + " (UTC)");
  row("hitl", html_escaped(in.run.hitl_version));
  row("flight stack", html_escaped(to_string(c.stack)));
  h << "<tr><th>flights</th><td class=\"counts\" id=\"counts\" data-flights=\"" << t.flights << "\" data-passed=\"" << t.passed
    << "\" data-failed=\"" << t.failed << "\" data-errors=\"" << t.errors << "\" data-missing=\"" << t.missing << "\">" << t.flights
    << ": <span class=\"passed\">" << t.passed << " passed</span><span class=\"failed\">" << t.failed
    << " failed</span><span class=\"error\">" << t.errors << " errors</span><span class=\"missing\">" << t.missing
    << " not flown</span></td></tr>\n";
  row("wall time", html_escaped(seconds_text(in.run.wall_s)) +
                       (in.run.collected ? " (the flights' own wall times added up: they were collected from another engine)" : "") +
                       (in.run.stopped ? " (stopped: --resume flies the rest)" : ""));
  h << "</table>\n";
  return h.str();
}

std::string matrix_html(const PageInput& in, const Cells& cells) {
  const Campaign& c = *in.campaign;
  const auto& flights = *in.flights;
  const auto& results = *in.results;
  std::ostringstream h;
  h << "<h2>The matrix</h2>\n<p class=\"how\">A row per trajectory, a column per fault case; in each cell its flights, each "
       "a link to its report (else its summary, else its log), coloured by outcome: green passed, red failed (a criterion "
       "broken), orange error (crashed, killed, past its time limit), grey not flown. Under them, what each broke.</p>\n";
  h << "<div class=\"wide\"><table id=\"matrix\">\n<tr><th></th>";
  for (const auto& fc : c.fault_cases) h << "<th>" << html_escaped(fc.name) << "</th>";
  h << "</tr>\n";
  for (std::size_t row = 0; row < cells.rows; ++row) {
    h << "<tr><th>" << html_escaped(c.trajectories[row].name) << "</th>";
    for (std::size_t column = 0; column < cells.columns; ++column) {
      const auto& indices = cells.flights[row * cells.columns + column];
      std::string worst = "passed";
      std::string links, broken, tooltip;
      for (const auto i : indices) {
        const Flight& f = flights[i];
        const std::string outcome = outcome_of(results[i]);
        if (severity(outcome) > severity(worst)) worst = outcome;
        const auto lines = broken_lines(results[i]);
        std::string title = f.name + ": " + outcome_words(outcome);
        if (results[i] && !results[i]->summary_line.empty()) title += "\n" + bounded(results[i]->summary_line);
        for (const auto& l : lines) title += "\n" + l;
        const std::string attributes = " class=\"flight " + outcome + "\" data-index=\"" + std::to_string(i) + "\" data-id=\"" +
                                       html_escaped(f.id) + "\" data-outcome=\"" + outcome + "\" title=\"" + html_escaped(title) + "\"";
        const std::string label = html_escaped(label_in_cell(c, f));
        const std::string& link = i < in.links.size() ? in.links[i] : std::string();
        if (link.empty()) links += "<span" + attributes + ">" + label + "</span>";
        else links += "<a" + attributes + " href=\"" + html_escaped(link) + "\">" + label + "</a>";
        if (outcome != "passed")
          for (const auto& l : lines) {
            broken += "<li>" + label + ": " + html_escaped(l) + "</li>";
            tooltip += (tooltip.empty() ? "" : "\n") + label_in_cell(c, f) + ": " + l;
          }
      }
      if (indices.empty()) worst = "missing";
      h << "<td class=\"cell " << worst << "\" data-cell=\"" << row * cells.columns + column << "\""
        << (tooltip.empty() ? std::string() : " title=\"" + html_escaped(tooltip) + "\"") << ">" << links;
      if (!broken.empty()) h << "<ul class=\"broken\">" << broken << "</ul>";
      h << "</td>";
    }
    h << "</tr>\n";
  }
  h << "</table></div>\n";
  return h.str();
}

/// The distribution table, and the data of each number criterion's plot (into `plots`).
std::string distribution_html(const PageInput& in, const Cells& cells, const std::vector<PageCriterion>& criteria,
                              nlohmann::json& plots) {
  const auto& results = *in.results;
  std::ostringstream h;
  const std::size_t seeds = in.campaign->seeds.size() * in.campaign->speeds.size();
  h << "<h2>Each criterion across the seeds</h2>\n<p class=\"how\">Per cell of the matrix (its " << seeds
    << " flight" << (seeds == 1 ? "" : "s")
    << "), each criterion's figure: min / median / max for a number; for a true/false or text figure and an expectation, "
       "how many flights broke it (a plot cannot show those). Red: a flight of the cell broke it. A cell's flights that "
       "erred or were not flown have no figures.</p>\n";
  h << "<div class=\"wide\"><table id=\"distribution\">\n<tr><th>cell</th>";
  for (const auto& k : criteria)
    h << "<th>" << html_escaped(k.name) << "<br><small>" << html_escaped(k.figure + " " + k.limit_text) << "</small></th>";
  h << "</tr>\n";
  std::vector<std::vector<Spread>> spreads(criteria.size());
  for (std::size_t k = 0; k < criteria.size(); ++k)
    for (const auto& indices : cells.flights) spreads[k].push_back(spread_of(criteria[k].name, indices, results));
  for (std::size_t cell = 0; cell < cells.flights.size(); ++cell) {
    h << "<tr><th>" << html_escaped(cells.names[cell]) << "</th>";
    for (std::size_t k = 0; k < criteria.size(); ++k) {
      const Spread& s = spreads[k][cell];
      std::string text;
      if (s.judged == 0) text = "&ndash;";
      else if (!s.values.empty() && criteria[k].limit)
        text = number_text(s.min()) + " / " + number_text(s.median()) + " / " + number_text(s.max());
      else text = s.broken == 0 ? std::to_string(s.judged) + " held" : std::to_string(s.broken) + " of " + std::to_string(s.judged) + " broke it";
      if (s.broken > 0 && !s.values.empty() && criteria[k].limit) text += " (" + std::to_string(s.broken) + " broke it)";
      h << "<td" << (s.broken > 0 ? " class=\"broken\"" : "") << ">" << text << "</td>";
    }
    h << "</tr>\n";
  }
  h << "</table></div>\n";
  for (std::size_t k = 0; k < criteria.size(); ++k) {
    if (!criteria[k].limit) continue;
    bool any = false;
    nlohmann::json rows = nlohmann::json::array();
    for (const auto& s : spreads[k]) {
      any = any || !s.values.empty();
      rows.push_back(s.values.empty() ? nlohmann::json(nullptr) : nlohmann::json{s.min(), s.median(), s.max()});
    }
    if (!any) continue;
    const std::string id = "dist-" + std::to_string(k);
    plots.push_back({{"id", id}, {"criterion", criteria[k].name}, {"figure", criteria[k].figure}, {"limit", *criteria[k].limit},
                     {"limit_text", criteria[k].limit_text}, {"rows", std::move(rows)}});
    h << "<figure id=\"" << id << "\" class=\"plot distribution\"><div class=\"values\"></div><div class=\"graph\"></div>"
      << "<figcaption>" << html_escaped(criteria[k].name) << ": " << html_escaped(criteria[k].figure) << " per cell, min to max "
      << "across its seeds, the dot its median; the limit " << html_escaped(criteria[k].limit_text) << " dashed when near them</figcaption></figure>\n";
  }
  return h.str();
}

std::string trends_html(const PageInput& in, nlohmann::json& plots) {
  std::ostringstream h;
  h << "<h2>Trends</h2>\n";
  if (!in.history) {
    h << "<p class=\"note\" id=\"no-trends\">No trends: " << html_escaped(in.history_note) << "</p>\n";
    return h.str();
  }
  const History& hist = *in.history;
  const std::size_t shown = hist.trends.empty() ? 0 : hist.trends.front().points.size();
  h << "<p class=\"how\">Each criterion over the last " << shown << " of the " << hist.runs << " runs of campaign "
    << html_escaped(hist.campaign) << " in the history, as <code>hitl campaign history</code> prints them: the mean and the "
       "worst of its figure over the flights (for a criterion without a number, how many flights broke it). A regression: "
       "the latest run worse than the runs before it by more than their spread.</p>\n";
  h << "<table id=\"trends\">\n<tr><th>criterion</th><th>figure</th><th>latest run</th><th>verdict</th></tr>\n";
  for (std::size_t k = 0; k < hist.trends.size(); ++k) {
    const Trend& t = hist.trends[k];
    std::string latest = "&ndash;";
    if (!t.points.empty()) {
      const TrendPoint& p = t.points.back();
      const bool threshold = t.limit.rfind("<= ", 0) == 0 || t.limit.rfind(">= ", 0) == 0;
      latest = threshold && p.flights > 0 ? "mean " + number_text(p.mean) + ", worst " + number_text(p.worst) + ", " : std::string();
      latest += std::to_string(p.failed) + " broke it";
    }
    h << "<tr" << (t.regression ? " class=\"regression\"" : "") << " data-criterion=\"" << html_escaped(t.criterion) << "\"><td>"
      << html_escaped(t.criterion) << "</td><td>" << html_escaped(t.figure + " " + t.limit) << "</td><td>" << latest << "</td><td"
      << (t.regression ? " class=\"regression\"" : "") << ">" << html_escaped(t.verdict) << "</td></tr>\n";
  }
  h << "</table>\n";
  for (std::size_t k = 0; k < hist.trends.size(); ++k) {
    const Trend& t = hist.trends[k];
    if (t.points.empty()) continue;
    // A figure against a max or min has a trend of its own; an equals criterion is judged by its failures.
    const bool threshold = t.limit.rfind("<= ", 0) == 0 || t.limit.rfind(">= ", 0) == 0;
    bool numeric = false;
    for (const auto& p : t.points) numeric = numeric || (threshold && p.flights > 0);
    nlohmann::json runs = nlohmann::json::array(), ticks = nlohmann::json::array(), rows = nlohmann::json::array();
    for (const auto& p : t.points) {
      runs.push_back("run " + std::to_string(p.run) + (p.label.empty() ? "" : " (" + bounded(p.label) + ")") + ", " + p.started_utc);
      ticks.push_back("run " + std::to_string(p.run) + (p.label.empty() ? "" : "\n" + bounded(p.label)));
      if (numeric)
        rows.push_back({p.flights > 0 ? nlohmann::json(p.mean) : nlohmann::json(nullptr),
                        p.flights > 0 ? nlohmann::json(p.worst) : nlohmann::json(nullptr), p.failed});
      else
        rows.push_back({p.failed});
    }
    std::optional<double> limit;
    if (numeric) {
      char* end = nullptr;
      const double v = std::strtod(t.limit.c_str() + 3, &end);
      if (end != nullptr && *end == '\0' && std::isfinite(v)) limit = v;
    }
    const std::string id = "trend-" + std::to_string(k);
    plots.push_back({{"id", id}, {"criterion", t.criterion}, {"figure", t.figure}, {"limit_text", t.limit},
                     {"limit", limit ? nlohmann::json(*limit) : nlohmann::json(nullptr)},
                     {"series", numeric ? nlohmann::json{"mean", "worst", "broke it"} : nlohmann::json{"broke it"}},
                     {"runs", std::move(runs)}, {"ticks", std::move(ticks)}, {"rows", std::move(rows)}, {"regression", t.regression}});
    h << "<figure id=\"" << id << "\" class=\"plot trend" << (t.regression ? " regression-plot" : "")
      << "\"><div class=\"values\"></div><div class=\"graph\"></div><figcaption>" << html_escaped(t.criterion) << ": "
      << html_escaped(t.figure + " " + t.limit) << " per run; <span" << (t.regression ? " class=\"regression\"" : "") << ">"
      << html_escaped(t.verdict) << "</span></figcaption></figure>\n";
  }
  return h.str();
}

}  // namespace

std::string flight_link(const std::string& folder, const std::string& relative) {
  for (const char* name : {kReportFile, kSummaryFile, kLogFile}) {
    std::error_code ec;
    if (std::filesystem::is_regular_file(std::filesystem::path(folder) / name, ec)) return relative + "/" + name;
  }
  return "";
}

std::string campaign_page_html(const PageInput& in) {
  const Campaign& c = *in.campaign;
  const Cells cells = cells_of(c, *in.flights);
  const auto criteria = page_criteria(c);
  nlohmann::json distributions = nlohmann::json::array(), trends = nlohmann::json::array();
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>hitl campaign " << html_escaped(c.name)
    << "</title>\n<style>" << kStyle << "</style>";
  if (in.dygraphs != nullptr) h << "<style>" << in.dygraphs->stylesheet << "</style>";
  h << "</head><body>\n<h1>hitl campaign: " << html_escaped(c.name) << "</h1>\n" << header_html(in);
  if (in.dygraphs == nullptr)
    h << "<p class=\"note\" id=\"no-plots\">No plots: " << html_escaped(in.dygraphs_note) << "; the tables carry the same figures.</p>\n";
  h << matrix_html(in, cells);
  h << distribution_html(in, cells, criteria, distributions);
  h << trends_html(in, trends);
  const nlohmann::json data = {{"cells", cells.names}, {"distributions", std::move(distributions)}, {"trends", std::move(trends)}};
  h << "<script type=\"application/json\" id=\"hitl-campaign-data\">" << report::script_safe_json(data) << "</script>\n";
  if (in.dygraphs != nullptr) h << "<script>" << in.dygraphs->script << "</script>\n<script>" << kCampaignPageScript << "</script>\n";
  h << "</body></html>\n";
  return h.str();
}

Status write_campaign_page(const std::string& out_dir, const Campaign& campaign, const std::vector<Flight>& flights,
                           const std::vector<std::optional<FlightResult>>& results, const PageRun& run,
                           const std::string& history_path) {
  PageInput in;
  in.campaign = &campaign;
  in.flights = &flights;
  in.results = &results;
  in.run = run;
  in.links.resize(flights.size());
  for (const auto& f : flights) in.links[f.index] = flight_link(flight_folder(out_dir, f), "flights/" + f.id);
  if (history_path.empty()) {
    in.history_note = run.no_history_reason;
  } else if (auto h = read_history(history_path, campaign.name, kPageTrendRuns)) {
    in.history = std::move(*h);
  } else {
    in.history_note = h.error().message;
  }
  auto library = report::load_dygraphs();
  if (library) in.dygraphs = &*library;
  else in.dygraphs_note = library.error().message;
  const auto path = std::filesystem::path(out_dir) / kPageFile;
  std::ofstream out(path, std::ios::trunc);
  out << campaign_page_html(in);
  if (!out) return Error::unavailable("cannot write " + path.string());
  return Ok{};
}

}  // namespace hitl::campaign
