// The report's plots as data, from a FlightLog: what each shows, its series (thinned to at most
// max_points each, evenly by index) and the events marked on its time axis. Drawing is gnuplot.h's.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "engine/report/flight_log.h"

namespace hitl::report {

enum class SeriesStyle { Setpoint, Truth, Estimate, Plain, Reference };

struct PlotSeries {
  std::string title;
  std::vector<double> x, y;
  SeriesStyle style = SeriesStyle::Plain;
  std::size_t samples = 0;  ///< in the recording, before thinning
};

struct EventMarker {
  double t_s = 0;
  Severity severity = Severity::Info;
};

/// A stretch of the time axis shaded behind every time plot: a fault window or a flight mode.
struct TimeBand {
  double start_s = 0, end_s = 0;
  std::string label;  ///< "imu-vibration:8,90", "Position"
};

/// What is marked on every time axis: the events, the fault windows and the flight modes.
struct TimeMarks {
  std::vector<EventMarker> events;
  std::vector<TimeBand> faults;  ///< one still active when the log ended runs to its end
  std::vector<TimeBand> modes;
};

struct Plot {
  std::string id;       ///< "top-view", "altitude", ... (the HTML's figure id)
  std::string title;
  std::string x_label, y_label;
  std::vector<PlotSeries> series;
  bool time_axis = true;     ///< x is the log's time, first to last record: events are marked on it
  bool equal_axes = false;   ///< the top view: one metre is one metre both ways
  std::string note;          ///< a line under the plot (the tracking RMS/max, how series were thinned)
  double x_min = 0, x_max = 0;  ///< the time axis' range
  std::string sources;       ///< the messages its series come from, in words ("ATTITUDE (estimate), ...")
  std::string lacks;         ///< no series (kept with PlotOptions::keep_lacking): what the log lacks for it
  bool log_axes = false;     ///< both axes logarithmic (the Allan deviation; every value > 0)
};

struct PlotOptions {
  std::size_t max_points = 2500;  ///< per series
  /// A point within this fraction of the plot's extent (both axes) of the last one drawn is left out:
  /// no drawing can tell them apart (1e-4 of a ~850 px wide plot is 0.085 px; SVG keeps 0.01 px).
  double indistinct_fraction = 1e-4;
  /// Keep a plot the log has no data for, without series and with `lacks` said, in its place.
  bool keep_lacking = false;
};

/// Every plot the log has data for, in the report's order; a plot with no data is left out (the
/// log's `missing` says why), or kept with its `lacks` said (PlotOptions::keep_lacking). Series are thinned (`thinned`), then points no drawing can tell
/// apart are dropped.
std::vector<Plot> plots_of(const FlightLog& log, const PlotOptions& options = {});

/// The events drawn as markers on every time axis (at most this many; the table lists them all).
std::vector<EventMarker> event_markers(const FlightLog& log, std::size_t max_markers = 200);

/// The events (event_markers), the fault windows and the flight modes, for every time axis.
TimeMarks time_marks(const FlightLog& log);

/// Every `stride`-th point from the first, the last always kept; consecutive equal points once.
PlotSeries thinned(std::string title, SeriesStyle style, const std::vector<double>& x, const std::vector<double>& y,
                   std::size_t max_points);

}  // namespace hitl::report
