// hitl bridge: the board link without the simulator (engine/bridge), with link health each second;
// --tui shows it in the dashboard, --adb reaches the board's GCS instance through adb.
#include <cstdio>
#include <iostream>
#include <thread>

#include "cli/adb_options.h"
#include "cli/commands.h"
#include "cli/number_check.h"
#include "engine/bridge/bridge.h"
#include "tui/bridge_dashboard.h"
#include "tui/draw.h"
#include "tui/terminal.h"

namespace hitl::cli {
namespace {

struct BridgeOptions {
  bridge::BridgeConfig config;
  std::vector<std::string> endpoints;
  double dedup_ms = 100;
  bool tui = false;
  AdbOptions adb;
};

std::string kilobytes(uint64_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f kB", static_cast<double>(bytes) / 1000.0);
  return text;
}

nlohmann::json to_json(const bridge::BridgeHealth& h) {
  nlohmann::json j = {{"type", "status"}, {"uptime_s", h.uptime_s}, {"board", h.board_state},
                      {"heartbeat_age_s", h.heartbeat_age_s ? nlohmann::json(*h.heartbeat_age_s) : nlohmann::json(nullptr)},
                      {"rtt_ms", h.rtt_ms ? nlohmann::json(*h.rtt_ms) : nlohmann::json(nullptr)},
                      {"clients", h.clients}, {"duplicates", h.duplicates},
                      {"ignored_other_address", h.ignored_other_address}, {"untracked_frames", h.untracked_frames},
                      {"kernel_rx_drops", h.kernel_rx_drops}, {"board_receive_buffer_bytes", h.board_receive_buffer_bytes}};
  nlohmann::json loss = nlohmann::json::object();
  for (const auto& [source, l] : h.loss) loss[source] = {{"received", l.received}, {"lost", l.lost}, {"loss_pct", l.loss_pct}};
  j["loss"] = loss;
  nlohmann::json links = nlohmann::json::array();
  for (const auto& l : h.links) {
    links.push_back({{"name", l.name}, {"partner", l.partner}, {"connected", l.connected}, {"packets_in", l.packets_in},
                     {"bytes_in", l.bytes_in}, {"packets_out", l.packets_out}, {"bytes_out", l.bytes_out},
                     {"duplicates_in", l.duplicates_in}, {"send_errors", l.send_errors}, {"dropped", l.dropped},
                     {"deliveries", l.deliveries}, {"send_buffer_full", l.send_buffer_full}, {"kernel_rx_drops", l.kernel_rx_drops},
                     {"lossless", l.lossless}, {"dropped_by_message", l.dropped_by_message}});
  }
  j["links"] = links;
  return j;
}

std::string to_line(const bridge::BridgeHealth& h) {
  const auto& board = h.links.front();
  char text[400];
  int n = std::snprintf(text, sizeof text, "board %s %-7s in %llu pkt %s  out %llu pkt %s", board.partner.c_str(),
                        h.board_state.c_str(), static_cast<unsigned long long>(board.packets_in), kilobytes(board.bytes_in).c_str(),
                        static_cast<unsigned long long>(board.packets_out), kilobytes(board.bytes_out).c_str());
  std::string line(text, static_cast<std::size_t>(std::max(n, 0)));
  if (board.send_errors > 0) line += "  SEND ERRORS " + std::to_string(board.send_errors);
  if (h.heartbeat_age_s) {
    std::snprintf(text, sizeof text, "  heartbeat %.1f s ago", *h.heartbeat_age_s);
    line += text;
  }
  if (h.rtt_ms) {
    std::snprintf(text, sizeof text, "  rtt %.2f ms", *h.rtt_ms);
    line += text;
  }
  for (const auto& [source, l] : h.loss) {
    std::snprintf(text, sizeof text, "  loss %s %.1f %%", source.c_str(), l.loss_pct);
    line += text;
  }
  line += "  clients " + std::to_string(h.clients);
  for (std::size_t i = 1; i < h.links.size(); ++i) {
    const auto& l = h.links[i];
    if (l.name == "clients") continue;
    line += "  " + l.name + (l.connected ? " " : " (down) ") + std::to_string(l.packets_in) + "/" + std::to_string(l.packets_out) + " pkt";
  }
  if (h.duplicates) line += "  duplicates dropped " + std::to_string(h.duplicates);
  if (h.ignored_other_address) line += "  ignored (not the board) " + std::to_string(h.ignored_other_address);
  if (h.kernel_rx_drops) line += "  kernel rx drops " + std::to_string(h.kernel_rx_drops);
  for (const auto& l : h.links) {
    if (l.name == "board") continue;
    // The clients' queue drops its oldest; an endpoint, the frame that found its send buffer full.
    const bool clients = l.name == "clients";
    if (l.dropped) line += "  " + l.name + " dropped " + std::to_string(l.dropped) + (clients ? " (oldest first)" : "");
    if (l.send_errors) line += "  " + l.name + " send errors " + std::to_string(l.send_errors);
  }
  return line;
}

class Printer : public bridge::BridgeObserver {
 public:
  explicit Printer(const GlobalOptions& g) : g_(g) {}
  void on_event(const std::string& text, Severity severity) override {
    if (g_.quiet && severity == Severity::Info) return;
    std::cerr << "hitl bridge: " << text << std::endl;
  }
  void on_health(const bridge::BridgeHealth& h) override {
    last_ = h;
    if (g_.json) print_json_line(to_json(h));
    else if (!g_.quiet) std::cout << to_line(h) << std::endl;
  }
  /// The last health report (the summary's figures), if any came.
  const std::optional<bridge::BridgeHealth>& last() const { return last_; }

 private:
  const GlobalOptions& g_;
  std::optional<bridge::BridgeHealth> last_;
};

/// The bridge on its own thread, the dashboard on this one; q, a signal or the bridge ending close it.
Status run_with_dashboard(const GlobalOptions& g, const bridge::BridgeConfig& config) {
  tui::BridgeDashboard dashboard(config);
  std::atomic<bool> stop{false};
  Status ran = Ok{};
  std::thread loop([&] {
    ran = bridge::run_bridge(config, dashboard, stop, nullptr);
    dashboard.mark_finished(ran ? std::string("the bridge ended") : "error: " + ran.error().message);
  });
  auto shown = tui::run_dashboard(dashboard, &dashboard);
  dashboard.shutdown();
  stop.store(true);
  loop.join();
  if (!shown) return shown.error().prefixed("--tui: ");
  if (shown->reason == tui::DashboardEnd::Reason::Signal) std::cerr << "hitl bridge: stopped by " << shown->detail << '\n';
  if (g.verbosity >= 1)
    log_info(g, tui::format("hitl bridge: the dashboard drew %llu frames, %.2f ms each on average, %.2f ms at most",
                            static_cast<unsigned long long>(shown->frames), shown->render_ms_mean, shown->render_ms_max));
  return ran;
}

int run(const GlobalOptions& g, BridgeOptions& o) {
  for (const auto& text : o.endpoints) {
    auto spec = net::parse_link_spec(text, {.lossless = true});
    if (!spec) {
      log_error("bridge", "--endpoint " + spec.error().message);
      return exit_code(spec.error());
    }
    o.config.endpoints.push_back(*spec);
  }
  o.config.dedup_window_s = o.dedup_ms / 1000.0;
  if (o.tui) {
    if (auto usable = tui::terminal_usable(); !usable) {
      std::cerr << "hitl bridge: --tui: " << usable.error().message << "; showing the health lines instead\n";
      o.tui = false;
    }
  }
  // --adb: the board's GCS instance is the tunnel's local endpoint (docs/adb.md).
  std::unique_ptr<net::AdbTunnel> tunnel;
  if (o.adb.enabled()) {
    auto opened = open_adb_tunnel(g, "bridge", o.adb);
    if (!opened) {
      log_error("bridge", "--adb: " + opened.error().message);
      return exit_code(opened.error());
    }
    tunnel = std::move(opened.value());
    log_info(g, "hitl bridge: " + tunnel->describe());
    o.config.board_ip = "127.0.0.1";
    o.config.board_port = tunnel->local_endpoint(adb::Channel::Gcs).port();
  }
  Status st = Ok{};
  Printer printer(g);
  bool signalled = o.tui;  // the dashboard ends on q or a signal, never by --duration alone
  if (o.tui) {
    st = run_with_dashboard(g, o.config);
  } else {
    const auto& stop = stop_flag_on_signals();
    st = bridge::run_bridge(o.config, printer, stop, nullptr);
    signalled = stop.load();
  }
  if (g.json) {
    // Exactly one summary, last: the last health report's figures, how it ended, the adb tunnel.
    nlohmann::json j = printer.last() ? to_json(*printer.last()) : nlohmann::json::object();
    j["type"] = "summary";
    j["end"] = !st ? "error" : (signalled || o.config.duration_s <= 0) ? "stopped" : "duration";
    if (!st) j["error"] = st.error().message;
    if (tunnel) j["adb"] = adb_tunnel_json(*tunnel);
    print_json_line(j);
  } else if (tunnel && !g.quiet) {
    std::printf("%s\n", adb_tunnel_line(*tunnel).c_str());
  }
  if (!st) {
    log_error("bridge", st.error().message);
    return exit_code(st.error());  // a port in use or a bad address: 2, as in every command
  }
  return kExitOk;
}

}  // namespace

void add_bridge_command(CLI::App& app, GlobalOptions& options, RunState& state) {
  auto o = std::make_shared<BridgeOptions>();
  auto& c = o->config;
  auto* sub = app.add_subcommand(
      "bridge",
      "The board link without the simulator: route MAVLink between the board's GCS instance, local clients "
      "(127.0.0.1:14600) and --endpoint links, like mavlink-router; link health every second");
  sub->add_option("-i,--target-ip", c.board_ip, "The board's IP (a VOXL2 on USB-Ethernet: 192.168.101.2)")->capture_default_str();
  sub->add_option("--port", c.board_port, "The board's GCS MAVLink instance")->capture_default_str()->check(number_in(1, 65535));
  sub->add_option("--local-port", c.local_port,
                  "Local port towards the board: fixed, since PX4 answers only the first port it heard")
      ->capture_default_str()->check(number_in(1, 65535));
  sub->add_option("--clients", c.clients_port, "UDP port on 127.0.0.1 for local clients (other hitl commands); 0: none")
      ->capture_default_str()->check(number_in(0, 65535));
  sub->add_option("--endpoint", o->endpoints,
                  "More links, as mavlink-router's: udp:HOST:PORT (QGroundControl: udp:127.0.0.1:14550), udpin:[HOST:]PORT, "
                  "tcp:HOST:PORT (reconnects every 2 s), tcpin:[HOST:]PORT (ground station tools connect, up to 16, "
                  "as to mavlink-router's TCP port 5760); a udp: or udpin: one may end in ?lossless (never dropped to: "
                  "a recorder); repeatable")
      ->type_name("KIND:ADDRESS");
  sub->add_option("--queue-ms", c.queue_ms,
                  "Fresh under overload: the clients' queue holds this many ms of their sending time; beyond it the "
                  "oldest frames are dropped (counted by link and message). An --endpoint ending in ?lossless "
                  "(udp:HOST:PORT?lossless, a recorder) gets every frame taken in")
      ->capture_default_str()->check(number_in(0.1, 10000.0));
  sub->add_option("--dedup", o->dedup_ms, "Drop a frame seen again within this many ms (arriving on two paths); 0: off")
      ->capture_default_str()->check(non_negative_number());
  sub->add_option("--duration", c.duration_s, "Seconds to run (0: until Ctrl-C)")->capture_default_str()->check(non_negative_number());
  sub->add_flag("--tui", o->tui,
                "The live dashboard (docs/tui.md): each link's packet rates, loss, rtt, HEARTBEAT age; the board's "
                "vehicle, EKF and dsp_hitl panels; keys a arm, d disarm, t takeoff, l land, s shell, ? help, q quit. "
                "Without a terminal: the health lines")
      ->group("Dashboard");
  add_adb_options(*sub, o->adb, "adb");
  for (const char* adb_name : {"--adb", "--adb-serial"})
    for (const char* other : {"--target-ip", "--port"}) sub->get_option(adb_name)->excludes(sub->get_option(other));
  sub->footer(
      "Health each second on stdout (--json: one object per line). The board going away and coming back is said\n"
      "on stderr within 2 s; clients keep their sockets and traffic resumes by itself.\n"
      "Examples:\n"
      "  hitl bridge -i 192.168.101.2 --endpoint udp:127.0.0.1:14550   # board + QGroundControl\n"
      "  hitl bridge --endpoint tcpin:5760                              # GCS tools connect to TCP 5760\n"
      "  hitl bridge & hitl arm && hitl fly takeoff                     # commands go through the bridge\n"
      "  hitl bridge --adb --tui                                        # board over USB through adb, dashboard");
  sub->callback([&options, &state, o]() { state.exit_code = run(options, *o); });
}

}  // namespace hitl::cli
