// One campaign flight, in this process: the flight stack started on ports the OS picks (it keeps
// its sockets), a lockstep session flying the flight's trajectory with its faults and seed as fast
// as the stack answers, then the summary judged against the criteria and written to the flight's
// folder (summary.json, result.json, flight.tlog, report.html when the campaign asks for it).
// `hitl campaign run FILE --only INDEX` is this; the runner (campaign_run.h) starts it as a child.
#pragma once

#include <atomic>
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "base/common/expected.h"
#include "engine/campaign/criteria.h"
#include "engine/campaign/flight.h"
#include "engine/campaign/flight_summary.h"
#include "engine/hil/session.h"

namespace hitl::campaign {

/// The flight stack a flight flies against, started for one flight and stopped after it.
class FlightStack {
 public:
  /// Where the stack listens (bound, and kept bound by the stack: no port is probed and let go).
  struct Ports {
    uint16_t hil_port = 0;
    uint16_t vio_port = 0;  ///< 0: no VIO listener
  };
  virtual ~FlightStack() = default;
  /// Opens its sockets on the OS's ports and starts running.
  virtual Expected<Ports> start() = 0;
  /// What the session needs of the stack beyond the ports (PX4: the build the session starts and
  /// stops, as hitl sim --px4 DIR); after the flight's own settings.
  virtual void configure(hil::SessionConfig& config) const { (void)config; }
  /// Stops it; figures() stays readable.
  virtual void stop() = 0;
  /// What the stack said and counted by the flight's end; `session`: the session's last snapshot.
  virtual StackFigures figures(const hil::SessionSnapshot& session) const = 0;
};

/// PX4 SITL as a flight's stack (stack = "px4"): nothing runs before the session, which starts PX4
/// on a free instance, in the flight's folder (flight.px4/, its console flight.px4.log, its ULog in
/// flight.px4/log/), in lockstep at the flight's speed, and stops it at the end (engine/hil/px4_launch.h).
/// The campaign's build must have been found (find_campaign_px4).
class Px4FlightStack : public FlightStack {
 public:
  explicit Px4FlightStack(const Campaign& campaign) : campaign_(campaign) {}
  Expected<Ports> start() override { return Ports{}; }
  void configure(hil::SessionConfig& config) const override;
  void stop() override {}
  /// PX4's armed, mode and landed state from its GCS instance; the simulator link's counts.
  StackFigures figures(const hil::SessionSnapshot& session) const override;

  /// PX4 must connect to its simulator port within this (hitl sim's --px4-timeout default).
  static constexpr double kConnectTimeout_s = 30;

 private:
  const Campaign& campaign_;
};

/// The campaign judges what only the recording holds (expectations, a criterion on
/// ekf_test_ratios.*): each flight reads its .tlog back and its summary has "ekf_test_ratios" and
/// "events"; otherwise it does not, and they are absent.
bool reads_recording(const Campaign& campaign);

/// A flight's folder inside the results: flights/<id>/.
std::string flight_folder(const std::string& out_dir, const Flight& flight);
inline constexpr const char* kSummaryFile = "summary.json";
inline constexpr const char* kResultFile = "result.json";
inline constexpr const char* kRecordingFile = "flight.tlog";
inline constexpr const char* kReportFile = "report.html";
inline constexpr const char* kLogFile = "log.txt";
/// stack = "px4": PX4's working folder (its ULogs in log/) and its console, beside the recording.
inline constexpr const char* kPx4WorkFolder = "flight.px4";
inline constexpr const char* kPx4ConsoleFile = "flight.px4.log";

/// How one flight came out: what result.json holds.
struct FlightResult {
  std::size_t index = 0;
  std::string id;
  std::string name;
  /// "passed", "failed" (a criterion broken), "error" (it crashed, hung, or could not start)
  std::string outcome;
  std::string reason;       ///< error: why (the runner's words: "killed by signal 9 (SIGKILL)")
  std::vector<Verdict> verdicts;
  std::string summary_line;
  double wall_s = 0;          ///< the flight in its process: stack start to result written
  double process_wall_s = 0;  ///< as the runner measured it: the child's start to its exit (0: run in-process)
  nlohmann::json figures;   ///< the summary (not in result.json: that is summary.json)
};

nlohmann::json to_json(const FlightResult& result);
/// result.json read back (figures empty); an Error when absent or unreadable.
Expected<FlightResult> read_result(const std::string& folder);
Status write_result(const std::string& folder, const FlightResult& result);

/// Flies `flight` against `stack` and writes its folder. An Error when the flight could not run
/// (the stack or the session could not start, the session failed); `stopped` is set when `stop`
/// ended it (its result is then not written: a resumed campaign flies it again).
Expected<FlightResult> run_flight(const Campaign& campaign, const Flight& flight, FlightStack& stack, const std::string& out_dir,
                                  const std::atomic<bool>& stop, hil::Session::Observer& observer, bool& stopped);

}  // namespace hitl::campaign
