// `hitl bridge --tui`: the bridge's link health each second (partner, packets each way per link,
// per-source loss, TIMESYNC round trip, HEARTBEAT age) as the data-path and link panels, plus the
// board panels and keys through the bridge's own client port (BoardClients), as `hitl arm` from
// another terminal would. No simulator: pause, reset and fly are refused with the reason, and the
// EKF panel has no ground truth to score the estimate against.
#pragma once

#include <mutex>
#include <optional>
#include <string>

#include "engine/bridge/bridge.h"
#include "tui/board_clients.h"
#include "tui/dashboard.h"
#include "tui/message_log.h"

namespace hitl::tui {

class BridgeDashboard : public DashboardSource, public DashboardActions, public bridge::BridgeObserver {
 public:
  /// The board panels reach the board through `config.clients_port` (0: they say why not).
  explicit BridgeDashboard(const bridge::BridgeConfig& config);

  // DashboardSource
  DashboardModel collect() override;
  std::optional<std::string> finished() override;
  void note(Severity severity, const std::string& text) override { log_.add_outcome(severity, text); }
  // DashboardActions
  std::optional<std::string> refusal(Action action) const override;
  void perform(Action action, const std::string& argument) override;
  // bridge::BridgeObserver (the bridge's thread)
  void on_event(const std::string& text, Severity severity) override;
  void on_health(const bridge::BridgeHealth& health) override;

  /// The bridge ended: the dashboard closes with `why`.
  void mark_finished(const std::string& why);
  /// Stops the client threads (before the bridge's sockets close).
  void shutdown() { board_.stop(); }

 private:
  MessageLog log_;
  bool board_reachable_;  ///< a client port to reach the board through (not --clients 0)
  BoardClients board_;
  mutable std::mutex mutex_;
  std::optional<bridge::BridgeHealth> health_, previous_;
  std::optional<std::string> finished_;
};

/// The bridge's health as data-path rows: per link, packets per second to it and from it (rates
/// from the two latest reports), the board's loss from sequence gaps, and the link's state.
PathsPanel bridge_paths(const bridge::BridgeHealth& now, const std::optional<bridge::BridgeHealth>& before);

}  // namespace hitl::tui
