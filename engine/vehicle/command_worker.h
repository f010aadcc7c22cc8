// The operator's commands for a dashboard, on their own thread and their own link, one at a time
// in the order asked: arm, disarm (forced when the operator confirmed a disarm in the air),
// takeoff, land; each through the action API (engine/vehicle/action.h), as `hitl arm` / `hitl fly`
// send them. Arming and disarming succeed only once HEARTBEAT shows the new state; takeoff and land
// once accepted. Outcomes go to a callback, in words.
#pragma once

#include <atomic>
#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

#include "engine/vehicle/action.h"
#include "engine/vehicle/vehicle_link.h"

namespace hitl::vehicle {

enum class OperatorCommand { Arm, Disarm, ForceDisarm, Takeoff, Land };
const char* to_string(OperatorCommand command);  ///< "arm", "disarm", "force disarm", "takeoff", "land"
/// "armed", "takeoff accepted", "arm temporarily rejected: Preflight Fail: ...", "land: no COMMAND_ACK ..."
std::string outcome_text(OperatorCommand command, const ActionOutcome& outcome);

class CommandWorker {
 public:
  using OutcomeSink = std::function<void(OperatorCommand command, bool ok, const std::string& text)>;

  CommandWorker(LinkOptions options, OutcomeSink outcome);
  ~CommandWorker();  ///< stops (after the command in flight) and joins
  CommandWorker(const CommandWorker&) = delete;
  CommandWorker& operator=(const CommandWorker&) = delete;

  void submit(OperatorCommand command);
  /// Commands queued or in flight.
  std::size_t pending() const;
  void stop();

 private:
  void run();
  void execute(class VehicleLink& link, OperatorCommand command);

  LinkOptions options_;
  OutcomeSink outcome_;
  std::atomic<bool> stop_{false};
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<OperatorCommand> queue_;
  std::size_t in_flight_ = 0;
  std::thread thread_;
};

}  // namespace hitl::vehicle
