#include "engine/vehicle/command_worker.h"

#include "engine/vehicle/patient_link.h"

namespace hitl::vehicle {

const char* to_string(OperatorCommand command) {
  switch (command) {
    case OperatorCommand::Arm: return "arm";
    case OperatorCommand::Disarm: return "disarm";
    case OperatorCommand::ForceDisarm: return "force disarm";
    case OperatorCommand::Takeoff: return "takeoff";
    case OperatorCommand::Land: return "land";
  }
  return "?";
}

CommandWorker::CommandWorker(LinkOptions options, OutcomeSink outcome)
    : options_(std::move(options)), outcome_(std::move(outcome)) {
  thread_ = std::thread([this] { run(); });
}

CommandWorker::~CommandWorker() { stop(); }

void CommandWorker::stop() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_.store(true);
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void CommandWorker::submit(OperatorCommand command) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    queue_.push_back(command);
  }
  wake_.notify_all();
}

std::size_t CommandWorker::pending() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return queue_.size() + in_flight_;
}

void CommandWorker::execute(VehicleLink& link, OperatorCommand command) {
  Action action(link);
  ActionOutcome outcome;
  switch (command) {
    case OperatorCommand::Arm: outcome = action.arm(); break;
    case OperatorCommand::Disarm: outcome = action.disarm(); break;
    case OperatorCommand::ForceDisarm: outcome = action.disarm(/*force=*/true); break;
    case OperatorCommand::Takeoff: outcome = action.takeoff(); break;  // the board's MIS_TAKEOFF_ALT above home
    case OperatorCommand::Land: outcome = action.land(); break;
  }
  if (outcome_) outcome_(command, outcome.ok(), outcome_text(command, outcome));
}

std::string outcome_text(OperatorCommand command, const ActionOutcome& outcome) {
  const std::string name = to_string(command);
  const bool arming = command == OperatorCommand::Arm || command == OperatorCommand::Disarm || command == OperatorCommand::ForceDisarm;
  switch (outcome.result) {
    case ActionResult::Success:
      if (arming) return command == OperatorCommand::Arm ? "armed" : "disarmed";
      return name + " " + outcome.command->text();
    case ActionResult::Refused: return name + " " + outcome.command->text();
    case ActionResult::NotShown:
      return name + " accepted, but HEARTBEAT did not show it within " + std::to_string(static_cast<int>(Action::kShowArmed_s)) + " s";
    case ActionResult::NoAnswer:
    case ActionResult::NoPosition: return name + ": " + outcome.error;
  }
  return name;
}

void CommandWorker::run() {
  auto link = connect_patiently(options_, stop_, {});
  while (link && !stop_.load()) {
    OperatorCommand command;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      // Wake now and then without work: the link's wait() keeps our HEARTBEAT going to the session.
      if (!wake_.wait_for(lock, std::chrono::milliseconds(500), [&] { return stop_.load() || !queue_.empty(); })) {
        lock.unlock();
        link->wait(0.01, [](const mavlink::Frame&) { return false; });
        continue;
      }
      if (stop_.load()) break;
      command = queue_.front();
      queue_.pop_front();
      in_flight_ = 1;
    }
    link->wait(0.01, [](const mavlink::Frame&) { return false; });  // drop what queued up meanwhile (old ACKs)
    execute(*link, command);
    std::lock_guard<std::mutex> lock(mutex_);
    in_flight_ = 0;
  }
  // Whatever is still queued never ran: say so rather than drop it silently.
  std::lock_guard<std::mutex> lock(mutex_);
  for (const auto command : queue_)
    if (outcome_) outcome_(command, false, std::string(to_string(command)) + ": not sent (no autopilot link)");
  queue_.clear();
}

}  // namespace hitl::vehicle
