// fly_trajectory() for a dashboard: on its own thread and its own link (as the command worker), so
// the keys and the drawing go on while it flies; stop() asks it to end. What it says as it goes and
// its result reach callbacks. The dashboard's `f` key flies through here, in-process.
#pragma once

#include <atomic>
#include <functional>
#include <mutex>
#include <thread>

#include "base/common/expected.h"
#include "engine/vehicle/trajectory_flight.h"

namespace hitl::vehicle {

class TrajectoryWorker {
 public:
  using Done = std::function<void(const Expected<FlightResult>& result)>;

  TrajectoryWorker() = default;
  ~TrajectoryWorker();  ///< stops a flight in progress and waits for it
  TrajectoryWorker(const TrajectoryWorker&) = delete;
  TrajectoryWorker& operator=(const TrajectoryWorker&) = delete;

  /// Connects with `link` (once, as `hitl fly` does) and flies `trajectory`; an Error when a flight
  /// is still in progress. `options.stop` is this worker's own.
  Status start(LinkOptions link, Trajectory trajectory, FlyTrajectoryOptions options, FlightNotes notes, Done done);
  bool running() const { return running_.load(); }
  /// Asks the flight to end (its result then says stopped); returns at once.
  void stop() { stop_.store(true); }

 private:
  std::atomic<bool> running_{false};
  std::atomic<bool> stop_{false};
  std::mutex mutex_;
  std::thread thread_;
};

}  // namespace hitl::vehicle
