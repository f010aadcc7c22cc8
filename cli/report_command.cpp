// hitl report FILE.tlog [-o report.html]: a recording to one self-contained HTML page (docs/report.md).
#include <cstdio>
#include <iostream>
#include <memory>

#include "cli/commands.h"
#include "cli/report_output.h"
#include "engine/report/report.h"

namespace hitl::cli {

std::string default_report_path(const std::string& tlog_path) {
  const std::string ext = ".tlog";
  if (tlog_path.size() > ext.size() && tlog_path.compare(tlog_path.size() - ext.size(), ext.size(), ext) == 0)
    return tlog_path.substr(0, tlog_path.size() - ext.size()) + ".html";
  return tlog_path + ".html";
}

Expected<report::ReportResult> write_report_and_say(const GlobalOptions& g, const std::string& command,
                                                    const std::string& tlog_path, const std::string& html_path) {
  auto r = report::write_report(tlog_path, html_path);
  if (!r) {
    log_error(command, (command == "report" ? "" : "--report: ") + r.error().message);
    return r.error();
  }
  if (!g.json && !g.quiet) {
    char line[160];
    std::snprintf(line, sizeof line, "hitl %s: report of %s: %zu plots, %.0f KiB in %.1f s%s", command.c_str(), tlog_path.c_str(),
                  r->plots, static_cast<double>(r->bytes) / 1024.0, r->seconds, r->missing.empty() ? "" : "; the log lacks:");
    std::cerr << line << '\n';
    for (const auto& m : r->missing) std::cerr << "  " << m << '\n';
    if (!r->skipped.empty()) std::cerr << "hitl " << command << ": not drawn from the damaged log:\n";
    for (const auto& m : r->skipped) std::cerr << "  " << m << '\n';
  }
  return r;
}

nlohmann::json report_json(const report::ReportResult& r) {
  return {{"path", r.html_path}, {"bytes", r.bytes}, {"plots", r.plots}, {"seconds", r.seconds}, {"lacks", r.missing}, {"skipped", r.skipped}};
}

void add_report_command(CLI::App& app, GlobalOptions& options, RunState& state) {
  struct ReportOptions {
    std::string tlog;
    std::string output;
  };
  auto o = std::make_shared<ReportOptions>();
  auto* sub = app.add_subcommand(
      "report", "Draw a recording (.tlog) as one self-contained HTML page: flight path, altitude, tracking error, attitude, "
                "motors, data path rates and jitter, EKF test ratios, events (docs/report.md)");
  sub->add_option("FILE", o->tlog, "The recording: hitl sim/demo --record, hitl inspect --record, QGroundControl, MAVProxy")
      ->required()->check(CLI::ExistingFile)->type_name("FILE.tlog");
  sub->add_option("-o,--output", o->output, "The page to write (default: FILE with .html for .tlog)")->type_name("FILE.html");
  sub->footer("Prints the page's path on stdout (--json: a summary line with path, bytes, plots, seconds, lacks). Needs gnuplot (Debian: gnuplot-nox).\n"
              "Exit: 0 written, 2 bad input (not a tlog) or gnuplot missing, 1 drawing or writing failed.");
  sub->callback([&options, &state, o]() {
    const std::string out = o->output.empty() ? default_report_path(o->tlog) : o->output;
    auto r = write_report_and_say(options, "report", o->tlog, out);
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
