#include "engine/vehicle/trajectory_worker.h"

namespace hitl::vehicle {

TrajectoryWorker::~TrajectoryWorker() {
  stop();
  std::lock_guard<std::mutex> lock(mutex_);
  if (thread_.joinable()) thread_.join();
}

Status TrajectoryWorker::start(LinkOptions link, Trajectory trajectory, FlyTrajectoryOptions options, FlightNotes notes, Done done) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (running_.load()) return Error::failed("a trajectory is already being flown");
  if (thread_.joinable()) thread_.join();  // the last flight's thread, finished
  stop_.store(false);
  running_.store(true);
  link.stop = &stop_;  // a discovery or a wait in progress ends when asked to stop
  options.stop = &stop_;
  thread_ = std::thread([this, link, trajectory = std::move(trajectory), options, notes = std::move(notes),
                         done = std::move(done)]() mutable {
    Expected<FlightResult> result = Error::failed("not flown");
    if (auto connected = VehicleLink::connect(link)) {
      result = fly_trajectory(**connected, std::move(trajectory), options, notes);
    } else {
      result = connected.error();
    }
    if (done) done(result);
    running_.store(false);
  });
  return Ok{};
}

}  // namespace hitl::vehicle
