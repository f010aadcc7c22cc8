// Debian's libjs-dygraphs, read from where the package puts it, to be inlined into the interactive
// page (interactive.h): the library, its stylesheet and the synchronizer extra that links the
// plots' zoom and selection. Nothing is fetched: a page that opens offline carries its own copy.
#pragma once

#include <string>

#include "base/common/expected.h"

namespace hitl::report {

/// Where Debian's libjs-dygraphs (2.2.1 in Debian 12) installs its files.
inline constexpr const char* kDebianDygraphsDir = "/usr/share/javascript/dygraphs";

struct DygraphsLibrary {
  std::string dir;
  std::string script;        ///< dygraph.min.js
  std::string stylesheet;    ///< dygraph.min.css
  std::string synchronizer;  ///< extras/synchronizer.js
};

/// The three files under `dir`, with their source-map comments left out (the maps are not
/// inlined). An Unavailable error naming the first file missing or unreadable and the package
/// that has it.
Expected<DygraphsLibrary> load_dygraphs(const std::string& dir = kDebianDygraphsDir);

}  // namespace hitl::report
