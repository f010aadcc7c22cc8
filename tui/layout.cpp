#include "tui/layout.h"

#include <algorithm>

namespace hitl::tui {

int paths_height(const DashboardModel& model, bool wide) {
  const int caption = wide && !model.paths.caption.empty() ? 1 : 0;
  return 3 + std::max<int>(1, static_cast<int>(model.paths.rows.size())) + caption;
}

int dsp_hitl_height(bool wide) { return 2 + 5 + (wide ? 2 : 0); }

int link_height(const DashboardModel& model, int width) {
  const int per_line = width - 2 >= 3 * 26 ? 3 : 2;
  const int lines = (static_cast<int>(model.link.size()) + per_line - 1) / per_line;
  return 2 + std::max(1, lines);
}

int ekf_height(bool wide) { return 2 + (wide ? 6 : 5); }

namespace {

/// Graphs in what the panels leave: the left column under the link's own rows (or under the loop
/// latency's), or the left half of messages that run across the bottom.
void place_graphs(Layout& l, int width, int height, const DashboardModel& m) {
  if (!m.graphs || (width <= kMinWidth && height <= kMinHeight)) return;
  const int link_own = link_height(m, l.link.w);
  if (l.link.x == 0 && l.link.h - link_own >= kGraphsMinHeight) {
    l.graphs = {0, l.link.y + link_own, l.link.w, l.link.h - link_own};
    l.link.h = link_own;
  } else if (!l.latency.empty() && l.latency.h - kLatencyHeight >= kGraphsMinHeight) {  // below the loop latency
    l.graphs = {0, l.latency.y + kLatencyHeight, l.latency.w, l.latency.h - kLatencyHeight};
    l.latency.h = kLatencyHeight;
  } else if (l.messages.x == 0 && l.messages.w == width && l.messages.h >= kGraphsMinHeight && width >= 2 * kMinWidth) {
    l.graphs = {0, l.messages.y, width / 2, l.messages.h};
    l.messages = {width / 2, l.messages.y, width - width / 2, l.messages.h};
  }
}

}  // namespace

Layout layout_for(int width, int height, const DashboardModel& m) {
  Layout l;
  if (width < kMinWidth || height < kMinHeight) {
    l.too_small = true;
    return l;
  }
  l.header = {0, 0, width, 1};
  l.footer = {0, height - 1, width, 1};
  const int top = 1, bottom = height - 1;  // body rows [top, bottom)
  const bool tall = height >= kTallHeight;

  if (!m.vehicle && !m.ekf && !m.dsp_hitl) {  // a link without a vehicle: inspect
    const int link_h = link_height(m, width);
    const int paths_h = std::min(paths_height(m, true), bottom - top - link_h - 5);
    l.paths = {0, top, width, paths_h};
    l.link = {0, top + paths_h, width, link_h};
    l.messages = {0, l.link.y + link_h, width, bottom - l.link.y - link_h};
    return l;
  }

  const int left_w = width / 2, right_w = width - left_w;
  const bool wide = left_w - 2 >= kWidePanel;
  int y = top;
  l.paths = {0, y, left_w, std::min(paths_height(m, wide), bottom - y)};
  y += l.paths.h;
  if (m.dsp_hitl) {
    l.dsp_hitl = {0, y, left_w, std::min(dsp_hitl_height(wide), std::max(0, bottom - y))};
    y += l.dsp_hitl.h;
  }
  const int left_used = y;

  int ry = top;
  if (m.vehicle) {
    l.vehicle = {left_w, ry, right_w, std::min(kVehicleHeight, bottom - ry)};
    ry += l.vehicle.h;
  }
  if (m.ekf) {
    l.ekf = {left_w, ry, right_w, std::min(ekf_height(wide), std::max(0, bottom - ry))};
    ry += l.ekf.h;
  }

  if (tall) {  // link under the left column; messages where they get the most rows
    const int link_h = link_height(m, left_w);
    const int messages_y = std::max(left_used + link_h, ry);
    if (bottom - ry > bottom - messages_y) {  // the right column is shorter: messages fill it
      l.link = {0, left_used, left_w, std::max(0, bottom - left_used)};
      l.messages = {left_w, ry, right_w, std::max(0, bottom - ry)};
      if (m.latency && l.link.h >= link_h + kLatencyHeight) {  // the link's spare rows
        l.link.h = link_h;
        l.latency = {0, left_used + link_h, left_w, bottom - left_used - link_h};
      }
    } else {  // across the bottom
      l.link = {0, left_used, left_w, link_h};
      l.messages = {0, messages_y, width, std::max(0, bottom - messages_y)};
      if (m.latency && messages_y - (left_used + link_h) >= kLatencyHeight)  // rows the left column has spare
        l.latency = {0, left_used + link_h, left_w, messages_y - left_used - link_h};
      if (ry < messages_y && m.ekf) l.ekf.h += messages_y - ry;  // no gap on the right
    }
  } else {
    l.link = {0, left_used, left_w, std::max(0, bottom - left_used)};
    l.messages = {left_w, ry, right_w, std::max(0, bottom - ry)};
  }
  place_graphs(l, width, height, m);
  return l;
}

}  // namespace hitl::tui
