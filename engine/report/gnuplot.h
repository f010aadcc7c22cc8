// Drawing the report's plots with gnuplot (Debian gnuplot-nox), run once per report as a separate
// process on one script: each plot to an SVG (svg terminal), one group per series (id gnuplot_plot_N,
// N from 1 in the plot's order) titled with the series' name, so that a reader of the SVG can tell which path is which. docs/report.md says why
// gnuplot rather than PLplot.
#pragma once

#include <string>
#include <vector>

#include "base/common/expected.h"
#include "engine/report/plots.h"

namespace hitl::report {

struct GnuplotOptions {
  int width_px = 960;
  int height_px = 380;
  int timeout_ms = 120'000;
};

/// The gnuplot script that draws `plots` into `dir`/<id>.svg (public for tests); on each time axis
/// `marks`: the fault windows shaded red and labelled, the flight modes tinted and named, the events
/// as dotted lines.
std::string gnuplot_script(const std::vector<Plot>& plots, const TimeMarks& marks, const std::string& dir,
                           const GnuplotOptions& options = {});

/// Each plot's SVG text, in order. When gnuplot fails on the whole script (a damaged log's series),
/// each plot is drawn on its own: one gnuplot cannot draw has an empty SVG and a line in `failed`
/// ("altitude: all points y value undefined!"). An Error when gnuplot is not installed, cannot run,
/// takes too long, or draws no plot at all.
Expected<std::vector<std::string>> render_svgs(const std::vector<Plot>& plots, const TimeMarks& marks,
                                               const GnuplotOptions& options = {}, std::vector<std::string>* failed = nullptr);

}  // namespace hitl::report
