// hitl report FILE.tlog [-o report.html]: a recording to one self-contained HTML page (docs/report.md).
#include <cstdio>
#include <iostream>
#include <memory>

#include "cli/commands.h"
#include "cli/report_output.h"
#include "cli/version.h"
#include "base/mavlink/message_set.h"
#include "engine/report/field_expression.h"
#include "engine/report/report.h"

namespace hitl::cli {

/// --plot given more often than this is refused (each is a plot on the page).
constexpr std::size_t kMaxFieldPlots = 20;

std::string default_report_path(const std::string& tlog_path) {
  const std::string ext = ".tlog";
  if (tlog_path.size() > ext.size() && tlog_path.compare(tlog_path.size() - ext.size(), ext.size(), ext) == 0)
    return tlog_path.substr(0, tlog_path.size() - ext.size()) + ".html";
  return tlog_path + ".html";
}

Expected<report::ReportResult> write_report_and_say(const GlobalOptions& g, const std::string& command,
                                                    const std::string& tlog_path, const std::string& html_path,
                                                    const report::ReportOptions& report_options) {
  report::ReportOptions options = report_options;
  options.generator = std::string("hitl ") + kVersion;
  auto r = report::write_report(tlog_path, html_path, options);
  if (!r) {
    log_error(command, (command == "report" ? "" : "--report: ") + r.error().message);
    return r.error();
  }
  if (!g.json && !g.quiet) {
    char line[160];
    if (!r->static_because.empty())
      std::cerr << "hitl " << command << ": " << r->static_because << ": wrote the static page (gnuplot's SVGs) instead\n";
    std::snprintf(line, sizeof line, "hitl %s: report of %s: %zu plots, %.0f KiB in %.1f s%s", command.c_str(), tlog_path.c_str(),
                  r->plots, static_cast<double>(r->bytes) / 1024.0, r->seconds, r->missing.empty() ? "" : "; the log lacks:");
    std::cerr << line << '\n';
    for (const auto& m : r->missing) std::cerr << "  " << m << '\n';
    if (r->px4) {
      const auto& m = r->px4->mean_offset_NED_m;
      const int n = std::snprintf(line, sizeof line, "mean offset against truth north %.3f m, east %.3f m, up %.3f m, RMS %.3f m",
                                  m[0], m[1], -m[2], r->px4->rms_m);
      if (r->px4->lag_s && n > 0 && static_cast<std::size_t>(n) < sizeof line)
        std::snprintf(line + n, sizeof line - static_cast<std::size_t>(n), ", lag %.0f ms", *r->px4->lag_s * 1e3);
      std::cerr << "hitl " << command << ": PX4's ULog " << r->ulog_path << (r->ulog_found ? " (found beside the recording)" : "")
                << ": " << line << '\n';
    }
    if (!r->skipped.empty()) std::cerr << "hitl " << command << ": not drawn from the damaged log:\n";
    for (const auto& m : r->skipped) std::cerr << "  " << m << '\n';
  }
  return r;
}

nlohmann::json report_json(const report::ReportResult& r) {
  nlohmann::json ulog = nullptr;
  if (r.px4) {
    const auto& m = r.px4->mean_offset_NED_m;
    ulog = {{"path", r.ulog_path},
            {"found", r.ulog_found},
            {"version", r.px4->version},
            {"positions", r.px4->position.size()},
            {"offset_m", {{"north", m[0]}, {"east", m[1]}, {"up", -m[2]}, {"rms", r.px4->rms_m}}},
            {"lag_ms", r.px4->lag_s ? nlohmann::json(*r.px4->lag_s * 1e3) : nlohmann::json(nullptr)}};
  }
  return {{"path", r.html_path}, {"bytes", r.bytes}, {"plots", r.plots}, {"seconds", r.seconds},
          {"interactive", r.interactive}, {"static_because", r.static_because.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.static_because)},
          {"lacks", r.missing}, {"skipped", r.skipped}, {"ulog", ulog}};
}

void add_report_command(CLI::App& app, GlobalOptions& options, RunState& state) {
  struct ReportOptions {
    std::string tlog;
    std::string output;
    std::string ulog;
    bool no_ulog = false;
    bool static_page = false;
    std::string dygraphs = report::kDebianDygraphsDir;
    std::vector<std::string> plots;
  };
  auto o = std::make_shared<ReportOptions>();
  auto* sub = app.add_subcommand(
      "report", "Draw a recording (.tlog) as one self-contained HTML page: flight path, altitude, tracking error, velocity, "
                "attitude, rate tracking, motors, sticks, raw IMU and its vibration spectrum, GPS quality, data path rates and jitter, loop "
                "latency, EKF test ratios, fault windows, flight modes, events (docs/report.md)");
  sub->add_option("FILE", o->tlog, "The recording: hitl sim/demo --record, hitl inspect --record, QGroundControl, MAVProxy")
      ->required()->check(CLI::ExistingFile)->type_name("FILE.tlog");
  sub->add_option("-o,--output", o->output, "The page to write (default: FILE with .html for .tlog)")->type_name("FILE.html");
  auto* ulog = sub->add_option("--ulog", o->ulog,
                               "PX4's ULog to merge: its estimate against the truth on the simulator's clock (default: the newest "
                               "FILE.px4/log/**.ulg that hitl sim --px4 left beside the recording)")
                   ->check(CLI::ExistingFile)
                   ->type_name("PX4.ulg");
  sub->add_flag("--no-ulog", o->no_ulog, "Merge no ULog, even one beside the recording")->excludes(ulog);
  auto* static_page = sub->add_flag("--static", o->static_page,
                                    "Write the static page: gnuplot's SVGs and no script (for mail and CI artefacts); default: the "
                                    "interactive page (dygraphs: zoom and pan linked across the time plots)");
  sub->add_option("--dygraphs", o->dygraphs,
                  "Where Debian's libjs-dygraphs is (dygraph.min.js, dygraph.min.css, extras/synchronizer.js), inlined into "
                  "the interactive page; without them the static page is written, said on stderr")
      ->capture_default_str()
      ->type_name("DIR")
      ->excludes(static_page);
  sub->add_option("--plot", o->plots,
                  "One more time plot of MAVLink fields, as MAVExplorer draws them: series separated by commas, each "
                  "MESSAGE.field (an array's element: MESSAGE.field[0]) with + - * / numbers, parentheses and degrees() "
                  "radians() abs() sqrt() ('ATTITUDE.roll,ATTITUDE.pitch', 'GLOBAL_POSITION_INT.relative_alt/1000'); repeatable")
      ->type_name("EXPR,...");
  sub->footer("Prints the page's path on stdout (--json: a summary line with path, bytes, plots, seconds, interactive, static_because, lacks, skipped, ulog). "
              "Needs gnuplot (Debian: gnuplot-nox) and, for the interactive page, libjs-dygraphs.\n"
              "Exit: 0 written, 2 bad input (not a tlog, a --ulog that is no ULog or not of this recording) or gnuplot missing, 1 drawing or writing failed.");
  sub->callback([&options, &state, o]() {
    const std::string out = o->output.empty() ? default_report_path(o->tlog) : o->output;
    report::ReportOptions report_options{o->ulog, !o->no_ulog, o->static_page, o->dygraphs};
    if (o->plots.size() > kMaxFieldPlots) {
      log_error("report", "--plot given " + std::to_string(o->plots.size()) + " times: at most " + std::to_string(kMaxFieldPlots));
      state.exit_code = kExitUsage;
      return;
    }
    const auto messages = mavlink::MessageSet::compiled();
    for (const auto& text : o->plots) {
      auto spec = report::parse_field_plot(text, messages);
      if (!spec) {
        log_error("report", "--plot " + spec.error().message);
        state.exit_code = exit_code(spec.error());
        return;
      }
      report_options.field_plots.push_back(std::move(*spec));
    }
    auto r = write_report_and_say(options, "report", o->tlog, out, report_options);
    if (!r) {
      state.exit_code = exit_code(r.error());
      return;
    }
    if (options.json) {
      auto j = report_json(*r);
      j["type"] = "summary";
      print_json_line(j);
    } else {
      std::cout << r->html_path << std::endl;
    }
    state.exit_code = kExitOk;
  });
}

}  // namespace hitl::cli
