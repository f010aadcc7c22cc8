// The interactive page's own script (interactive.h): it reads the page's data (the JSON in
// <script id="hitl-data">), draws each time plot with dygraphs, links their zoom, pan and selection
// (Dygraph.synchronize for zoom and pan; the selection at the nearest time), shades the fault windows and flight-mode bands behind every plot, shows the
// values under the cursor in each plot's legend and toggles a series when its name is clicked.
// It leaves window.hitlReport = {graphs, ids, drawn_ms} for tests and the console.
#pragma once

namespace hitl::report {

extern const char* const kPageScript;

}  // namespace hitl::report
