// Where each panel goes for a terminal size. 80x24 is the minimum: two columns (data paths,
// dsp_hitl and link on the left; vehicle, EKF and messages on the right). From 40 rows the
// messages go where they get the most rows: down the right column under the EKF, or across the
// whole width under the link when the left column is the shorter one; wider panels show more columns and longer bars
// (each panel decides from its own width). A source without vehicle panels (inspect) gets the
// data paths across the top, then link, then messages. A model with graphs (the sim's) gets them
// in the room left over, never at 80x24: under the link when the left column has kGraphsMinHeight
// rows to spare, else beside the messages when those run across the bottom.
#pragma once

#include "tui/dashboard_model.h"
#include "tui/screen.h"

namespace hitl::tui {

inline constexpr int kMinWidth = 80;
inline constexpr int kMinHeight = 24;
/// From this many rows, the link panel keeps its own height and messages may span the whole width.
inline constexpr int kTallHeight = 40;
/// A panel at least this wide inside shows its extra columns.
inline constexpr int kWidePanel = 56;
/// The fewest rows (box included) the graphs panel is given.
inline constexpr int kGraphsMinHeight = 12;

struct Layout {
  bool too_small = false;
  Rect header, footer;
  Rect paths, dsp_hitl, link, vehicle, ekf, messages;  ///< empty when the panel is not shown
  Rect latency;  ///< loop latency: tall terminals only, in rows the left column has spare below the link
  Rect graphs;
};

/// Rows each panel needs for its content (borders included), given the model.
int paths_height(const DashboardModel& model, bool wide);
int dsp_hitl_height(bool wide);
int link_height(const DashboardModel& model, int width);
inline constexpr int kVehicleHeight = 9;
int ekf_height(bool wide);
/// The loop latency panel: a summary line and the histogram's rows that hold samples.
inline constexpr int kLatencyHeight = 2 + 1 + 7;

Layout layout_for(int width, int height, const DashboardModel& model);

}  // namespace hitl::tui
