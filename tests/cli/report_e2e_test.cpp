// hitl report through the real binary: the demo's report rendered in headless Chromium (not blank;
// its script runs without an error and zooming one time plot zooms them all), and each plot holds
// the series its figure claims (the interactive page's data, the static page's SVG), with as many
// points as it says, of as many samples as the recording holds; a plain MAVLink peer's log (hitl target recorded by hitl
// inspect: no simulator, no pilot) gives a report of what it has and says what it lacks.
#include <gtest/gtest.h>

#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <fstream>
#include <regex>
#include <sstream>
#include <tuple>

#include "base/contract/session_status.h"
#include "base/mavlink/enums.h"
#include "base/mavlink/frame_parser.h"
#include "base/mavlink/message_set.h"
#include "base/mavlink/messages.h"
#include "base/mavlink/text_field.h"
#include "engine/mavlink/tlog.h"
#include "engine/report/flight_log.h"
#include "engine/report/plots.h"
#include "tests/support/chromium.h"
#include "tests/support/json_lines.h"
#include "tests/support/lockstep_session.h"
#include "tests/support/process.h"
#include "tests/support/recorded_flight.h"
#include "tests/support/tools.h"
#include "tests/support/ulog_writer.h"

namespace hitl {
namespace {
using namespace std::chrono_literals;
namespace msg = mavlink::msg;

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

struct SeriesClaim {
  std::string title;
  std::size_t points = 0;
  std::size_t samples = 0;
  std::size_t drawn = 0;  ///< coordinate pairs in the SVG group of that title, less the key's sample line
};

/// The text of the SVG group that starts at `at` ("<g id=..."), nested groups included.
std::string group_at(const std::string& text, std::size_t at) {
  int depth = 0;
  std::size_t pos = at;
  while (pos < text.size()) {
    const auto open = text.find("<g", pos), close = text.find("</g>", pos);
    if (close == std::string::npos) return text.substr(at);
    if (open != std::string::npos && open < close && (text[open + 2] == ' ' || text[open + 2] == '>')) {
      ++depth;
      pos = open + 2;
      continue;
    }
    if (open != std::string::npos && open < close) {
      pos = open + 2;
      continue;
    }
    --depth;
    pos = close + 4;
    if (depth == 0) return text.substr(at, pos - at);
  }
  return text.substr(at);
}

/// Coordinate pairs ("12.5,40.25") in the d='...' attributes of `svg`.
std::size_t coordinate_pairs(const std::string& svg) {
  std::size_t pairs = 0;
  for (std::size_t at = 0; (at = svg.find("d='", at)) != std::string::npos;) {
    const auto end = svg.find('\'', at + 3);
    for (std::size_t k = at + 3; k < end; ++k) pairs += svg[k] == ',' ? 1 : 0;
    at = end;
  }
  return pairs;
}

/// The interactive page's data (<script type="application/json" id="hitl-data">); null when none.
nlohmann::json page_data(const std::string& html) {
  const std::string open = "<script type=\"application/json\" id=\"hitl-data\">";
  const auto at = html.find(open);
  if (at == std::string::npos) return nullptr;
  const auto start = at + open.size();
  return nlohmann::json::parse(html.substr(start, html.find("</script>", start) - start));
}

/// Each figure's claims and what it draws (its SVG's paths; a time plot of the interactive page, the
/// points of its series in the page's data): figure id -> series in plot order.
std::map<std::string, std::vector<SeriesClaim>> figures_of(const std::string& html) {
  std::map<std::string, std::vector<SeriesClaim>> out;
  const auto page = page_data(html);
  std::map<std::string, nlohmann::json> data_plots;
  if (!page.is_null())
    for (const auto& p : page["plots"]) data_plots[p["id"]] = p;
  const std::string open = "<figure id=\"plot-";
  for (std::size_t at = 0; (at = html.find(open, at)) != std::string::npos;) {
    const auto id_end = html.find('"', at + open.size());
    const std::string id = html.substr(at + open.size(), id_end - at - open.size());
    const auto data = html.find("data-series=\"", id_end) + 13;
    const auto claims = nlohmann::json::parse(test::html_unescaped(html.substr(data, html.find('"', data) - data)));
    const auto fig_end = html.find("</figure>", at);
    const std::string fig = html.substr(at, fig_end - at);
    at = fig_end;
    auto& series = out[id];
    for (std::size_t k = 0; k < claims.size(); ++k) {
      SeriesClaim c{claims[k]["title"], claims[k]["points"], claims[k]["samples"], 0};
      const auto g = fig.find("<g id=\"gnuplot_plot_" + std::to_string(k + 1) + "\"");
      if (fig.find("class=\"time-plot\"") != std::string::npos) {
        const auto& p = data_plots[id];
        if (p.is_null() || k >= p["series"].size()) {
          c.title = "(no data on the page) " + c.title;
        } else {
          if (p["series"][k]["title"] != c.title) c.title = "(another series in the data) " + c.title;
          c.drawn = p["series"][k]["t"].size();
          EXPECT_EQ(p["series"][k]["y"].size(), c.drawn) << id << " / " << c.title;
        }
      } else if (g == std::string::npos) {
        c.title = "(no group in the SVG) " + c.title;
      } else {
        const std::string group = group_at(fig, g);
        if (group.find("<text>" + c.title + "</text>") == std::string::npos) c.title = "(another key in the SVG) " + c.title;
        const std::size_t pairs = coordinate_pairs(group);
        c.drawn = pairs >= 2 ? pairs - 2 : 0;  // the key's sample line is two points
      }
      series.push_back(c);
    }
  }
  return out;
}

/// Counted straight from the recording with the codec, not with the report's reader.
struct RecordingCounts {
  std::size_t truth = 0, setpoint = 0, tracking = 0, estimate = 0, attitude = 0, actuators = 0, manual_control = 0, hil_sensor = 0, hil_gps = 0;
  std::size_t latency_p50 = 0, latency_p99 = 0, latency_max = 0;  ///< the session's status once something was answered (not -1)
};

RecordingCounts count_recording(const std::string& path) {
  RecordingCounts c;
  auto reader = mavlink::TlogReader::open(path);
  EXPECT_TRUE(reader);
  if (!reader) return c;
  const auto messages = mavlink::MessageSet::compiled();
  mavlink::FrameParser parser(messages);
  mavlink::TlogRecord r;
  while (reader->next(r)) {
    parser.parse_datagram(r.frame, [&](const mavlink::Frame& f) {
      const bool sim = f.sysid == kSimulatorSystemId;
      if (sim && f.is<msg::Odometry>() && f.as<msg::Odometry>().estimator_type == static_cast<uint8_t>(mavlink::MavEstimatorType::Mocap)) ++c.truth;
      if (sim && f.is<msg::PositionTargetLocalNed>()) ++c.setpoint;
      if (sim && f.is<msg::NamedValueFloat>() && mavlink::text_of(f.as<msg::NamedValueFloat>().name) == kTrackingErrorName) ++c.tracking;
      if (!sim && f.is<msg::LocalPositionNed>()) ++c.estimate;
      if (!sim && f.is<msg::Attitude>()) ++c.attitude;
      if (!sim && f.is<msg::HilActuatorControls>()) ++c.actuators;
      if (f.is<msg::ManualControl>()) ++c.manual_control;
      if (sim && f.is<msg::HilSensor>()) ++c.hil_sensor;
      if (sim && f.is<msg::HilGps>()) ++c.hil_gps;
      if (sim && f.is<msg::NamedValueInt>() && f.as<msg::NamedValueInt>().value >= 0) {
        const auto name = mavlink::text_of(f.as<msg::NamedValueInt>().name);
        c.latency_p50 += name == kStatusLoopLatencyP50Name ? 1 : 0;
        c.latency_p99 += name == kStatusLoopLatencyP99Name ? 1 : 0;
        c.latency_max += name == kStatusLoopLatencyMaxName ? 1 : 0;
      }
    });
  }
  return c;
}

std::string last_line(const std::string& out) {
  std::string text = out;
  while (!text.empty() && text.back() == '\n') text.pop_back();
  const auto nl = text.rfind('\n');
  return nl == std::string::npos ? text : text.substr(nl + 1);
}

std::string fixed2(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", v);
  return text;
}

/// Headless Chromium's screenshot of `html` into `png`; "" when taken, else why not.
std::string screenshot(const std::string& chromium, const std::string& html, const std::string& png, const std::string& profile) {
  auto r = test::run_program({chromium, "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars", "--user-data-dir=" + profile,
                              "--window-size=1200,3200", "--screenshot=" + png, "file://" + html},
                             180s);
  if (r.exit_code != 0) return "chromium exit " + std::to_string(r.exit_code) + ": " + r.err;
  if (!std::filesystem::exists(png)) return "chromium wrote no " + png + ": " + r.err;
  return "";
}

/// Moves the mouse over the middle of the third time plot and reads the time selected in each;
/// zooms the second time plot to 2 s and reads every time plot's x range before and after; then
/// clicks the first series' name in the first plot's legend.
constexpr const char* kZoomProbe = R"(out.ids=r.ids;out.drawn_ms=r.drawn_ms;
var h=r.graphs[2],ha=h.getArea(),hc=h.mouseEventElement_,hr=hc.getBoundingClientRect();
hc.dispatchEvent(new MouseEvent('mousemove',{clientX:hr.left+ha.x+ha.w/2,clientY:hr.top+ha.y+ha.h/2,bubbles:true}));
out.hover_t=h.getSelection()<0?null:h.getValue(h.getSelection(),0);
out.selected=r.graphs.map(function(o){return o.getSelection()<0?null:o.getValue(o.getSelection(),0)});
out.first_legend=document.querySelector('#plot-'+r.ids[0]+' .values').textContent;
h.clearSelection();
out.before=r.graphs.map(function(g){return g.xAxisRange()});
var g=r.graphs[1],x=g.xAxisRange(),a=x[0]+0.4*(x[1]-x[0]);out.zoom=[a,a+2];g.updateOptions({dateWindow:out.zoom});
out.after=r.graphs.map(function(g){return g.xAxisRange()});
var item=document.querySelector('#plot-'+r.ids[0]+' .values [data-i="0"]');out.legend_item=item?item.textContent:null;
if(item)item.click();out.visible_after_click=r.graphs[0].visibility()[0];
out.canvases=document.querySelectorAll('figure.time-plot canvas').length;)";

/// For each time plot and each fault window, the share of a column of the plot's pixels that are
/// red-tinted (the window's band) at the window's middle ("inside") and at 5 s ("outside").
constexpr const char* kShadeProbe = R"(var faults=JSON.parse(document.getElementById('hitl-data').textContent).faults;
function reddish(g,t){var a=g.getArea(),c=g.hidden_,k=c.width/g.width_,ctx=c.getContext('2d'),n=0,all=0;
var x=Math.round(g.toDomXCoord(t)*k);for(var y=a.y+2;y<a.y+a.h-2;y+=3){var p=ctx.getImageData(x,Math.round(y*k),1,1).data;
all++;if(p[0]>p[1]+12&&p[0]>p[2]+12)n++;}return n/all;}
out.ids=r.ids;out.faults=faults;
out.inside=r.graphs.map(function(g){return faults.map(function(f){return reddish(g,(f.t0+f.t1)/2)})});
out.outside=r.graphs.map(function(g){return reddish(g,5)});)";

TEST(ReportE2E, TheDemosReportRendersInChromiumWithEverySeriesItClaims) {
  const std::string dir = test::temp_dir();
  const std::string tlog = dir + "/demo.tlog", html = dir + "/demo.html";
  auto demo = test::run_hitl({"--json", "demo", "--record", tlog, "--report", html}, 300s);
  ASSERT_EQ(demo.exit_code, 0) << demo.out << demo.err;
  const auto summary = test::last_json_line(demo.out);
  ASSERT_EQ(summary["type"], "summary") << demo.out;
  EXPECT_EQ(summary["report"]["path"], html);
  EXPECT_EQ(summary["recording"], tlog);
  EXPECT_EQ(summary["report"]["interactive"], true) << summary["report"].dump();
  const std::string page = read_file(html);
  // One file that opens offline: its scripts and styles inline, nothing fetched.
  for (const char* reach : {"<script src", "src=\"http", "href=\"http", "href='http", "url(http", "@import", "<link"})
    EXPECT_EQ(page.find(reach), std::string::npos) << "the page must not reach the network: " << reach;
  EXPECT_NE(page.find("Dygraph.synchronize = synchronize"), std::string::npos) << "the synchronizer is inlined";

  // The static page of the same recording: gnuplot's SVGs, no script.
  auto static_run = test::run_hitl({"--json", "report", tlog, "--static", "-o", dir + "/static.html"});
  ASSERT_EQ(static_run.exit_code, 0) << static_run.err;
  EXPECT_EQ(test::last_json_line(static_run.out)["interactive"], false);
  const std::string static_page = read_file(dir + "/static.html");
  EXPECT_EQ(static_page.find("<script"), std::string::npos);

  // The summary table's tracking figures are the session's.
  const auto& trajectory = summary["trajectory"];
  const std::string tracking_row = "RMS " + fixed2(trajectory["rms_m"]) + " m, max " + fixed2(trajectory["max_m"]) + " m (" +
                                   std::to_string(trajectory["samples"].get<uint64_t>()) + " samples)";
  EXPECT_NE(page.find(tracking_row), std::string::npos) << trajectory.dump();
  EXPECT_NE(static_page.find(tracking_row), std::string::npos) << trajectory.dump();
  // The header: when it was recorded, the vehicle, what drew it.
  for (const char* row : {"<tr><th>recorded</th><td>20", "<tr><th>vehicle</th><td>system 1: quadrotor, autopilot PX4",
                          "<tr><th>drawn by</th><td>hitl "})
    EXPECT_NE(page.find(row), std::string::npos) << row;

  // Each plot's series, on both pages: drawn with the points claimed, of the samples recorded.
  const auto counts = count_recording(tlog);
  EXPECT_GT(counts.truth, 1000u);
  EXPECT_EQ(counts.tracking, trajectory["samples"].get<std::size_t>());
  // The demo is lockstep against hitl target: its loop latency is measured and recorded each second.
  EXPECT_GT(counts.latency_p99, 10u);
  for (const auto& [which, text, most_points] : {std::tuple{"interactive", &page, 10100u}, std::tuple{"static", &static_page, 2600u}}) {
    SCOPED_TRACE(which);
    const auto figures = figures_of(*text);
    for (const char* id : {"top-view", "altitude", "tracking-error", "velocity-north", "velocity-east", "velocity-up", "attitude-roll",
                           "attitude-pitch", "attitude-yaw", "rate-roll", "rate-pitch", "rate-yaw", "motors", "sticks", "imu-accel",
                           "imu-gyro", "vibration", "gps", "rates", "jitter", "loop-latency", "ekf"})
      EXPECT_TRUE(figures.count(id)) << "no figure " << id;
    EXPECT_EQ(text->find("<figure id=\"lacks-"), std::string::npos) << "the demo's log has every plot's data";
    // Each plot says which messages it comes from; the emulated board streams no ATTITUDE_TARGET.
    EXPECT_NE(text->find("<span class=\"from\">from ATTITUDE_TARGET body rates (setpoint)"), std::string::npos);
    EXPECT_NE(text->find("no rate setpoint: this log has no ATTITUDE_TARGET"), std::string::npos);
    for (const auto& [id, series] : figures) {
      for (const auto& s : series) {
        EXPECT_EQ(s.drawn, s.points) << id << " / " << s.title;
        EXPECT_GT(s.points, 0u) << id << " / " << s.title;
        EXPECT_LE(s.points, most_points) << id << " / " << s.title;
      }
    }
    auto samples = [&](const std::string& id, const std::string& title) -> std::size_t {
      if (!figures.count(id)) return 0;
      for (const auto& s : figures.at(id))
        if (s.title == title) return s.samples;
      return 0;
    };
    EXPECT_EQ(samples("top-view", "truth"), counts.truth);
    EXPECT_EQ(samples("top-view", "setpoint"), counts.setpoint);
    EXPECT_EQ(samples("top-view", "estimate"), counts.estimate);
    EXPECT_EQ(samples("altitude", "truth"), counts.truth);
    EXPECT_EQ(samples("tracking-error", "error against truth"), counts.tracking);
    EXPECT_EQ(samples("attitude-roll", "estimate"), counts.attitude);
    EXPECT_EQ(samples("motors", "motor 0"), counts.actuators);
    EXPECT_EQ(samples("velocity-up", "estimate"), counts.estimate);
    EXPECT_EQ(samples("rate-roll", "truth"), counts.truth);
    EXPECT_EQ(samples("sticks", "throttle"), counts.manual_control);
    EXPECT_EQ(samples("imu-gyro", "z (down)"), counts.hil_sensor);
    EXPECT_EQ(samples("gps", "satellites (HIL_GPS)"), counts.hil_gps);
    EXPECT_EQ(samples("vibration", "z (down)"), 257u) << "0 to 125 Hz in 512-sample segments";
    EXPECT_EQ(samples("loop-latency", "p50"), counts.latency_p50);
    EXPECT_EQ(samples("loop-latency", "p99"), counts.latency_p99);
    EXPECT_EQ(samples("loop-latency", "max"), counts.latency_max);
    EXPECT_EQ(text->find("the loop latency"), std::string::npos) << "the demo's log has it";
  }

  // Chromium draws it, and what it draws is not a blank page.
  std::string why_not;
  bool required = false;
  const std::string chromium = test::find_chromium(why_not, required);
  if (chromium.empty()) {
    if (required) FAIL() << why_not;
    GTEST_SKIP() << why_not;
  }
  const std::string shot = HITL_REPORT_SCREENSHOT;
  std::filesystem::remove(shot);
  ASSERT_EQ(screenshot(chromium, html, shot, dir + "/profile"), "");
  const std::string blank_html = dir + "/blank.html", blank_png = dir + "/blank.png";
  std::ofstream(blank_html) << "<!DOCTYPE html><html><body></body></html>\n";
  ASSERT_EQ(screenshot(chromium, blank_html, blank_png, dir + "/profile"), "");
  const auto shot_bytes = std::filesystem::file_size(shot), blank_bytes = std::filesystem::file_size(blank_png);
  // A white 1200x3200 page compresses to a few KiB; the report's plots and tables to far more.
  EXPECT_GT(shot_bytes, 10 * blank_bytes) << shot << ": " << shot_bytes << " bytes, a blank page " << blank_bytes;
  std::cout << "screenshot: " << shot << " (" << shot_bytes << " bytes)\n";

  // The page's script: no error; zoom one time plot and every time plot's x range follows.
  const auto probe = test::probe_in_chromium(chromium, html, dir, kZoomProbe);
  ASSERT_FALSE(probe.contains("failure")) << probe.dump();
  EXPECT_EQ(probe["errors"].size(), 0u) << probe["errors"].dump();
  const auto data = page_data(page);
  ASSERT_FALSE(data.is_null());
  EXPECT_EQ(probe["ids"].size(), data["plots"].size()) << "a dygraph for every time plot";
  EXPECT_GE(probe["ids"].size(), 10u);
  EXPECT_GE(probe["canvases"].get<int>(), 2 * static_cast<int>(probe["ids"].size())) << "each plot drew its canvases";
  const double zoom0 = probe["zoom"][0], zoom1 = probe["zoom"][1];
  for (std::size_t i = 0; i < probe["after"].size(); ++i) {
    EXPECT_NEAR(probe["after"][i][0].get<double>(), zoom0, 1e-6) << probe["ids"][i];
    EXPECT_NEAR(probe["after"][i][1].get<double>(), zoom1, 1e-6) << probe["ids"][i];
    EXPECT_GT(probe["before"][i][1].get<double>() - probe["before"][i][0].get<double>(), 10.0) << probe["ids"][i];
  }
  // Hovering one plot selects the nearest time in every other and shows the values there.
  ASSERT_FALSE(probe["hover_t"].is_null()) << probe.dump().substr(0, 400);
  for (std::size_t i = 0; i < probe["selected"].size(); ++i) {
    ASSERT_FALSE(probe["selected"][i].is_null()) << probe["ids"][i];
    EXPECT_NEAR(probe["selected"][i].get<double>(), probe["hover_t"].get<double>(), 0.6) << probe["ids"][i];  // the 1 s windows' middles
  }
  EXPECT_EQ(probe["first_legend"].get<std::string>().rfind("t = ", 0), 0u) << probe["first_legend"];
  // The legend's series names toggle their series.
  EXPECT_NE(probe["legend_item"], nullptr);
  EXPECT_EQ(probe["visible_after_click"], false);
  std::cout << "the page's script drew " << probe["ids"].size() << " time plots " << probe["drawn_ms"].get<double>()
            << " ms after navigation started (" << page.size() / 1024 << " KiB page)\n";
}

TEST(ReportE2E, SimWithATrajectoryAndReportRecordsBesideThePageAndMarksTheFaults) {
  // hitl sim -t --report against hitl target: no --record given, the recording goes beside the page.
  const std::string dir = test::temp_dir();
  const uint16_t hil = test::free_udp_port(), gcs = test::free_udp_port(), sim_local = test::free_udp_port();
  test::Process board({test::hitl_binary(), "target", "--bind", "127.0.0.1", "--hil-port", std::to_string(hil), "--gcs-port",
                       std::to_string(gcs), "--vio-port", "0", "--lockstep"});
  ASSERT_TRUE(board.wait_for_stderr("EMULATED", 10s)) << board.err();
  test::Process sim({test::hitl_binary(), "sim", "-i", "127.0.0.1", "--hil-port", std::to_string(hil), "--local-port",
                     std::to_string(sim_local), "--no-vio", "--clients", "0", "--lockstep", "--speed", "0", "-t",
                     std::string(HITL_SOURCE_DIR) + "/docs/examples/square.json", "--fault", "gps-loss@15+3", "--fault",
                     "imu-vibration:8,90@20+2", "--report", dir + "/flight.html"});
  EXPECT_EQ(sim.wait(150s), 0) << sim.err();
  board.signal(SIGINT);
  board.wait(20s);
  EXPECT_EQ(last_line(sim.out()), dir + "/flight.html") << sim.out();
  EXPECT_NE(sim.err().find("--report: recording to " + dir + "/flight.tlog"), std::string::npos) << sim.err();
  EXPECT_TRUE(std::filesystem::exists(dir + "/flight.tlog"));
  const std::string page = read_file(dir + "/flight.html");
  for (const char* id : {"top-view", "altitude", "tracking-error", "motors", "rates"})
    EXPECT_NE(page.find(std::string("<figure id=\"plot-") + id + "\""), std::string::npos) << id;
  // The fault's start and end and the pilot's states are events with their simulated times.
  EXPECT_NE(page.find("<td>15.00</td><td>simulator</td><td>info</td><td>t=15.000 s fault gps-loss started (3 s)</td>"),
            std::string::npos);
  EXPECT_NE(page.find("<td>pilot</td><td>info</td><td>trajectory: HOLD (trajectory flown)</td>"), std::string::npos);
  EXPECT_EQ(page.find("What this log lacks</h2>\n<ul class=\"lacks\" id=\"lacks\">\n<li>ground truth"), std::string::npos);
  // Each fault in the summary with its arguments named, and its window in the page's data.
  EXPECT_NE(page.find("<tr><th>fault</th><td>gps-loss: from 15.00 s to 18.00 s (3.0 s)</td></tr>"), std::string::npos);
  EXPECT_NE(page.find("<tr><th>fault</th><td>imu-vibration (amp_m_s2 8, freq_hz 90): from 20.00 s to 22.00 s (2.0 s)</td></tr>"),
            std::string::npos);
  const auto data = page_data(page);
  ASSERT_FALSE(data.is_null());
  EXPECT_EQ(data["faults"].dump(),
            R"([{"label":"gps-loss","t0":15.0,"t1":18.0},{"label":"imu-vibration:8,90","t0":20.0,"t1":22.0}])");
  bool position = false;
  for (const auto& m : data["modes"]) position = position || m["mode"] == "Position";
  EXPECT_TRUE(position) << data["modes"].dump();

  // The vibration at 90 Hz is the accelerometer spectrum's peak (at 250 Hz no fold: below 125 Hz).
  {
    auto log = report::read_flight_log(dir + "/flight.tlog");
    ASSERT_TRUE(log) << log.error().message;
    for (const auto& p : report::plots_of(*log))
      if (p.id == "vibration")
        for (const auto& series : p.series) {
          if (series.title == "z (down)") continue;  // the vibration is along x and y
          std::size_t best = 0;
          for (std::size_t k = 0; k < series.y.size(); ++k)
            if (series.x[k] > 20 && series.y[k] > series.y[best]) best = k;
          EXPECT_NEAR(series.x[best], 90, 1) << series.title;
          EXPECT_GT(series.y[best], 1.0) << series.title << ": 8 m/s^2 for 2 s of the flight";
        }
  }
  // On the static page each time plot has both windows labelled (gnuplot's labels).
  auto static_run = test::run_hitl({"report", dir + "/flight.tlog", "--static", "-o", dir + "/static.html"});
  ASSERT_EQ(static_run.exit_code, 0) << static_run.err;
  const std::string static_page = read_file(dir + "/static.html");
  auto count = [&](const std::string& needle) {
    std::size_t n = 0;
    for (std::size_t at = 0; (at = static_page.find(needle, at)) != std::string::npos; at += needle.size()) ++n;
    return n;
  };
  const auto static_figures = figures_of(static_page);
  ASSERT_TRUE(static_figures.count("top-view") && static_figures.count("vibration"));
  const std::size_t time_plots = static_figures.size() - 2;  // all but the top view and the spectrum
  EXPECT_GE(time_plots, 10u);
  EXPECT_EQ(count(">gps-loss<"), time_plots);
  EXPECT_EQ(count(">imu-vibration:8,90<"), time_plots);

  // Both windows shaded behind every time plot, and nothing red at 5 s, before them.
  const std::string chromium = test::find_program("chromium");
  if (chromium.empty()) return;  // the demo's test says why
  const auto probe = test::probe_in_chromium(chromium, dir + "/flight.html", dir, kShadeProbe);
  ASSERT_FALSE(probe.contains("failure")) << probe.dump();
  EXPECT_EQ(probe["errors"].size(), 0u) << probe["errors"].dump();
  ASSERT_EQ(probe["ids"].size(), data["plots"].size());
  for (std::size_t i = 0; i < probe["ids"].size(); ++i) {
    for (std::size_t k = 0; k < 2; ++k) EXPECT_GE(probe["inside"][i][k].get<double>(), 0.5) << probe["ids"][i] << " fault " << k;
    EXPECT_LE(probe["outside"][i].get<double>(), 0.25) << probe["ids"][i];
  }
}

/// The altitude plot's series `title` as drawn: time -> height.
std::vector<std::pair<double, double>> altitude_series(const std::vector<report::Plot>& plots, const std::string& title) {
  std::vector<std::pair<double, double>> out;
  for (const auto& p : plots)
    if (p.id == "altitude")
      for (const auto& s : p.series)
        if (s.title == title)
          for (std::size_t i = 0; i < s.x.size(); ++i) out.emplace_back(s.x[i], s.y[i]);
  return out;
}

double nearest(const std::vector<std::pair<double, double>>& series, double t_s) {
  auto it = std::lower_bound(series.begin(), series.end(), std::pair{t_s, -1e300});
  if (it == series.end()) return series.back().second;
  if (it != series.begin() && t_s - (it - 1)->first < it->first - t_s) --it;
  return it->second;
}

/// `hitl sim -t` a 2.5 m hover of `hover_s` seconds against `hitl target --lockstep`, recorded to
/// DIR/NAME; the recording's path (empty, with a test failure, when the flight did not end well).
std::string record_hover_against_target(const std::string& dir, const std::string& name, int hover_s) {
  const std::string trajectory = dir + "/hover.json";
  std::ofstream(trajectory) << R"({"waypoints": [{"t": 0, "x": 0, "y": 0, "z": 2.5, "yaw": 0},
                                                 {"t": )" << hover_s << R"(, "x": 0, "y": 0, "z": 2.5, "yaw": 0}]})";
  return test::record_against_target(dir + "/" + name, {"-t", trajectory}, 150s);
}

TEST(ReportE2E, AHoverAt2_5mPlotsTruthSetpointAndEstimateWithinCentimetres) {
  // hitl sim -t a 2.5 m hover --record against hitl target: every height on one datum (from home,
  // 0.00 m on the ground: docs/sim.md), so the plot shows no error the flight did not have.
  const std::string tlog = record_hover_against_target(test::temp_dir(), "hover.tlog", 10);
  ASSERT_FALSE(tlog.empty());
  auto log = report::read_flight_log(tlog);
  ASSERT_TRUE(log) << log.error().message;
  const auto plots = report::plots_of(*log);
  const auto setpoint = altitude_series(plots, "setpoint"), truth = altitude_series(plots, "truth"),
             estimate = altitude_series(plots, "estimate");
  ASSERT_FALSE(setpoint.empty());
  ASSERT_FALSE(truth.empty());
  ASSERT_FALSE(estimate.empty());
  // At rest before the climb: the truth 0.00 m, the emulated estimate noisy (its barometer) about 0.
  auto mean_before = [](const std::vector<std::pair<double, double>>& s, double t_s) {
    double sum = 0;
    std::size_t n = 0;
    for (const auto& [t, v] : s)
      if (t < t_s) sum += v, ++n;
    return n > 0 ? sum / static_cast<double>(n) : NAN;
  };
  const double climb_s = setpoint.front().first - 3;  // the pilot takes off before its first setpoint
  EXPECT_NEAR(truth.front().second, 0.0, 0.01) << "at rest, on the ground";
  EXPECT_NEAR(mean_before(estimate, climb_s), 0.0, 0.05) << "at rest, on the ground";
  // The hover: from 3 s after the trajectory started (the climb settled) to its last setpoint. The
  // setpoints are 2.5 m; the truth and the estimate agree with them on average within centimetres
  // (the emulated estimator's noise is a few centimetres either way).
  std::size_t compared = 0;
  double setpoint_sum_m = 0, truth_sum_m = 0, estimate_sum_m = 0;
  for (const auto& [t_s, sp_m] : setpoint) {
    if (t_s < setpoint.front().first + 3) continue;
    setpoint_sum_m += sp_m;
    truth_sum_m += nearest(truth, t_s);
    estimate_sum_m += nearest(estimate, t_s);
    ++compared;
  }
  ASSERT_GT(compared, 100u);
  const double n = static_cast<double>(compared);
  EXPECT_NEAR(setpoint_sum_m / n, 2.5, 0.01);
  EXPECT_NEAR(truth_sum_m / n, 2.5, 0.03) << "the truth in the hover, from home";
  EXPECT_NEAR(estimate_sum_m / n, 2.5, 0.05) << "the estimate in the hover, from home";
  std::cout << "hover at 2.5 m: setpoint " << setpoint_sum_m / n << " m, truth " << truth_sum_m / n << " m, estimate "
            << estimate_sum_m / n << " m (mean of " << compared << " setpoints); at rest: truth " << truth.front().second
            << " m, estimate " << mean_before(estimate, climb_s) << " m\n";
}

TEST(ReportE2E, FlyTrajectoryReportThroughASessionIsScoredOnTheEstimate) {
  // hitl fly trajectory --report, through a session: the link's frames (the board's telemetry, the
  // session's truth) and the pilot's setpoints and errors, against the board's estimate.
  const std::string dir = test::temp_dir();
  test::LockstepSessionWithClients session;
  ASSERT_EQ(session.failure(), "");
  auto r = test::run_hitl(
      session.fly({"trajectory", std::string(HITL_SOURCE_DIR) + "/docs/examples/square.json", "--report", dir + "/fly.html"}),
      120s);
  session.stop();
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const auto j = test::last_json_line(r.out);
  EXPECT_EQ(j["report"]["path"], dir + "/fly.html");
  const std::string page = read_file(dir + "/fly.html");
  EXPECT_NE(page.find("RMS " + fixed2(j["rms_m"]) + " m, max " + fixed2(j["max_m"]) + " m (" +
                      std::to_string(j["samples"].get<uint64_t>()) + " samples)"),
            std::string::npos)
      << j.dump().substr(0, 300);
  const auto figures = figures_of(page);
  for (const char* id : {"top-view", "altitude", "tracking-error"}) EXPECT_TRUE(figures.count(id)) << id;
  bool truth = false;
  for (const auto& s : figures.at("top-view")) truth = truth || s.title == "truth";
  EXPECT_TRUE(truth) << "the session's truth ODOMETRY reached the recording";
}

TEST(ReportE2E, APlainPeersLogGivesWhatItHasAndSaysWhatItLacks) {
  // hitl target (the board's MAVLink, no simulator) recorded by hitl inspect: no truth, no pilot.
  const std::string dir = test::temp_dir();
  const std::string hil = std::to_string(test::free_udp_port()), gcs = std::to_string(test::free_udp_port());
  test::Process board({test::hitl_binary(), "target", "--bind", "127.0.0.1", "--hil-port", hil, "--gcs-port", gcs, "--vio-port", "0"});
  ASSERT_TRUE(board.wait_for_stderr("EMULATED", 10s)) << board.err();
  auto rec = test::run_hitl({"inspect", "--connect", "127.0.0.1:" + gcs, "--local-port", std::to_string(test::free_udp_port()),
                             "--duration", "4", "--record", dir + "/plain.tlog"},
                            30s);
  board.signal(SIGINT);
  board.wait(10s);
  ASSERT_EQ(rec.exit_code, 0) << rec.err;

  auto r = test::run_hitl({"report", dir + "/plain.tlog"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(last_line(r.out), dir + "/plain.html");
  EXPECT_NE(r.err.find("the log lacks:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("ground truth"), std::string::npos) << r.err;
  const std::string page = read_file(dir + "/plain.html");
  EXPECT_NE(page.find("What this log lacks"), std::string::npos);
  EXPECT_NE(page.find("the simulator's clock"), std::string::npos);
  EXPECT_NE(page.find("the loop latency (no hitl session status in this log"), std::string::npos);
  EXPECT_FALSE(figures_of(page).count("loop-latency"));
  const auto figures = figures_of(page);
  // Without sensor input the board has an attitude and EKF test ratios, but no position.
  EXPECT_TRUE(figures.count("attitude-roll")) << "the board's ATTITUDE is drawn";
  EXPECT_TRUE(figures.count("ekf")) << "the board's ESTIMATOR_STATUS is drawn";
  EXPECT_FALSE(figures.count("top-view"));
  // A plot the log has no data for says so in its place, naming the messages it would come from.
  EXPECT_NE(page.find("<figure id=\"lacks-top-view\" class=\"lacking\"><p><b>Top view: setpoint, truth and estimate</b>: this log "
                      "has no POSITION_TARGET_LOCAL_NED (setpoint)"),
            std::string::npos);
  EXPECT_NE(page.find("<figure id=\"lacks-sticks\" class=\"lacking\"><p><b>Sticks</b>: this log has no MANUAL_CONTROL or RC_CHANNELS_OVERRIDE"),
            std::string::npos);
  EXPECT_NE(page.find("the vehicle's position estimate (LOCAL_POSITION_NED)"), std::string::npos);
  EXPECT_FALSE(figures.count("tracking-error"));
  for (const auto& [id, series] : figures)
    for (const auto& s : series) {
      EXPECT_NE(s.title, "truth") << id;
      EXPECT_EQ(s.drawn, s.points) << id << " / " << s.title;
    }
  EXPECT_NE(page.find("hitl target: an emulated VOXL2 board"), std::string::npos) << "its STATUSTEXT is an event";

  // --json: one summary line with what it lacks.
  auto j = test::run_hitl({"--json", "report", dir + "/plain.tlog", "-o", dir + "/again.html"});
  ASSERT_EQ(j.exit_code, 0) << j.err;
  const auto s = test::last_json_line(j.out);
  EXPECT_EQ(s["type"], "summary");
  EXPECT_EQ(s["path"], dir + "/again.html");
  EXPECT_GT(s["lacks"].size(), 3u);
  EXPECT_EQ(s["interactive"], true);
  EXPECT_TRUE(s["static_because"].is_null());

  // Without dygraphs' files: the static page, and the file that is missing named.
  const std::string nowhere = dir + "/no-dygraphs";
  auto fallback = test::run_hitl({"report", dir + "/plain.tlog", "--dygraphs", nowhere, "-o", dir + "/fallback.html"});
  ASSERT_EQ(fallback.exit_code, 0) << fallback.err;
  EXPECT_NE(fallback.err.find("hitl report: " + nowhere + "/dygraph.min.js is missing (Debian/Ubuntu: apt-get install libjs-dygraphs)"),
            std::string::npos)
      << fallback.err;
  EXPECT_NE(fallback.err.find("wrote the static page"), std::string::npos) << fallback.err;
  EXPECT_EQ(read_file(dir + "/fallback.html").find("<script"), std::string::npos);
  auto fallback_json = test::run_hitl({"--json", "report", dir + "/plain.tlog", "--dygraphs", nowhere, "-o", dir + "/fallback.html"});
  ASSERT_EQ(fallback_json.exit_code, 0) << fallback_json.err;
  const auto f = test::last_json_line(fallback_json.out);
  EXPECT_EQ(f["interactive"], false);
  EXPECT_NE(f["static_because"].get<std::string>().find(nowhere + "/dygraph.min.js is missing"), std::string::npos) << f.dump();
}

TEST(ReportE2E, PX4sULogIsMergedGivenOrFoundBesideTheRecordingAndABadOneIsNamed) {
  // A hitl sim recording (against hitl target), and ULogs written here on its simulator's clock.
  const std::string dir = test::temp_dir();
  const std::string tlog = record_hover_against_target(dir, "s.tlog", 4);
  ASSERT_FALSE(tlog.empty());
  // PX4's estimate at 2.5 m from 1 s to 5 s of the simulator's clock, 50 Hz.
  test::ULogWriter w;
  w.format("vehicle_local_position:uint64_t timestamp;float x;float y;float z;bool xy_valid;bool z_valid;");
  w.format("vehicle_rates_setpoint:uint64_t timestamp;float roll;float pitch;float yaw;");
  w.subscribe(0, "vehicle_local_position");
  w.subscribe(1, "vehicle_rates_setpoint");
  for (uint64_t t_us = 1'000'000; t_us <= 5'000'000; t_us += 20'000) {
    w.data(0, test::ULogWriter::raw(t_us) + test::ULogWriter::raw(0.0F) + test::ULogWriter::raw(0.0F) +
                  test::ULogWriter::raw(-2.5F) + std::string("\1\1", 2));
    // PX4's rate controller's input: 0.5 rad/s of roll (28.6 deg/s).
    w.data(1, test::ULogWriter::raw(t_us) + test::ULogWriter::raw(0.5F) + test::ULogWriter::raw(0.0F) + test::ULogWriter::raw(0.0F));
  }
  std::ofstream(dir + "/px4.ulg", std::ios::binary) << w.text();

  auto given = test::run_hitl({"--json", "report", tlog, "--ulog", dir + "/px4.ulg", "-o", dir + "/given.html"});
  ASSERT_EQ(given.exit_code, 0) << given.err;
  auto j = test::last_json_line(given.out);
  EXPECT_EQ(j["ulog"]["path"], dir + "/px4.ulg");
  EXPECT_EQ(j["ulog"]["found"], false);
  EXPECT_EQ(j["ulog"]["positions"], 201);
  const std::string page = read_file(dir + "/given.html");
  for (const char* id : {"px4-altitude", "px4-offset"})
    EXPECT_NE(page.find(std::string("<figure id=\"plot-") + id + "\""), std::string::npos) << id;
  // PX4's rate setpoint from its ULog in the rate tracking plot, in deg/s.
  bool rate_setpoint = false;
  const auto data = page_data(page);
  for (const auto& p : data["plots"])
    if (p["id"] == "rate-roll")
      for (const auto& series : p["series"])
        if (series["title"] == "PX4 setpoint (ULog)") {
          rate_setpoint = true;
          EXPECT_EQ(series["t"].size(), 201u);
          EXPECT_NEAR(series["y"][0].get<double>(), 28.6479, 1e-3);
        }
  EXPECT_TRUE(rate_setpoint);
  EXPECT_EQ(page.find("no rate setpoint"), std::string::npos) << "PX4's ULog has it";

  // Not given: the newest FILE.px4/log/**.ulg beside FILE.tlog, said on stderr.
  std::filesystem::create_directories(dir + "/s.px4/log/2026-11-29");
  std::filesystem::copy_file(dir + "/px4.ulg", dir + "/s.px4/log/2026-11-29/09_00_00.ulg");
  auto found = test::run_hitl({"report", tlog, "-o", dir + "/found.html"});
  ASSERT_EQ(found.exit_code, 0) << found.err;
  EXPECT_NE(found.err.find("hitl report: PX4's ULog " + dir + "/s.px4/log/2026-11-29/09_00_00.ulg (found beside the recording): "
                           "mean offset against truth"),
            std::string::npos)
      << found.err;
  auto refused = test::run_hitl({"--json", "report", tlog, "--no-ulog", "-o", dir + "/none.html"});
  ASSERT_EQ(refused.exit_code, 0) << refused.err;
  EXPECT_TRUE(test::last_json_line(refused.out)["ulog"].is_null());

  // A bad ULog given is bad input, named; a bad one found beside is said and left out.
  std::ofstream(dir + "/junk.ulg") << "not a ULog\n";
  auto junk = test::run_hitl({"report", tlog, "--ulog", dir + "/junk.ulg", "-o", dir + "/junk.html"});
  EXPECT_EQ(junk.exit_code, 2) << junk.err;
  EXPECT_NE(junk.err.find("hitl report: '" + dir + "/junk.ulg' is not a ULog"), std::string::npos) << junk.err;
  std::filesystem::copy_file(dir + "/junk.ulg", dir + "/s.px4/log/2026-11-29/09_30_00.ulg");
  auto beside = test::run_hitl({"--json", "report", tlog, "-o", dir + "/beside.html"});
  ASSERT_EQ(beside.exit_code, 0) << beside.err;
  j = test::last_json_line(beside.out);
  EXPECT_TRUE(j["ulog"].is_null());
  EXPECT_NE(j["lacks"].dump().find("PX4's ULog found beside the recording ('" + dir + "/s.px4/log/2026-11-29/09_30_00.ulg' is not a ULog"),
            std::string::npos)
      << j.dump();
}

/// Zooms the first time plot to 2 s and reads every time plot's x range after, and the --plot plots'
/// series as dygraphs holds them (their labels and the rows drawn).
constexpr const char* kFieldPlotProbe = R"(out.ids=r.ids;
var g=r.graphs[0],x=g.xAxisRange(),a=x[0]+0.4*(x[1]-x[0]);out.zoom=[a,a+2];g.updateOptions({dateWindow:out.zoom});
out.after=r.graphs.map(function(o){return o.xAxisRange()});
out.fields=r.ids.map(function(id,i){return id.indexOf('field-')==0?{id:id,labels:r.graphs[i].getLabels(),rows:r.graphs[i].numRows()}:null}).filter(function(f){return f});
out.canvases=document.querySelectorAll('figure.time-plot canvas').length;)";

TEST(ReportE2E, PlotOfAnyFieldJoinsTheLinkedZoomOnBothPagesAndBadOnesAreNamed) {
  // hitl report --plot on a recorded flight (hitl sim against hitl target): the named fields as one
  // more time plot each, drawn by Chromium without an error, following the zoom of the others.
  const std::string dir = test::temp_dir();
  const std::string tlog = record_hover_against_target(dir, "f.tlog", 4);
  ASSERT_FALSE(tlog.empty());
  auto r = test::run_hitl({"--json", "report", tlog, "--plot", "ATTITUDE.roll, ATTITUDE.pitch", "--plot",
                           "HIL_ACTUATOR_CONTROLS.controls[0]*100", "--plot", "SERIAL_CONTROL.baudrate", "-o", dir + "/f.html"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string page = read_file(dir + "/f.html");
  const auto data = page_data(page);
  ASSERT_FALSE(data.is_null());
  std::map<std::string, nlohmann::json> plots;
  for (const auto& p : data["plots"]) plots[p["id"]] = p;
  ASSERT_TRUE(plots.count("field-1")) << "the first --plot";
  EXPECT_EQ(plots["field-1"]["title"], "ATTITUDE.roll, ATTITUDE.pitch");
  EXPECT_EQ(plots["field-1"]["y_label"], "rad") << "both one field of one unit";
  ASSERT_EQ(plots["field-1"]["series"].size(), 2u);
  EXPECT_EQ(plots["field-1"]["series"][0]["title"], "ATTITUDE.roll");
  EXPECT_EQ(plots["field-1"]["series"][1]["title"], "ATTITUDE.pitch");
  EXPECT_GT(plots["field-1"]["series"][0]["t"].size(), 20u);
  // The motor command in percent: 0 to 100, hovering above 20.
  ASSERT_TRUE(plots.count("field-2"));
  double high = 0;
  for (const auto& y : plots["field-2"]["series"][0]["y"]) {
    if (y.is_null()) continue;
    EXPECT_GE(y.get<double>(), 0.0);
    EXPECT_LE(y.get<double>(), 100.0);
    high = std::max(high, y.get<double>());
  }
  EXPECT_GT(high, 20.0);
  // Each figure claims the series it holds (points and samples), as every plot does; a message the
  // log lacks keeps the plot's place.
  const auto figures = figures_of(page);
  ASSERT_TRUE(figures.count("field-1"));
  for (const auto& c : figures.at("field-1")) EXPECT_EQ(c.points, c.drawn) << c.title;
  EXPECT_NE(page.find("<figure id=\"lacks-field-3\" class=\"lacking\">"), std::string::npos) << "no shell was used: no SERIAL_CONTROL";
  EXPECT_NE(page.find("this log has no SERIAL_CONTROL"), std::string::npos);
  // The last section: the parameters (a hitl sim recording: none read over its HIL link).
  EXPECT_NE(page.find("<h2>Parameters that differ from the defaults</h2>"), std::string::npos);

  // The static page draws them too (gnuplot's SVG, the series by name).
  auto static_run = test::run_hitl({"report", tlog, "--static", "--plot", "ATTITUDE.roll,ATTITUDE.pitch", "-o", dir + "/s.html"});
  ASSERT_EQ(static_run.exit_code, 0) << static_run.err;
  const auto static_figures = figures_of(read_file(dir + "/s.html"));
  ASSERT_TRUE(static_figures.count("field-1"));
  ASSERT_EQ(static_figures.at("field-1").size(), 2u);
  for (const auto& c : static_figures.at("field-1")) {
    EXPECT_EQ(c.title.rfind("ATTITUDE.", 0), 0u) << c.title;
    EXPECT_EQ(c.points, c.drawn) << c.title;
  }

  // Bad values: exit 2, the value and the place named, nothing written.
  for (const auto& [value, said] : std::vector<std::pair<std::string, std::string>>{
           {"ATTITUDE.rol", "hitl report: --plot 'ATTITUDE.rol' at character 10: ATTITUDE has no field 'rol' (its fields: "},
           {"HIL_ACTUATOR_CONTROLS.controls[99]", "at character 32: the index of HIL_ACTUATOR_CONTROLS.controls is 0 to 15"},
           {"ATTITUDE.roll*(2", "at character 15: '(' without its ')'"},
           {std::string(2000, '('), "at character 1001: longer than 1000 characters"}}) {
    auto bad = test::run_hitl({"report", tlog, "--plot", value, "-o", dir + "/bad.html"});
    EXPECT_EQ(bad.exit_code, 2) << value << ": " << bad.err;
    EXPECT_NE(bad.err.find(said), std::string::npos) << bad.err;
    EXPECT_FALSE(std::filesystem::exists(dir + "/bad.html"));
  }

  // Chromium draws the page without an error; zooming one time plot zooms the --plot plots too.
  const std::string chromium = test::find_program("chromium");
  if (chromium.empty()) return;  // the demo's test says why
  const auto probe = test::probe_in_chromium(chromium, dir + "/f.html", dir, kFieldPlotProbe);
  ASSERT_FALSE(probe.contains("failure")) << probe.dump();
  EXPECT_EQ(probe["errors"].size(), 0u) << probe["errors"].dump();
  ASSERT_EQ(probe["fields"].size(), 2u) << probe.dump();  // the third lacks its data
  EXPECT_EQ(probe["fields"][0]["labels"].dump(), R"(["t","ATTITUDE.roll","ATTITUDE.pitch"])");
  EXPECT_GT(probe["fields"][0]["rows"].get<int>(), 20);
  EXPECT_EQ(probe["canvases"].get<int>() > 0, true);
  for (std::size_t i = 0; i < probe["after"].size(); ++i) {
    EXPECT_NEAR(probe["after"][i][0].get<double>(), probe["zoom"][0].get<double>(), 1e-6) << probe["ids"][i];
    EXPECT_NEAR(probe["after"][i][1].get<double>(), probe["zoom"][1].get<double>(), 1e-6) << probe["ids"][i];
  }
}

TEST(ReportE2E, AParameterSetThroughARecordingSessionShowsInTheParametersTable) {
  // hitl params set through hitl sim's client port while it records: the board's PARAM_VALUE (the
  // value read first, then its echo) are in the recording, and the report's last section says so.
  const std::string dir = test::temp_dir();
  std::ofstream(dir + "/hover.json") << R"({"waypoints": [{"t": 0, "x": 0, "y": 0, "z": 2.5, "yaw": 0},
                                                          {"t": 6, "x": 0, "y": 0, "z": 2.5, "yaw": 0}]})";
  const uint16_t hil = test::free_udp_port(), clients = test::free_udp_port();
  test::Process board({test::hitl_binary(), "target", "--bind", "127.0.0.1", "--hil-port", std::to_string(hil), "--gcs-port",
                       std::to_string(test::free_udp_port()), "--vio-port", "0", "--lockstep"});
  ASSERT_TRUE(board.wait_for_stderr("EMULATED", 10s)) << board.err();
  test::Process sim({test::hitl_binary(), "sim", "-i", "127.0.0.1", "--hil-port", std::to_string(hil), "--local-port",
                     std::to_string(test::free_udp_port()), "--no-vio", "--clients", std::to_string(clients), "--lockstep", "--speed",
                     "3", "-t", dir + "/hover.json", "--record", dir + "/p.tlog"});
  ASSERT_TRUE(sim.wait_for_stderr("trajectory:", 30s)) << sim.err();
  auto set = test::run_hitl({"params", "--connect", "udp:127.0.0.1:" + std::to_string(clients), "--local-port",
                             std::to_string(test::free_udp_port()), "set", "MPC_XY_P", "1.1"},
                            30s);
  EXPECT_EQ(set.exit_code, 0) << set.out << set.err;
  EXPECT_EQ(sim.wait(90s), 0) << sim.err();
  board.signal(SIGINT);
  board.wait(20s);
  auto r = test::run_hitl({"report", dir + "/p.tlog", "-o", dir + "/p.html"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string page = read_file(dir + "/p.html");
  EXPECT_NE(page.find("Values: PARAM_VALUE in this log ("), std::string::npos);
  EXPECT_NE(page.find("Defaults: the spec's HITL set that hitl target boots with"), std::string::npos);
  EXPECT_NE(page.find("<tr><td>MPC_XY_P</td><td>1.1</td><td>0.95</td></tr>"), std::string::npos)
      << page.substr(page.find("<h2>Parameters that differ"), 1500);
}

TEST(ReportE2E, NotATlogIsBadInputNamed) {
  const std::string dir = test::temp_dir();
  std::ofstream(dir + "/notes.txt") << "not a telemetry log\n";
  {  // noise (fixed, so the same every run): whatever looks like a frame of an unknown id is not a log
    std::string bytes(100000, '\0');
    uint32_t x = 12345;
    for (char& c : bytes) c = static_cast<char>((x = x * 1664525u + 1013904223u) >> 24);
    std::ofstream(dir + "/random.tlog", std::ios::binary) << bytes;
  }
  auto noise = test::run_hitl({"report", dir + "/random.tlog"});
  EXPECT_EQ(noise.exit_code, 2) << noise.err;
  auto r = test::run_hitl({"report", dir + "/notes.txt"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("hitl report: '" + dir + "/notes.txt' holds no MAVLink frame"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir + "/notes.html"));
}

}  // namespace
}  // namespace hitl
