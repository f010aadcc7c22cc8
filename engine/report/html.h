// The report as one self-contained HTML page: the summary table, what the log lacks, each plot in
// a <figure id="plot-ID" data-series="[...]"> (the series it claims: title, points drawn, samples in
// the recording), and the events. The static page (report_html: no scripts, no network) has each
// plot's SVG inline; the interactive one (interactive.h) shares its sections.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/report/flight_log.h"
#include "engine/report/plots.h"

namespace hitl::report {

/// `svgs[i]` is plots[i] drawn (a plot without series: lacking_figure in its place).
std::string report_html(const FlightLog& log, const std::vector<Plot>& plots, const std::vector<std::string>& svgs);

/// The page up to its <h1> (`extra_head` goes at the end of <head>).
std::string page_start(const FlightLog& log, const std::string& extra_head);
/// The summary table, and what the log had that is not drawn and what it lacks.
std::string summary_sections(const FlightLog& log);
/// The events table.
std::string events_section(const FlightLog& log);
/// "Parameters that differ from the defaults" (parameters.h): the table, where its values and defaults
/// came from, or "no PARAM_VALUE in this log".
std::string parameters_section(const FlightLog& log);
/// <figure id="plot-ID" class="CSS_CLASS" data-series="..."> `inner` <figcaption>note</figcaption></figure>.
std::string figure_html(const Plot& plot, const std::string& inner, const std::string& css_class = "");
/// A plot the log has no data for, in its place: <figure id="lacks-ID" class="lacking"> its title
/// and what the log lacks.
std::string lacking_figure(const Plot& plot);
/// The figure with gnuplot's SVG inline.
std::string svg_figure(const Plot& plot, const std::string& svg);

/// Text for HTML (&, <, >, ").
std::string html_escaped(const std::string& text);

/// JSON text that can sit inside <script type="application/json">: every '<' written as \u003c, so
/// no text in it ("</script>") ends the element early; invalid UTF-8 replaced.
std::string script_safe_json(const nlohmann::json& data);

}  // namespace hitl::report
