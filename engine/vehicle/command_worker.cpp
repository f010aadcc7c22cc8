#include "engine/vehicle/command_worker.h"

#include <cmath>

#include "base/mavlink/enums.h"
#include "base/mavlink/messages.h"
#include "engine/vehicle/command_client.h"
#include "engine/vehicle/patient_link.h"

namespace hitl::vehicle {
namespace {
namespace msg = mavlink::msg;
constexpr double kConfirm_s = 3.0;  ///< how long HEARTBEAT may take to show an accepted arm/disarm
}  // namespace

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
  CommandClient client(link);
  const char* name = to_string(command);
  auto report = [&](bool ok, const std::string& text) {
    if (outcome_) outcome_(command, ok, text);
  };
  Expected<CommandOutcome> outcome = Error{""};
  switch (command) {
    case OperatorCommand::Arm:
    case OperatorCommand::Disarm:
    case OperatorCommand::ForceDisarm: {
      const bool arm = command == OperatorCommand::Arm;
      const float force = command == OperatorCommand::ForceDisarm ? mavlink::cmd::kArmDisarmForceMagic : 0.0f;
      outcome = client.send(mavlink::cmd::kComponentArmDisarm, {arm ? 1.0f : 0.0f, force, 0, 0, 0, 0, 0});
      if (!outcome) return report(false, std::string(name) + ": " + outcome.error().message);
      if (!outcome->accepted()) return report(false, std::string(name) + " " + outcome->text());
      const bool shown = link.wait(kConfirm_s, [&](const mavlink::Frame& f) {
        return f.is<msg::Heartbeat>() && ((f.as<msg::Heartbeat>().base_mode & mavlink::mode_flag::kSafetyArmed) != 0) == arm;
      });
      if (!shown) return report(false, std::string(name) + " accepted, but HEARTBEAT did not show it within 3 s");
      return report(true, arm ? "armed" : "disarmed");
    }
    case OperatorCommand::Takeoff:  // NaN altitude: the board's MIS_TAKEOFF_ALT above home
      outcome = client.send(mavlink::cmd::kNavTakeoff, {0, 0, 0, NAN, NAN, NAN, NAN});
      break;
    case OperatorCommand::Land:
      outcome = client.send(mavlink::cmd::kNavLand, {0, 0, 0, NAN, NAN, NAN, NAN});
      break;
  }
  if (!outcome) return report(false, std::string(name) + ": " + outcome.error().message);
  report(outcome->accepted(), std::string(name) + " " + outcome->text());
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
