// The interactive page's parts: Debian's dygraphs found (or a missing file named), times to whole
// milliseconds, and data that cannot end its <script> early.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "engine/report/dygraphs.h"
#include "engine/report/interactive.h"

namespace hitl::report {
namespace {

std::string temp_dir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("hitl-interactive-test-" + name + "-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir / "extras");
  return dir.string();
}

TEST(Interactive, AMissingDygraphsFileIsNamedWithItsPackage) {
  const std::string dir = temp_dir("missing");
  std::ofstream(dir + "/dygraph.min.js") << "var Dygraph = 1;\n";
  std::ofstream(dir + "/dygraph.min.css") << ".dygraph-legend{}\n";
  const auto lib = load_dygraphs(dir);
  ASSERT_FALSE(lib);
  EXPECT_EQ(lib.error().kind, ErrorKind::Unavailable);
  EXPECT_NE(lib.error().message.find(dir + "/extras/synchronizer.js is missing"), std::string::npos) << lib.error().message;
  EXPECT_NE(lib.error().message.find("libjs-dygraphs"), std::string::npos) << lib.error().message;
  std::filesystem::remove_all(dir);
}

TEST(Interactive, DygraphsIsReadWithoutItsSourceMapsAndAScriptEndIsRefused) {
  const std::string dir = temp_dir("maps");
  std::ofstream(dir + "/dygraph.min.js") << "var Dygraph = 1;\n//# sourceMappingURL=dygraph.min.js.map\n";
  std::ofstream(dir + "/dygraph.min.css") << ".dygraph-legend{}\n/*# sourceMappingURL=dygraph.min.css.map */\n";
  std::ofstream(dir + "/extras/synchronizer.js") << "Dygraph.synchronize = 1;\n//# sourceMappingURL=data:application/json;base64,eyJ9\n";
  const auto lib = load_dygraphs(dir);
  ASSERT_TRUE(lib) << lib.error().message;
  EXPECT_EQ(lib->script, "var Dygraph = 1;\n");
  EXPECT_EQ(lib->stylesheet, ".dygraph-legend{}\n");
  EXPECT_EQ(lib->synchronizer, "Dygraph.synchronize = 1;\n");
  std::ofstream(dir + "/dygraph.min.js") << "var s = '</SCRIPT>';\n";
  const auto refused = load_dygraphs(dir);
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("cannot be inlined"), std::string::npos) << refused.error().message;
  std::filesystem::remove_all(dir);
}

TEST(Interactive, DebiansDygraphsWhenInstalled) {
  if (!std::filesystem::exists(std::string(kDebianDygraphsDir) + "/dygraph.min.js")) GTEST_SKIP() << "libjs-dygraphs is not installed";
  const auto lib = load_dygraphs();
  ASSERT_TRUE(lib) << lib.error().message;
  EXPECT_NE(lib->synchronizer.find("Dygraph.synchronize = synchronize"), std::string::npos);
  EXPECT_EQ(lib->synchronizer.find("sourceMappingURL"), std::string::npos);
  EXPECT_LT(lib->script.size() + lib->synchronizer.size() + lib->stylesheet.size(), 200'000u);
}

TEST(Interactive, TimesAreWholeMillisecondsAndOnePointAMillisecond) {
  Plot p;
  p.series.push_back(thinned("a", SeriesStyle::Plain, {1.0001, 1.0004, 1.0019, 1.004}, {1, 2, 3, 4}, 100));
  round_times_to_ms(p);
  EXPECT_EQ(p.series[0].x, (std::vector<double>{1.0, 1.002, 1.004}));
  EXPECT_EQ(p.series[0].y, (std::vector<double>{1, 3, 4}));
}

TEST(Interactive, ThePagesDataCannotEndItsScript) {
  FlightLog log;
  log.path = "</script><b>.tlog";
  log.duration_s = 2;
  log.events.push_back({1.0, Severity::Warning, "vehicle 1", "</script>"});
  Plot p{"altitude", "Altitude </script>", "time (s)", "m", {}, true, false, "", 0, 2};
  p.series.push_back(thinned("</script>", SeriesStyle::Truth, {0, 1, 2}, {0.12345678, 1, 2}, 100));
  const std::string html = interactive_html(log, {p}, {""}, DygraphsLibrary{"", "/*lib*/", "", "/*sync*/"});
  const auto data = html.find("<script type=\"application/json\" id=\"hitl-data\">");
  ASSERT_NE(data, std::string::npos);
  const auto end = html.find("</script>", data);
  const std::string json = html.substr(data, end - data);
  EXPECT_EQ(json.find('<', 1), std::string::npos) << json;
  EXPECT_NE(json.find("\"t\":[0,1000,1000]"), std::string::npos) << json;
  EXPECT_NE(json.find("0.1235"), std::string::npos) << "values to 1e-4: " << json;
  EXPECT_NE(html.find("<figure id=\"plot-altitude\" class=\"time-plot\""), std::string::npos);
}

}  // namespace
}  // namespace hitl::report
