#include "tui/bridge_dashboard.h"

#include "tui/draw.h"

namespace hitl::tui {
namespace {

/// Packets per second between two reports of the same link (0 before the second report).
double per_second(uint64_t now, uint64_t before, double dt_s) {
  return dt_s > 0 && now >= before ? static_cast<double>(now - before) / dt_s : 0.0;
}

const bridge::LinkHealth* find_link(const std::optional<bridge::BridgeHealth>& h, const std::string& name) {
  if (!h) return nullptr;
  for (const auto& l : h->links)
    if (l.name == name) return &l;
  return nullptr;
}

std::string optional_text(const std::optional<double>& v, const char* format_text) {
  return v ? format(format_text, *v) : "-";
}

}  // namespace

PathsPanel bridge_paths(const bridge::BridgeHealth& now, const std::optional<bridge::BridgeHealth>& before) {
  PathsPanel panel;
  panel.caption = "packets per second per link; loss: sequence gaps of the board's frames";
  const double dt_s = before ? now.uptime_s - before->uptime_s : 0.0;
  uint64_t received = 0, lost = 0;
  for (const auto& [source, l] : now.loss) {
    received += l.received;
    lost += l.lost;
  }
  for (const auto& link : now.links) {
    const bridge::LinkHealth* old = find_link(before, link.name);
    const bool board = &link == &now.links.front();
    Health health = Health::Good;
    std::string note;
    if (board && now.board_state == "gone") {
      health = Health::Bad;
      note = "gone";
    } else if (board && now.board_state == "waiting") {
      health = Health::Degraded;
      note = "wait";
    } else if (!link.connected) {
      health = Health::Bad;
      note = "down";
    }
    PathRow in;
    in.name = "rx " + link.name;
    in.message = "from " + (link.partner.empty() ? link.name : link.partner);
    in.outgoing = false;
    in.rate_hz = old ? per_second(link.packets_in, old->packets_in, dt_s) : 0.0;
    in.count = link.packets_in;
    in.health = health;
    in.note = note;
    if (board && received + lost > 0) in.loss_pct = 100.0 * static_cast<double>(lost) / static_cast<double>(received + lost);
    PathRow out = in;
    out.name = "tx " + link.name;
    out.message = "to " + (link.partner.empty() ? link.name : link.partner);
    out.outgoing = true;
    out.rate_hz = old ? per_second(link.packets_out, old->packets_out, dt_s) : 0.0;
    out.count = link.packets_out;
    out.loss_pct.reset();
    panel.rows.push_back(std::move(in));
    panel.rows.push_back(std::move(out));
  }
  return panel;
}

BridgeDashboard::BridgeDashboard(const bridge::BridgeConfig& config)
    : board_reachable_(config.clients_port != 0),
      board_(config.clients_port, std::nullopt, config.dsp_hitl_rates, log_) {
  log_.add(Severity::Info, "hitl bridge --tui: ? for the keys");
}

void BridgeDashboard::on_event(const std::string& text, Severity severity) {
  log_.add(severity, text);
}

void BridgeDashboard::on_health(const bridge::BridgeHealth& health) {
  std::lock_guard<std::mutex> lock(mutex_);
  previous_ = std::move(health_);
  health_ = health;
}

void BridgeDashboard::mark_finished(const std::string& why) {
  std::lock_guard<std::mutex> lock(mutex_);
  finished_ = why;
}

std::optional<std::string> BridgeDashboard::finished() {
  std::lock_guard<std::mutex> lock(mutex_);
  return finished_;
}

std::optional<std::string> BridgeDashboard::refusal(Action action) const {
  switch (action) {
    case Action::TogglePause:
    case Action::ResetHome:
    case Action::FlyTrajectory:
    case Action::StopTrajectory:
    case Action::Fault:
      return "hitl bridge runs no simulator (pause, reset, trajectories and faults belong to hitl sim --tui)";
    default: return board_.refusal(action);
  }
}

void BridgeDashboard::perform(Action action, const std::string& argument) {
  if (auto why = refusal(action)) {
    log_.add_outcome(Severity::Warning, std::string(to_string(action)) + ": " + *why);
    return;
  }
  board_.perform(action, argument);
}

DashboardModel BridgeDashboard::collect() {
  std::optional<bridge::BridgeHealth> h, before;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    h = health_;
    before = previous_;
  }
  DashboardModel m;
  m.title = "hitl bridge";
  m.keys = board_reachable_ ? "adtls" : "";  // no simulator: no pause, reset or trajectory
  board_.fill(m, 1.0);  // the board runs on its own clock: real time
  if (m.ekf && !m.ekf->unavailable) m.ekf->error_note = "no ground truth: hitl bridge runs no simulator";
  m.messages = log_.lines();
  m.outcome = log_.outcome();
  if (!h) {
    m.state = "starting";
    m.state_health = Health::Degraded;
    return m;
  }
  m.state = "board " + h->board_state;
  m.state_health = h->board_state == "up" ? Health::Good : h->board_state == "gone" ? Health::Bad : Health::Degraded;
  m.clock = format("up %.0f s", h->uptime_s);
  m.paths = bridge_paths(*h, before);

  const auto& board = h->links.front();
  m.link_partner = board.partner.empty() ? "board: waiting" : "board " + board.partner;
  m.link_health = m.state_health;
  const auto age_health = !h->heartbeat_age_s ? Health::Degraded
                          : *h->heartbeat_age_s > bridge::kBoardGoneAfter_s ? Health::Bad
                                                                            : Health::Good;
  auto count = [](uint64_t n) { return std::to_string(n); };
  m.link = {
      {"board", h->board_state, m.state_health},
      {"heartbeat", optional_text(h->heartbeat_age_s, "%.1f s ago"), age_health},
      {"rtt", optional_text(h->rtt_ms, "%.2f ms"), h->rtt_ms ? Health::Good : Health::Degraded},
      {"clients", count(h->clients)},
      {"in", count(board.packets_in) + " pkt"},
      {"out", count(board.packets_out) + " pkt"},
      {"send err", count(board.send_errors), board.send_errors ? Health::Bad : Health::Good},
      {"dups", count(h->duplicates), h->duplicates ? Health::Degraded : Health::Good},
      {"rx drops", count(h->kernel_rx_drops), h->kernel_rx_drops ? Health::Degraded : Health::Good},
      {"links", count(h->links.size())},
  };
  for (const auto& l : h->links)  // what was taken in and lost towards the clients and endpoints, counted where it happened
    if (l.name != "board" && l.dropped + l.send_errors > 0)
      m.link.push_back({l.name == "clients" ? std::string("client drops") : "drops " + l.name, count(l.dropped + l.send_errors),
                        l.lossless || l.send_errors > 0 ? Health::Bad : Health::Degraded});
  for (const auto& [source, l] : h->loss)
    m.link.push_back({"loss " + source, format("%.1f %%", l.loss_pct), l.loss_pct > 0 ? Health::Degraded : Health::Good});
  return m;
}

}  // namespace hitl::tui
