// COMMAND_LONG as a ground station sends it: retransmitted (confirmation 0, 1, 2, ...) until a
// COMMAND_ACK for that command comes back; IN_PROGRESS extends the wait; every STATUSTEXT heard
// meanwhile is kept, so a denial can say why ("Arming denied: Preflight Fail: ekf2 not aligned").
#pragma once

#include <array>
#include <string>
#include <vector>

#include "base/common/expected.h"
#include "base/mavlink/enums.h"
#include "engine/vehicle/command_request.h"
#include "engine/vehicle/vehicle_link.h"

namespace hitl::vehicle {

std::string to_string(mavlink::MavResult result);

struct CommandOutcome {
  mavlink::MavResult result = mavlink::MavResult::Failed;
  std::vector<std::string> statustexts;  ///< heard while waiting, in order
  /// "accepted" / "temporarily rejected: Preflight Fail: ekf2 not aligned"
  std::string text() const;
  bool accepted() const { return result == mavlink::MavResult::Accepted; }
  /// A refusal that goes away by itself (the estimator or GPS still converging: "Preflight Fail:
  /// ekf2 not aligned", "GPS checks pending"), not one that needs the operator.
  bool pending() const;
};

class CommandClient {
 public:
  explicit CommandClient(VehicleLink& link) : link_(link) {}
  /// An Error only when no COMMAND_ACK came back at all (after `retries` sends).
  Expected<CommandOutcome> send(uint16_t command, const std::array<float, 7>& params, double timeout_s = 1.0,
                                int retries = 3, double in_progress_limit_s = 30.0);
  Expected<CommandOutcome> send(const CommandRequest& request, double timeout_s = 1.0) {
    return send(request.command, request.params, timeout_s);
  }

 private:
  VehicleLink& link_;
};

}  // namespace hitl::vehicle
