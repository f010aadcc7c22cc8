// The interactive report page (the default of hitl report; docs/report.md): one self-contained
// HTML file that opens offline, with Debian's dygraphs and the page's script (page_script.h)
// inlined. Each time plot is drawn by dygraphs from its series embedded as compact JSON (times in
// delta-coded milliseconds, values to 1e-4); zoom, pan and the selection are linked across every
// time plot; the fault windows and flight-mode bands are shaded behind each. Plots that are not
// against time (the top view) are gnuplot's SVG, as on the static page.
#pragma once

#include <string>
#include <vector>

#include "engine/report/dygraphs.h"
#include "engine/report/flight_log.h"
#include "engine/report/plots.h"

namespace hitl::report {

/// How many points the interactive page embeds (docs/report.md "The interactive page"): each series
/// is thinned evenly by index (plots.h) to at most min(kInteractiveMaxPoints, kInteractivePointBudget
/// / the number of series in its time plots) points, so a page's data is bounded whatever the flight's
/// length (about 12 bytes a point: a 10-minute flight's page stays under 5 MB), and a 2 s transient
/// keeps every sample of a 50 Hz series of a flight up to 200 s (10 000 points).
inline constexpr std::size_t kInteractiveMaxPoints = 10'000;
inline constexpr std::size_t kInteractivePointBudget = 250'000;

/// The points per series for these time plots (the rule above).
std::size_t interactive_points_per_series(const std::vector<Plot>& plots);

/// Each time on the interactive page is whole milliseconds: `plot`'s series' times rounded so, a
/// point at the same millisecond as the one before it dropped (the points a figure claims are the
/// points its JSON holds).
void round_times_to_ms(Plot& plot);

/// The page. `plots` in the page's order: time plots are drawn by dygraphs from their data,
/// the others from `svgs[i]` (gnuplot's; "" for a time plot).
std::string interactive_html(const FlightLog& log, const std::vector<Plot>& plots, const std::vector<std::string>& svgs,
                             const DygraphsLibrary& library);

}  // namespace hitl::report
