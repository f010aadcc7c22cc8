// `hitl inspect --tui`: the panels inspect can fill. Data paths: one row per message with its
// rate over the last second, jitter (inter-arrival standard deviation) and longest gap, held to
// the --expect rates when given; messages: the STATUSTEXT heard; link: frames, datagrams, parser
// errors and each source's sequence loss. No actions: inspect only listens.
#pragma once

#include <map>
#include <mutex>
#include <optional>
#include <string>

#include "engine/inspect/inspector.h"
#include "engine/mavlink/statustext.h"
#include "tui/dashboard.h"
#include "tui/message_log.h"

namespace hitl::tui {

class InspectDashboard : public DashboardSource, public inspect::Inspector::Observer {
 public:
  /// `where`: the source in words (Inspector::where()); `expected_hz`: --expect, by message name;
  /// `stay_open`: keep showing after the source ended (a .tlog), until q.
  InspectDashboard(std::string where, std::map<std::string, double> expected_hz, bool stay_open);

  // DashboardSource
  DashboardModel collect() override;
  std::optional<std::string> finished() override;
  void note(Severity severity, const std::string& text) override { log_.add_outcome(severity, text); }
  // inspect::Inspector::Observer (the inspector's thread)
  void on_frame(const mavlink::Frame& frame, const std::string& source, int64_t t_unix_ns) override;
  void on_tick(const telemetry::TrafficSummary& summary) override;

  /// The inspector's run ended (`why`: "duration", "end of log", an error).
  void mark_finished(const std::string& why);

 private:
  std::string where_;
  std::map<std::string, double> expected_hz_;
  bool stay_open_;
  MessageLog log_;
  void show(const mavlink::StatusText& text);
  mavlink::StatusTextAssembler statustexts_;  // the inspector's thread only
  std::map<uint8_t, std::string> source_of_sysid_;  // at most 256
  mutable std::mutex mutex_;
  std::optional<telemetry::TrafficSummary> summary_;
  std::optional<std::string> finished_;
};

}  // namespace hitl::tui
