// hitl inspect: decode and measure MAVLink on a port, a connection or a .tlog.
#include <atomic>
#include <iostream>
#include <thread>
#include <map>
#include <memory>
#include <optional>
#include <set>

#include "base/mavlink/enums.h"
#include "cli/commands.h"
#include "cli/inspect_allan.h"
#include "cli/inspect_spectrum.h"
#include "cli/number_check.h"
#include "cli/traffic_table.h"
#include "cli/value_types.h"
#include "engine/inspect/expectations.h"
#include "engine/inspect/frame_text.h"
#include "engine/inspect/inspector.h"
#include "engine/mavlink/field_format.h"
#include "engine/telemetry/traffic_json.h"
#include "tui/dashboard.h"
#include "tui/inspect_dashboard.h"
#include "tui/terminal.h"

namespace hitl::cli {
namespace {

struct InspectOptions {
  std::optional<uint16_t> port;
  std::string connect;
  std::string tlog;
  std::string bind = "0.0.0.0";
  uint16_t local_port = kDirectLocalPort;
  std::string record;
  std::vector<std::string> show;
  bool follow = false;
  double duration_s = 0;
  uint64_t count = 0;
  std::string expect;
  double tolerance_pct = 5.0;
  int sysid = mavlink::kGcsSystemId;
  int compid = mavlink::kCompIdMissionPlanner;
  std::string signing_key;
  bool require_signed = false;
  bool tui = false;  ///< --tui: the dashboard's data paths, messages and link panels (docs/tui.md)
  bool allan = false;  ///< --allan: the IMU's Allan deviation of a --tlog (inspect_allan.h)
  bool spectrum = false;  ///< --spectrum: the IMU's amplitude spectrum of a --tlog (inspect_spectrum.h)
  std::optional<double> from_s;  ///< --from, --to: the window of HIL_SENSOR time read by --allan, --spectrum
  std::optional<double> to_s;
};

nlohmann::json frame_json(const mavlink::Frame& f, const std::string& source, int64_t t_ns) {
  return {{"type", "frame"},
          {"t_unix_us", t_ns / 1000},
          {"source", source},
          {"name", f.desc ? f.desc->name : "#" + std::to_string(f.msgid)},
          {"id", f.msgid},
          {"sysid", f.sysid},
          {"compid", f.compid},
          {"seq", f.seq},
          {"fields", mavlink::fields_to_json(f)}};
}

/// Turns what the inspector reports into text or JSON lines.
class InspectPrinter : public inspect::Inspector::Observer {
 public:
  InspectPrinter(const GlobalOptions& global, const InspectOptions& options, std::vector<uint32_t> show_ids)
      : global_(global), options_(options), show_ids_(std::move(show_ids)), live_table_(stdout_is_tty() && !options.follow) {}

  void on_frame(const mavlink::Frame& frame, const std::string& source, int64_t t_ns) override {
    if (global_.verbosity >= 1) narrate(frame, source);
    if (!shown(frame.msgid)) return;
    if (options_.follow) {
      if (global_.json) print_json_line(frame_json(frame, source, t_ns));
      else std::cout << inspect::frame_text(frame) << '\n';
      return;
    }
    latest_[frame.msgid] = {inspect::frame_text(frame), frame_json(frame, source, t_ns)};
  }

  void on_notice(const std::string& text) override { std::cerr << "hitl inspect: " << text << '\n'; }

  void on_tick(const telemetry::TrafficSummary& summary) override {
    if (global_.json) {
      auto j = telemetry::to_json(summary);
      j["type"] = "status";
      add_latest(j);
      print_json_line(j);
    } else if (global_.quiet) {
      return;
    } else if (live_table_) {
      std::cout << "\x1b[H\x1b[J" << traffic_table(summary) << latest_text() << std::flush;
    } else if (options_.follow) {
      std::cerr << traffic_line(summary) << '\n';
    } else {
      std::cout << traffic_line(summary) << '\n' << std::flush;
    }
  }

  void on_send_error(const std::string& text) override { std::cerr << "hitl inspect: error: " << text << '\n'; }

  void add_latest(nlohmann::json& j) const {
    if (show_ids_.empty() || options_.follow) return;
    nlohmann::json latest = nlohmann::json::object();
    for (const auto& [id, text_and_json] : latest_) latest[text_and_json.second["name"].get<std::string>()] = text_and_json.second;
    j["latest"] = std::move(latest);
  }

  std::string latest_text() const {
    std::string out;
    for (const auto& [id, text_and_json] : latest_) out += text_and_json.first + "\n";
    return out.empty() ? out : "\n" + out;
  }

 private:
  /// -v: say on stderr when a new sender or message id appears; -vv: every frame.
  void narrate(const mavlink::Frame& frame, const std::string& source) {
    const std::string name = frame.desc ? frame.desc->name : "#" + std::to_string(frame.msgid) + " (unknown id)";
    // Bounded like the tables: past the bound, nothing new is narrated.
    if (sources_.size() < telemetry::kMaxSources && sources_.insert(source + "/" + std::to_string(frame.sysid) + "/" + std::to_string(frame.compid)).second)
      std::cerr << "new source " << source << " sysid " << int{frame.sysid} << " compid " << int{frame.compid}
                << (frame.version == mavlink::Version::V1 ? " (MAVLink 1)" : "") << '\n';
    if (ids_.size() < telemetry::kMaxMessageIds && ids_.insert(frame.msgid).second) std::cerr << "new message " << name << " from " << source << '\n';
    if (global_.verbosity >= 2)
      std::cerr << source << " seq " << int{frame.seq} << " " << inspect::frame_text(frame) << '\n';
  }

  bool shown(uint32_t id) const {
    return std::find(show_ids_.begin(), show_ids_.end(), id) != show_ids_.end();
  }

  const GlobalOptions& global_;
  const InspectOptions& options_;
  std::vector<uint32_t> show_ids_;
  bool live_table_;
  std::map<uint32_t, std::pair<std::string, nlohmann::json>> latest_;
  std::set<std::string> sources_;
  std::set<uint32_t> ids_;
};

const char* end_reason_name(inspect::Inspector::EndReason reason) {
  switch (reason) {
    case inspect::Inspector::EndReason::Duration: return "duration";
    case inspect::Inspector::EndReason::Count: return "count";
    case inspect::Inspector::EndReason::EndOfLog: return "end_of_log";
    case inspect::Inspector::EndReason::Stopped: return "stopped";
  }
  return "?";
}

/// Feeds the dashboard and keeps --show's latest values for the final output.
class DashboardTee : public inspect::Inspector::Observer {
 public:
  DashboardTee(tui::InspectDashboard& dashboard, InspectPrinter& printer) : dashboard_(dashboard), printer_(printer) {}
  void on_frame(const mavlink::Frame& frame, const std::string& source, int64_t t_ns) override {
    dashboard_.on_frame(frame, source, t_ns);
    printer_.on_frame(frame, source, t_ns);
  }
  void on_tick(const telemetry::TrafficSummary& summary) override { dashboard_.on_tick(summary); }
  void on_send_error(const std::string& text) override { dashboard_.note(tui::Severity::Error, text); }

 private:
  tui::InspectDashboard& dashboard_;
  InspectPrinter& printer_;
};

/// --tui: the inspector on its own thread, the dashboard on this one; q or a signal ends both.
Expected<inspect::Inspector::EndReason> run_with_dashboard(inspect::Inspector& inspector, InspectPrinter& printer,
                                                           const InspectOptions& opt,
                                                           const std::vector<inspect::Expectation>& expectations) {
  std::map<std::string, double> expected_hz;
  for (const auto& e : expectations) expected_hz[e.name] = e.rate_hz;
  tui::InspectDashboard dashboard(inspector.where(), expected_hz, !opt.tlog.empty());
  DashboardTee tee(dashboard, printer);
  std::atomic<bool> stop{false};
  Expected<inspect::Inspector::EndReason> end = Error::failed("not run");
  std::thread loop([&] {
    end = inspector.run(stop, tee);
    dashboard.mark_finished(end ? std::string(end_reason_name(*end)) : "error: " + end.error().message);
  });
  auto shown = tui::run_dashboard(dashboard, nullptr);
  stop.store(true);
  loop.join();
  if (!shown) log_error("inspect", "--tui: " + shown.error().message);
  return end;
}

int run_inspect(const GlobalOptions& global, const InspectOptions& opt_in) {
  InspectOptions opt = opt_in;
  if (opt.tui && opt.follow) {
    return log_error("inspect", Error::usage("--follow prints every frame as it arrives; it does not go with --tui"));
  }
  if (opt.tui) {
    if (auto usable = tui::terminal_usable(); !usable) {
      std::cerr << "hitl inspect: --tui: " << usable.error().message << "; printing the summary lines instead\n";
      opt.tui = false;
    }
  }
  const std::string cmd = "inspect";
  const int sources = (opt.port ? 1 : 0) + (opt.connect.empty() ? 0 : 1) + (opt.tlog.empty() ? 0 : 1);
  if (sources != 1) {
    return log_error(cmd, Error::usage("give exactly one source: --port P, --connect udp:HOST:PORT or --tlog FILE"));
  }
  if (opt.allan && opt.spectrum) return log_error(cmd, Error::usage("give one of --allan and --spectrum"));
  if ((opt.from_s || opt.to_s) && !opt.allan && !opt.spectrum)
    return log_error(cmd, Error::usage("--from and --to choose the part of the recording --allan or --spectrum reads"));
  if (opt.allan || opt.spectrum) {
    const std::string flag = opt.allan ? "--allan" : "--spectrum";
    if (opt.tlog.empty()) return log_error(cmd, Error::usage(flag + " reads a recording: give --tlog FILE"));
    if (opt.tui || opt.follow || !opt.show.empty() || !opt.expect.empty() || !opt.record.empty() || opt.duration_s > 0 || opt.count > 0)
      return log_error(cmd, Error::usage(flag + " reads the whole --tlog on its own: it does not go with --tui, --follow, --show, "
                                         "--expect, --record, --duration or --count"));
    telemetry::ImuWindow window;
    if (opt.from_s) window.from_s = *opt.from_s;
    if (opt.to_s) window.to_s = *opt.to_s;
    if (window.to_s <= window.from_s) return log_error(cmd, Error::usage("--to must be after --from"));
    if (opt.allan) return run_inspect_allan(global, opt.tlog, window);
    return run_inspect_spectrum(global, opt.tlog, window);
  }
  auto messages = load_messages(global);
  if (!messages) {
    log_error(cmd, messages.error().message);
    return exit_code(messages.error());
  }
  std::vector<uint32_t> show_ids;
  for (const auto& name : opt.show) {
    const auto* desc = messages->lookup(name);
    if (desc == nullptr) {
      return log_error(cmd, Error::input("--show: unknown message '" + name + "' (load its dialect with --dialect FILE.xml)"));
    }
    show_ids.push_back(desc->id);
  }
  std::vector<inspect::Expectation> expectations;
  if (!opt.expect.empty()) {
    auto parsed = inspect::parse_expectations(opt.expect, *messages);
    if (!parsed) {
      log_error(cmd, "--expect: " + parsed.error().message);
      return exit_code(parsed.error());
    }
    expectations = std::move(parsed.value());
  }

  inspect::InspectConfig config;
  if (opt.port) {
    config.source = inspect::InspectConfig::Source::Port;
    config.port = *opt.port;
  } else if (!opt.connect.empty()) {
    config.source = inspect::InspectConfig::Source::Connect;
    config.connect = opt.connect;
  } else {
    config.source = inspect::InspectConfig::Source::Tlog;
    config.tlog_path = opt.tlog;
  }
  config.bind_address = opt.bind;
  config.local_port = opt.local_port;
  config.record_path = opt.record;
  config.duration_s = opt.duration_s;
  config.count = opt.count;
  config.count_ids = show_ids;
  config.sysid = static_cast<uint8_t>(opt.sysid);
  config.compid = static_cast<uint8_t>(opt.compid);
  if (!opt.signing_key.empty()) {
    auto key = mavlink::parse_signing_key(opt.signing_key);
    if (!key) {
      log_error(cmd, "--signing-key: " + key.error().message);
      return exit_code(key.error());
    }
    config.parser.signing_key = *key;
    config.parser.accept_unsigned = !opt.require_signed;
  }

  if (global.verbosity >= 1) log_info(global, "hitl inspect: " + std::to_string(messages->size()) + " message definitions known");
  auto inspector = inspect::Inspector::open(config, *messages);
  if (!inspector) {
    log_error(cmd, inspector.error().message);
    return exit_code(inspector.error());
  }
  const auto& stop = stop_flag_on_signals();
  const char* verb = opt.port ? "listening on " : (opt.connect.empty() ? "reading " : "sending HEARTBEATs to, and listening for, ");
  log_info(global, "hitl inspect: " + std::string(verb) + (*inspector)->where() +
                       (opt.record.empty() ? "" : ", recording to " + opt.record) + (opt.tui ? "" : " (Ctrl-C for the summary)"));

  GlobalOptions printer_options = global;
  if (opt.tui) printer_options.verbosity = 0;  // nothing may write over the dashboard
  InspectPrinter printer(printer_options, opt, show_ids);
  auto end = opt.tui ? run_with_dashboard(**inspector, printer, opt, expectations) : (*inspector)->run(stop, printer);
  if (!end) {
    log_error(cmd, end.error().message);
    return exit_code(end.error());
  }
  const auto summary = (*inspector)->summary();
  const auto results = inspect::check_expectations(summary, expectations, opt.tolerance_pct);
  bool ok = true;
  for (const auto& r : results) ok = ok && r.ok;
  // --connect to a partner no datagram could reach: say so rather than a table of nothing.
  const uint64_t send_errors = (*inspector)->send_errors();
  if (!opt.connect.empty() && send_errors > 0 && summary.frames == 0) {
    log_error(cmd, "--connect " + opt.connect + ": every HEARTBEAT failed to send (" + std::to_string(send_errors) +
                       "); nothing was received");
    ok = false;
  }
  if ((*inspector)->record_failed()) {
    log_error(cmd, "--record: " + (*inspector)->record_error() + "; the recording is incomplete");
    ok = false;
  }

  if (global.json) {
    auto j = telemetry::to_json(summary);
    j["type"] = "summary";
    j["end"] = end_reason_name(*end);
    if (!opt.connect.empty()) j["send_errors"] = send_errors;
    printer.add_latest(j);
    if (!expectations.empty()) {
      nlohmann::json arr = nlohmann::json::array();
      for (const auto& r : results)
        arr.push_back({{"name", r.expected.name},
                       {"expected_hz", r.expected.rate_hz},
                       {"measured_hz", r.measured_hz},
                       {"low_hz", r.low_hz},
                       {"high_hz", r.high_hz},
                       {"ok", r.ok}});
      j["expect"] = std::move(arr);
    }
    j["ok"] = ok;
    print_json_line(j);
  } else {
    std::cout << (stdout_is_tty() && !opt.follow ? "\x1b[H\x1b[J" : "\n") << traffic_table(summary)
              << printer.latest_text();
    if (send_errors > 0) std::cout << "send errors " << send_errors << " (HEARTBEATs to " << opt.connect << " the kernel refused)\n";
    for (const auto& r : results) std::cout << (r.ok ? "PASS " : "FAIL ") << r.verdict << '\n';
    std::cout << std::flush;
  }
  return ok ? kExitOk : kExitFailed;
}

}  // namespace

void add_inspect_command(CLI::App& app, GlobalOptions& options, RunState& state) {
  auto opt = std::make_shared<InspectOptions>();
  auto* sub = app.add_subcommand("inspect", "Decode and measure MAVLink on a UDP port, a connection or a .tlog");
  sub->footer(
      "Examples:\n"
      "  hitl inspect --port 14570 --duration 5 --expect ODOMETRY=250   # the spec's Phase 1 check\n"
      "  hitl inspect --connect udp:192.168.101.2:14558 --show HEARTBEAT,ATTITUDE\n"
      "  hitl inspect --tlog flight.tlog --json\n"
      "  hitl inspect --tlog rest.tlog --allan           # the IMU's noise density and bias instability\n"
      "  hitl inspect --tlog hover.tlog --spectrum --from 10 --to 20   # the IMU's vibration lines in a hover\n"
      "Exit: 0 ok (every --expect met), 1 an expectation failed, 2 bad usage or the source cannot be opened.");
  auto* src = sub->add_option_group("Source", "exactly one of --port, --connect, --tlog");
  src->add_option("--port", opt->port, "Listen passively on this UDP port (e.g. 14570 for ODOMETRY)")
      ->check(number_in(1, 65535));
  src->add_option("--connect", opt->connect,
                  "Talk to a MAVLink instance at udp:HOST:PORT (or HOST:PORT), sending HEARTBEAT at 1 Hz so it streams to us")
      ->type_name("udp:HOST:PORT");
  src->add_option("--tlog", opt->tlog, "Read a telemetry log offline, as fast as it reads")
      ->check(CLI::ExistingFile)
      ->type_name("FILE.tlog");
  src->require_option(1);
  sub->add_option("--bind", opt->bind, "Address to listen on with --port")->capture_default_str()->group("Connection");
  sub->add_option("--local-port", opt->local_port,
                  "Local UDP port for --connect; fixed, since PX4 answers only the first port it heard")
      ->capture_default_str()
      ->group("Connection");
  sub->add_option("--record", opt->record, "Save every frame received to a .tlog")->type_name("FILE.tlog");
  sub->add_option("--show", opt->show, "Print decoded fields of these messages, enums by name, a line each (latest, or each with --follow)")
      ->delimiter(',')
      ->type_name(value_type::kMessageList);
  sub->add_flag("--follow", opt->follow, "With --show: print every matching message as it arrives");
  sub->add_flag("--tui", opt->tui,
                "The live dashboard (docs/tui.md): a row per message (rate against --expect, jitter, max gap), "
                "STATUSTEXT, per-source loss; q quits. Without a terminal: the summary lines");
  sub->add_flag("--allan", opt->allan,
                "With --tlog of a vehicle at rest: the overlapping Allan deviation of its IMU (HIL_SENSOR gyro and accel, "
                "per axis), each curve's noise_density and bias_instability (docs/inspect.md)");
  sub->add_flag("--spectrum", opt->spectrum,
                "With --tlog: the amplitude spectrum of its IMU (HIL_SENSOR gyro and accel, per axis; Welch, Hann, 1 s "
                "segments, 50 % overlap) and its strongest peaks: the rotors' vibration lines (docs/inspect.md)");
  sub->add_option("--from", opt->from_s, "With --allan or --spectrum: read the IMU from this simulated time (HIL_SENSOR time_usec)")
      ->check(non_negative_number())
      ->type_name("S");
  sub->add_option("--to", opt->to_s, "With --allan or --spectrum: read the IMU up to this simulated time (HIL_SENSOR time_usec)")
      ->check(non_negative_number())
      ->type_name("S");
  sub->add_option("--duration", opt->duration_s, "Stop after this many seconds (tlog: of log time)")
      ->check(positive_number())
      ->type_name("S");
  sub->add_option("--count", opt->count, "Stop after N messages (of the --show names when given)")
      ->check(positive_number())
      ->type_name("N");
  sub->add_option("--expect", opt->expect, "Rates the link must carry; exit 1 when one falls outside the tolerance")
      ->type_name(value_type::kMessageRateList);
  sub->add_option("--tolerance", opt->tolerance_pct, "Accepted deviation from each --expect rate, percent")
      ->capture_default_str()
      ->check(number_in(0.0, 100.0))
      ->type_name("PCT");
  sub->add_option("--sysid", opt->sysid, "System id of our HEARTBEAT with --connect")
      ->capture_default_str()
      ->check(number_in(1, 255))
      ->group("Identity");
  sub->add_option("--compid", opt->compid, "Component id of our HEARTBEAT with --connect")
      ->capture_default_str()
      ->check(number_in(1, 255))
      ->group("Identity");
  sub->add_option("--signing-key", opt->signing_key,
                  "Verify MAVLink 2 signatures with this key (64 hex digits, or a passphrase hashed with SHA-256)")
      ->group("Signing");
  sub->add_flag("--require-signed", opt->require_signed, "With --signing-key: reject unsigned frames")
      ->group("Signing");
  sub->callback([&options, &state, opt]() { state.exit_code = run_inspect(options, *opt); });
}

}  // namespace hitl::cli
