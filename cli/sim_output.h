// How `hitl sim` shows a session: the status line each second (or a JSON status), the events, and
// the summary at the end (text or JSON). Output only: the numbers come from hil::SessionSnapshot.
#pragma once

#include <nlohmann/json.hpp>

#include "cli/common_options.h"
#include "engine/hil/session.h"
#include "engine/hil/snapshot_json.h"

namespace hitl::cli {

/// A fault's start or end as a JSON status object: {"type":"status","fault":{"event":"started",...}}.
nlohmann::json fault_event_json(const faults::FaultChange& change);
using hil::snapshot_json;  // engine/hil/snapshot_json.h: the status lines and the summary
/// "t   12.0 s  rtf 1.00  out HIL_SENSOR 250 GPS 10 ODOM  30 Hz  in ACT 200 Hz  ARMED ..."
std::string status_line(const hil::SessionSnapshot& s);
/// The text summary after the run, ended for `end` ("duration", "stopped", ...).
void print_summary(const hil::SessionSnapshot& s, const char* end);

/// Events to stderr ("hitl sim: warning: ..."), the status line once a second (redrawn in place on
/// a terminal) or its JSON.
class SimPrinter : public hil::Session::Observer {
 public:
  explicit SimPrinter(const GlobalOptions& global);
  void on_event(const hil::SessionEvent& e) override;
  void on_status(const hil::SessionSnapshot& s) override;
  /// Ends a status line drawn in place.
  void end_line();

 private:
  const GlobalOptions& global_;
  bool tty_;
  bool pending_ = false;
};

}  // namespace hitl::cli
