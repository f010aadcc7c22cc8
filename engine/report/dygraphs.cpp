#include "engine/report/dygraphs.h"

#include <cctype>
#include <filesystem>
#include <string_view>

#include "base/common/bounded_read.h"

namespace hitl::report {
namespace {

constexpr std::size_t kMaxLibraryFileBytes = 4u << 20;  // dygraph.min.js is 128 KiB, the unminified one 420 KiB

/// `text` without its `//# sourceMappingURL=` / `/*# sourceMappingURL=...*/` lines: the synchronizer
/// carries its map inline (20 KiB of base64), the library points at a file the page does not have.
std::string without_source_maps(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  std::size_t at = 0;
  while (at < text.size()) {
    auto end = text.find('\n', at);
    if (end == std::string::npos) end = text.size();
    const std::string_view line(text.data() + at, end - at);
    if (line.find("# sourceMappingURL=") == std::string_view::npos) out.append(line).push_back('\n');
    at = end + 1;
  }
  return out;
}

}  // namespace

Expected<DygraphsLibrary> load_dygraphs(const std::string& dir) {
  DygraphsLibrary lib;
  lib.dir = dir;
  for (auto [name, text] : {std::pair{"dygraph.min.js", &lib.script}, std::pair{"dygraph.min.css", &lib.stylesheet},
                            std::pair{"extras/synchronizer.js", &lib.synchronizer}}) {
    const std::string path = (std::filesystem::path(dir) / name).string();
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
      return Error::unavailable(path + " is missing (Debian/Ubuntu: apt-get install libjs-dygraphs); the interactive page inlines it");
    auto read = read_bounded_file(path, "dygraphs file", kMaxLibraryFileBytes);
    if (!read) return Error::unavailable(read.error().message);
    *text = without_source_maps(*read);
    std::string lower = *text;
    for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (lower.find("</script") != std::string::npos || lower.find("</style") != std::string::npos)
      return Error::unavailable(path + " holds '</script' or '</style', which cannot be inlined into a page");
  }
  return lib;
}

}  // namespace hitl::report
