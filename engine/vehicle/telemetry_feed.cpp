#include "engine/vehicle/telemetry_feed.h"

#include <cmath>
#include <cstring>

#include "base/common/clock.h"
#include "base/mavlink/messages.h"
#include "base/mavlink/text_field.h"
#include "engine/vehicle/patient_link.h"

namespace hitl::vehicle {
namespace {

namespace msg = mavlink::msg;
/// A requested stream silent for this long (wall time) is asked for again.
constexpr double kRerequestAfter_s = 5.0;

}  // namespace

std::vector<StreamRequest> dashboard_streams() {
  return {{msg::EstimatorStatus::kId, 5},      {msg::LocalPositionNed::kId, 10}, {msg::AttitudeQuaternion::kId, 10},
          {msg::ExtendedSysState::kId, 2},     {msg::Heartbeat::kId, 1},         {msg::SysStatus::kId, 1},
          {msg::BatteryStatus::kId, 1},        {msg::GlobalPositionInt::kId, 5}};
}

TelemetryFeed::TelemetryFeed(LinkOptions options, std::vector<StreamRequest> streams, TextSink statustext,
                             std::optional<uint8_t> truth_sysid)
    : options_(std::move(options)),
      streams_(std::move(streams)),
      truth_sysid_(truth_sysid),
      requested_at_s_(streams_.size(), -1e9),
      statustext_(std::move(statustext)) {
  thread_ = std::thread([this] { run(); });
}

TelemetryFeed::~TelemetryFeed() { stop(); }

void TelemetryFeed::stop() {
  stop_.store(true);
  if (thread_.joinable()) thread_.join();
}

TelemetryFeedSnapshot TelemetryFeed::snapshot() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return published_;
}

void TelemetryFeed::show(const std::vector<mavlink::StatusText>& texts) {
  if (!statustext_) return;
  for (const auto& t : texts)
    statustext_(static_cast<mavlink::MavSeverity>(t.severity), mavlink::printable_statustext(t.text));
}

void TelemetryFeed::request_streams(VehicleLink& link, double now_s, bool all) {
  const auto& heard = tracker_.state().last_heard_s;
  for (std::size_t i = 0; i < streams_.size(); ++i) {
    const auto& r = streams_[i];
    const auto it = heard.find(r.message_id);
    const bool silent = it == heard.end() || now_s - it->second > kRerequestAfter_s;
    if (!all && (!silent || now_s - requested_at_s_[i] < kRerequestAfter_s)) continue;
    // Sent without waiting for the ACK: waiting would drop the telemetry that arrives meanwhile.
    msg::CommandLong c;
    c.target_system = link.target_sysid();
    c.target_component = link.target_compid();
    c.command = mavlink::cmd::kSetMessageInterval;
    c.param1 = static_cast<float>(r.message_id);
    c.param2 = static_cast<float>(1e6 / r.rate_hz);
    link.send(c);
    requested_at_s_[i] = now_s;
  }
}

void TelemetryFeed::on_truth(const mavlink::Frame& f) {
  if (!truth_sysid_ || f.sysid != *truth_sysid_ || !f.is<msg::Odometry>()) return;
  const auto odo = f.as<msg::Odometry>();
  if (odo.estimator_type != static_cast<uint8_t>(mavlink::MavEstimatorType::Mocap)) return;
  telemetry::TruthPose t;
  t.sim_time_s = static_cast<double>(odo.time_usec) * 1e-6;
  t.p_NED_m = {odo.x, odo.y, odo.z};
  t.q_FRD_to_NED = {odo.q[0], odo.q[1], odo.q[2], odo.q[3]};
  for (double v : t.p_NED_m)
    if (!std::isfinite(v)) return;
  // The estimator's origin is where the vehicle rested when it started: learn the truth's height
  // there while the autopilot says it is on the ground.
  const auto& v = tracker_.state();
  if (v.landed && *v.landed == "on ground" && !v.armed) rest_down_m_ = t.p_NED_m[2];
  if (rest_down_m_) t.p_NED_m[2] -= *rest_down_m_;
  truth_ = t;
}

void TelemetryFeed::run() {
  auto link = connect_patiently(options_, stop_, [&](const std::string&) {
    std::lock_guard<std::mutex> lock(mutex_);
    published_.link = "waiting for an autopilot HEARTBEAT through " + options_.connect;
  });
  if (!link) return;
  link->on_other_systems([this](const mavlink::Frame& f) { on_truth(f); });
  {
    std::lock_guard<std::mutex> lock(mutex_);
    published_.connected = true;
    published_.link = "through " + options_.connect;
  }
  if (statustext_)
    statustext_(mavlink::MavSeverity::Info,
                "telemetry: autopilot " + std::to_string(link->target_sysid()) + " through " + options_.connect);
  request_streams(*link, monotonic_s(), true);
  uint64_t refused = 0;
  double next_publish_s = 0;
  while (!stop_.load()) {
    link->wait(0.05, [&](const mavlink::Frame& f) {
      const double now_s = monotonic_s();
      tracker_.on_frame(f, now_s);
      if (f.is<msg::Statustext>()) {
        show(statustexts_.on_frame(f, now_s));
      } else if (f.is<msg::CommandAck>()) {
        const auto a = f.as<msg::CommandAck>();
        if (a.command == mavlink::cmd::kSetMessageInterval && a.result != static_cast<uint8_t>(mavlink::MavResult::Accepted))
          ++refused;
      } else if (truth_ && f.is<msg::LocalPositionNed>()) {
        if (rest_down_m_) error_meter_.on_position(*tracker_.state().p_NED_m, *truth_);
      } else if (truth_ && f.is<msg::AttitudeQuaternion>()) {
        error_meter_.on_attitude(*tracker_.state().q_FRD_to_NED, *truth_);
      }
      return false;
    });
    const double now_s = monotonic_s();
    show(statustexts_.expire(now_s));
    request_streams(*link, now_s, false);
    if (now_s >= next_publish_s) {
      next_publish_s = now_s + 0.05;
      std::lock_guard<std::mutex> lock(mutex_);
      published_.vehicle = tracker_.state();
      published_.estimate_error = error_meter_.error();
      published_.truth_heard = truth_.has_value();
      published_.requests_refused = refused;
    }
  }
}

}  // namespace hitl::vehicle
