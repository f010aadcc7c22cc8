// One draw function per panel (btop's draw(const cpu_info&, ...)): each draws its part of the
// model inside its rectangle, box included, and nothing else; none touches a socket or a session.
#pragma once

#include <optional>
#include <vector>

#include "tui/dashboard_model.h"
#include "tui/screen.h"

namespace hitl::tui {

void draw_paths(Screen& screen, const Rect& r, const PathsPanel& panel);
void draw_dsp_hitl(Screen& screen, const Rect& r, const DspHitlPanel& panel);
void draw_ekf(Screen& screen, const Rect& r, const EkfPanel& panel);
void draw_vehicle(Screen& screen, const Rect& r, const VehiclePanel& panel);
/// `top_row`: the first row shown (rows after wrapping, oldest 0); nullopt follows the newest.
void draw_messages(Screen& screen, const Rect& r, const std::vector<LogLine>& lines, std::optional<int> top_row = std::nullopt);
/// How many rows `lines` take wrapped to `width` (the panel's inside).
int message_row_count(const std::vector<LogLine>& lines, int width);
void draw_link(Screen& screen, const Rect& r, const std::string& partner, Health health, const std::vector<LinkField>& fields);
/// The rolling graphs (graph.h, graph_history.h).
void draw_graphs(Screen& screen, const Rect& r, const GraphsPanel& panel);

void draw_latency(Screen& screen, const Rect& r, const LatencyPanel& panel);
/// "n/a: <reason>", wrapped inside a panel's box (for any panel a source cannot fill).
void draw_unavailable(Screen& screen, const Rect& inner, const std::string& reason);

}  // namespace hitl::tui
