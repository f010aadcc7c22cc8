// The dashboard rendered onto the in-memory screen for the drawing tests, and the style of a cell
// found by its row and text.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "tui/memory_screen.h"
#include "tui/render.h"

namespace hitl::tui::test {

inline MemoryScreen draw(int w, int h, const DashboardModel& m, const Interaction& in = {}) {
  MemoryScreen s(w, h);
  render(s, m, in);
  return s;
}

/// The style of the first cell of `needle` on the row that holds `row_key` (e.g. the "mag" row).
inline Style style_of(const MemoryScreen& s, const std::string& row_key, const std::string& needle) {
  for (int y = 0; y < s.height(); ++y) {
    const std::string row = s.row(y);
    const auto k = row.find(row_key);
    if (k == std::string::npos) continue;
    const auto at = row.find(needle, k + row_key.size());
    if (at != std::string::npos) return s.style_at(static_cast<int>(at), y);
  }
  ADD_FAILURE() << "'" << needle << "' not after '" << row_key << "' on any row:\n" << s.dump();
  return {};
}

}  // namespace hitl::tui::test
