#include "engine/doctor/observations.h"

#include <string_view>

#include "base/contract/board_ports.h"
#include "base/contract/data_rates.h"
#include "base/contract/session_status.h"
#include "base/mavlink/enums.h"
#include "base/mavlink/messages.h"

namespace hitl::doctor {
namespace {

namespace msg = mavlink::msg;

template <std::size_t N>
std::string text_of(const std::array<char, N>& field) {
  std::size_t n = 0;
  while (n < N && field[n] != '\0') ++n;
  return std::string(field.data(), n);
}

}  // namespace

bool HeartbeatSeen::armed() const { return (base_mode & mavlink::mode_flag::kSafetyArmed) != 0; }

void ObservationTracker::on_autopilot_frame(const mavlink::Frame& f, double now_s) {
  if (f.desc == nullptr) return;
  switch (f.msgid) {
    case msg::Heartbeat::kId: {
      const auto m = f.as<msg::Heartbeat>();
      if (m.autopilot == static_cast<uint8_t>(mavlink::MavAutopilot::Invalid)) return;
      auto& h = seen_.heartbeat;
      if (!h) {
        h.emplace();
        h->first_s = now_s;
      }
      h->sysid = f.sysid;
      h->compid = f.compid;
      h->autopilot = m.autopilot;
      h->type = m.type;
      h->base_mode = m.base_mode;
      h->custom_mode = m.custom_mode;
      h->system_status = m.system_status;
      h->last_s = now_s;
      ++h->count;
      break;
    }
    case msg::SysStatus::kId: {
      const auto m = f.as<msg::SysStatus>();
      seen_.sys_status = SysStatusSeen{m.onboard_control_sensors_present, m.onboard_control_sensors_enabled,
                                       m.onboard_control_sensors_health};
      break;
    }
    case msg::EstimatorStatus::kId:
      seen_.estimator = telemetry::estimator_status_from(f);
      ++seen_.estimator_reports;
      break;
    case msg::Statustext::kId: {
      for (auto& text : statustexts_.on_frame(f, now_s)) add_statustext(std::move(text.text));
      break;
    }
    default: break;
  }
}

void ObservationTracker::add_statustext(std::string text) {
  seen_.statustext.push_back(std::move(text));
  if (seen_.statustext.size() > 50) seen_.statustext.erase(seen_.statustext.begin());
}

const Observations& ObservationTracker::observations() {
  for (auto& text : statustexts_.flush()) add_statustext(std::move(text.text));
  return seen_;
}

void ObservationTracker::on_other_frame(const mavlink::Frame& f, double now_s) {
  if (f.desc == nullptr) return;
  SessionStatus& s = seen_.session;
  if (f.is<msg::NamedValueFloat>()) {
    const auto m = f.as<msg::NamedValueFloat>();
    const std::string name = text_of(m.name);
    const double v = m.value;
    if (name == hitl::kStatusRtfName) {
      s.sysid = f.sysid;
      s.rtf = v;
      ++s.reports;
    } else if (s.sysid && f.sysid == *s.sysid) {
      if (name == hitl::kStatusSpeedName) s.speed = v;
      else if (name == hitl::kStatusActuatorRateName) s.actuator_hz = v;
    }
  } else if (f.is<msg::NamedValueInt>()) {
    const auto m = f.as<msg::NamedValueInt>();
    if (!s.sysid || f.sysid != *s.sysid) return;  // the session says "sim_rtf" first each second
    const std::string name = text_of(m.name);
    if (name == hitl::kStatusLateName) {
      s.last_late = SessionStatus::LateSample{now_s, m.value};
      if (!s.first_late) s.first_late = s.last_late;
    } else if (name == hitl::kStatusPauseName) {
      s.paused = m.value != 0;
    } else if (name == hitl::kStatusLockstepName) {
      s.lockstep = m.value != 0;
    } else if (name == hitl::kStatusActuatorFlagsName) {
      s.actuator_flags = m.value;
    } else if (name == hitl::kStatusActuatorArmedName) {
      s.actuator_armed = m.value;
    } else if (name == hitl::kStatusLoopLatencyP99Name) {
      s.loop_latency_p99_us = m.value;
    } else if (name == hitl::kStatusPx4InstanceName) {
      s.px4_instance = m.value;
    }
  } else if (f.is<msg::Heartbeat>()) {
    const auto m = f.as<msg::Heartbeat>();
    if (s.sysid && f.sysid == *s.sysid && m.autopilot == static_cast<uint8_t>(mavlink::MavAutopilot::Invalid))
      s.system_status = m.system_status;
  }
}

}  // namespace hitl::doctor
