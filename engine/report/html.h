// The report as one self-contained HTML page (no scripts, no network): the summary table, what the
// log lacks, each plot's SVG inline in a <figure id="plot-ID" data-series="[...]"> (the series it
// claims: title, points drawn, samples in the recording), and the events.
#pragma once

#include <string>
#include <vector>

#include "engine/report/flight_log.h"
#include "engine/report/plots.h"

namespace hitl::report {

/// `svgs[i]` is plots[i] drawn.
std::string report_html(const FlightLog& log, const std::vector<Plot>& plots, const std::vector<std::string>& svgs);

/// Text for HTML (&, <, >, ").
std::string html_escaped(const std::string& text);

}  // namespace hitl::report
