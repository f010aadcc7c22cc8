#include "engine/report/flight_log.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>

#include "base/contract/data_rates.h"
#include "base/contract/session_status.h"
#include "base/mavlink/enums.h"
#include "base/mavlink/frame_parser.h"
#include "base/mavlink/message_set.h"
#include "base/mavlink/messages.h"
#include "base/mavlink/severity.h"
#include "base/mavlink/text_field.h"
#include "engine/frames/frames.h"
#include "engine/mavlink/statustext.h"
#include "engine/mavlink/tlog.h"
#include "engine/mavlink/tlog_timeline.h"
#include "engine/report/fault_windows.h"
#include "engine/report/parameters.h"
#include "engine/telemetry/px4_mode.h"

namespace hitl::report {
namespace msg = mavlink::msg;

namespace {

constexpr double kRadToDeg = 180.0 / M_PI;
constexpr uint8_t kMavAutopilotInvalid = 8;
constexpr uint8_t kMavTypeGcs = 6;
constexpr double kTimingWindow_s = 1.0;

/// Wall time (tlog timestamps) to the simulator's clock: HIL_SENSOR's (wall, time_usec) pairs,
/// interpolated between, 1:1 beyond the ends. Without pairs: seconds since the first record.
class Clock {
 public:
  void add(uint64_t wall_us, uint64_t sim_us) {
    if (!anchors_.empty() && (wall_us < anchors_.back().first || sim_us < anchors_.back().second)) return;  // a reset
    anchors_.emplace_back(wall_us, sim_us);
  }
  void set_first_wall(uint64_t wall_us) { first_wall_us_ = wall_us; }
  bool simulated() const { return !anchors_.empty(); }
  double t_s(uint64_t wall_us) const {
    if (anchors_.empty()) return static_cast<double>(static_cast<int64_t>(wall_us - first_wall_us_)) * 1e-6;
    auto it = std::upper_bound(anchors_.begin(), anchors_.end(), wall_us,
                               [](uint64_t w, const std::pair<uint64_t, uint64_t>& a) { return w < a.first; });
    if (it == anchors_.begin()) return (static_cast<double>(it->second) - static_cast<double>(it->first - wall_us)) * 1e-6;
    const auto& a = *(it - 1);
    if (it == anchors_.end() || it->first == a.first)
      return (static_cast<double>(a.second) + static_cast<double>(wall_us - a.first)) * 1e-6;
    const double f = static_cast<double>(wall_us - a.first) / static_cast<double>(it->first - a.first);
    return (static_cast<double>(a.second) + f * static_cast<double>(it->second - a.second)) * 1e-6;
  }

 private:
  std::vector<std::pair<uint64_t, uint64_t>> anchors_;
  uint64_t first_wall_us_ = 0;
};

struct Arrivals {
  std::string name;
  std::optional<double> expected_hz;
  std::vector<double> t_s;
  std::vector<uint64_t> wall_us;
};

PathTiming timing_of(const Arrivals& a) {
  PathTiming p;
  p.name = a.name;
  p.expected_hz = a.expected_hz;
  p.count = a.t_s.size();
  if (a.t_s.size() < 2) return p;
  const double span_s = a.t_s.back() - a.t_s.front();
  p.mean_rate_hz = span_s > 0 ? static_cast<double>(a.t_s.size() - 1) / span_s : 0;
  std::size_t i = 0;
  for (double w0 = std::floor(a.t_s.front()); w0 < a.t_s.back(); w0 += kTimingWindow_s) {
    const double w1 = w0 + kTimingWindow_s;
    const std::size_t start = i;
    while (i < a.t_s.size() && a.t_s[i] < w1) ++i;
    const double length_s = std::min(w1, a.t_s.back()) - std::max(w0, a.t_s.front());
    if (length_s < 0.5 * kTimingWindow_s) continue;  // a partial window at either end says little
    p.rate_hz.t_s.push_back(w0 + 0.5 * kTimingWindow_s);
    p.rate_hz.value.push_back(static_cast<double>(i - start) / length_s);
    double sum = 0, sum_sq = 0;
    std::size_t n = 0;
    for (std::size_t k = start + 1; k < i; ++k) {
      const double d_ms = static_cast<double>(a.wall_us[k] - a.wall_us[k - 1]) * 1e-3;
      sum += d_ms;
      sum_sq += d_ms * d_ms;
      ++n;
    }
    if (n >= 2) {
      const double mean = sum / static_cast<double>(n);
      p.jitter_ms.t_s.push_back(w0 + 0.5 * kTimingWindow_s);
      p.jitter_ms.value.push_back(std::sqrt(std::max(0.0, sum_sq / static_cast<double>(n) - mean * mean)));
    }
  }
  return p;
}

void add_point(Track& track, double t_s, double n, double e, double d) {
  track.t_s.push_back(t_s);
  track.north_m.push_back(n);
  track.east_m.push_back(e);
  track.down_m.push_back(d);
}

void add_attitude(AttitudeTrack& track, double t_s, double roll_rad, double pitch_rad, double yaw_rad) {
  track.t_s.push_back(t_s);
  track.roll_deg.push_back(roll_rad * kRadToDeg);
  track.pitch_deg.push_back(pitch_rad * kRadToDeg);
  track.yaw_deg.push_back(yaw_rad * kRadToDeg);
}

void add_velocity(VelocityTrack& track, double t_s, const Eigen::Vector3d& v_NED_m_s) {
  track.t_s.push_back(t_s);
  track.north_m_s.push_back(v_NED_m_s.x());
  track.east_m_s.push_back(v_NED_m_s.y());
  track.down_m_s.push_back(v_NED_m_s.z());
}

void add_rates(RateTrack& track, double t_s, double roll_rad_s, double pitch_rad_s, double yaw_rad_s) {
  track.t_s.push_back(t_s);
  track.roll_deg_s.push_back(roll_rad_s * kRadToDeg);
  track.pitch_deg_s.push_back(pitch_rad_s * kRadToDeg);
  track.yaw_deg_s.push_back(yaw_rad_s * kRadToDeg);
}

void add(Series& s, double t_s, double v);

void add_sticks(Sticks& sticks, double t_s, double roll, double pitch, double throttle, double yaw) {
  add(sticks.roll, t_s, roll);
  add(sticks.pitch, t_s, pitch);
  add(sticks.throttle, t_s, throttle);
  add(sticks.yaw, t_s, yaw);
}

/// POSITION_TARGET_LOCAL_NED's type_mask bits 3-5: vx, vy, vz ignored; ATTITUDE_TARGET's bits 0-2:
/// the body rates ignored.
constexpr uint16_t kPositionTargetIgnoreVelocity = 0b111000;
constexpr uint8_t kAttitudeTargetIgnoreRates = 0b111;
void add_gps(GpsQuality& q, double t_s, uint8_t fix_type, uint8_t satellites, uint16_t eph, uint16_t epv) {
  add(q.fix_type, t_s, fix_type);
  if (satellites != UINT8_MAX) add(q.satellites, t_s, satellites);
  if (eph != UINT16_MAX) add(q.eph, t_s, eph / 100.0);
  if (epv != UINT16_MAX) add(q.epv, t_s, epv / 100.0);
}

/// HIL_SENSOR's fields_updated bits 0-5: xacc, yacc, zacc, xgyro, ygyro, zgyro.
constexpr uint32_t kHilSensorAccelAndGyro = 0b111111;
/// RC_CHANNELS_OVERRIDE: a channel of 0 or UINT16_MAX is not overridden.
bool rc_valid(uint16_t us) { return us >= 800 && us <= 2200; }
double rc_stick(uint16_t us) { return (static_cast<double>(us) - 1500.0) / 500.0; }

void add(Series& s, double t_s, double v) {
  s.t_s.push_back(t_s);
  s.value.push_back(v);
}

/// The vehicle's HEARTBEATs as events: armed, disarmed, each mode change.
struct VehicleState {
  std::optional<bool> armed;
  std::optional<std::string> mode;
};

std::string source_name(uint8_t sysid, uint8_t compid, uint8_t sim_id) {
  if (compid == mavlink::kCompIdPathPlanner) return "pilot";
  if (sysid == sim_id) return "simulator";
  return "system " + std::to_string(sysid);
}
std::string source_name(const mavlink::Frame& f, uint8_t sim_id) { return source_name(f.sysid, f.compid, sim_id); }

}  // namespace

Expected<FlightLog> read_flight_log(const std::string& path, const ReadLimits& limits, const std::vector<FieldPlotSpec>& field_plots) {
  const auto messages = mavlink::MessageSet::compiled();
  // Pass 1: the simulator's clock.
  Clock clock;
  std::optional<uint8_t> sim_sysid;
  // Both passes read through the timeline (tlog_timeline.h): a record whose stamp jumped is set
  // aside, never drawn.
  {
    auto opened = mavlink::TlogReader::open(path);
    if (!opened) return opened.error();
    mavlink::TlogTimeline reader(std::move(opened.value()), &messages);
    mavlink::FrameParser parser(messages);
    mavlink::TimedRecord timed;
    const mavlink::TlogRecord& r = timed.record;
    bool first = true;
    for (uint64_t n = 0; n < limits.max_records && reader.next(timed); ++n) {
      if (timed.unchecked) continue;  // no frame that checks: its stamp says nothing
      if (first) clock.set_first_wall(r.time_unix_us);
      first = false;
      parser.parse_datagram(r.frame, [&](const mavlink::Frame& f) {
        if (!f.is<msg::HilSensor>()) return;
        if (!sim_sysid) sim_sysid = f.sysid;
        if (f.sysid == *sim_sysid) clock.add(r.time_unix_us, f.as<msg::HilSensor>().time_usec);
      });
    }
  }
  // The simulator: who sent HIL_SENSOR; without one (a client's recording, hitl fly trajectory
  // --report through a session), hitl's simulator id, whose truth and status reach clients.
  const uint8_t sim_id = sim_sysid.value_or(kSimulatorSystemId);
  // Pass 2: the series.
  auto opened = mavlink::TlogReader::open(path);
  if (!opened) return opened.error();
  auto reader = std::make_unique<mavlink::TlogTimeline>(std::move(opened.value()), &messages);
  mavlink::FrameParser parser(messages);
  FlightLog log;
  log.path = path;
  log.simulated_time = clock.simulated();
  // hitl report --plot: each series by its message's id.
  std::map<uint32_t, std::vector<std::pair<const FieldExpression*, FieldSeries*>>> field_series_of;
  log.field_plots.resize(field_plots.size());
  for (std::size_t p = 0; p < field_plots.size(); ++p) {
    log.field_plots[p].text = field_plots[p].text;
    log.field_plots[p].series.resize(field_plots[p].series.size());
  }
  for (std::size_t p = 0; p < field_plots.size(); ++p)
    for (std::size_t k = 0; k < field_plots[p].series.size(); ++k) {
      const FieldExpression& e = field_plots[p].series[k];
      FieldSeries& s = log.field_plots[p].series[k];
      s.title = e.text, s.message = e.message, s.units = e.units;
      field_series_of[e.msgid].emplace_back(&e, &s);
    }
  Arrivals sensor{"HIL_SENSOR", 1.0 / kStepPeriod_s, {}, {}};
  Arrivals gps{"HIL_GPS", std::nullopt, {}, {}};
  Arrivals vio{"ODOMETRY (VIO)", kVioRate_hz, {}, {}};
  Arrivals actuators{"HIL_ACTUATOR_CONTROLS", std::nullopt, {}, {}};
  Track vehicle_setpoint;
  VelocityTrack vehicle_setpoint_velocity;
  std::map<uint8_t, VehicleState> vehicles;
  std::optional<uint8_t> mode_vehicle;  // whose modes are drawn as bands: the first vehicle heard
  uint64_t events_dropped = 0;
  uint64_t parameters_dropped = 0;
  auto event = [&](double t_s, Severity severity, std::string source, std::string text) {
    if (log.events.size() >= limits.max_events) {
      ++events_dropped;
      return;
    }
    log.events.push_back({t_s, severity, std::move(source), std::move(text)});
  };
  mavlink::StatusTextAssembler statustexts;  // PX4's long texts come in chunks
  auto statustext_event = [&](const mavlink::StatusText& t) {
    event(t.first_chunk_s, mavlink::severity_of(t.severity), source_name(t.sysid, t.compid, sim_id),
          mavlink::printable_statustext(t.text));
  };
  auto arrive = [](Arrivals& a, double t_s, uint64_t wall_us) {
    a.t_s.push_back(t_s);
    a.wall_us.push_back(wall_us);
  };
  double tracking_sum_sq = 0;
  bool armed_seen = false;                      // a vehicle said armed: the truth is no longer at rest
  std::vector<std::size_t> setpoints_on_truth;  // log.setpoint's points from the simulator's pilot (hitl sim -t)
  mavlink::TimedRecord timed;
  const mavlink::TlogRecord& r = timed.record;
  std::optional<uint64_t> first_wall_us, last_wall_us;
  std::optional<double> first_t_s, last_t_s;
  bool cut = false;
  for (;;) {
    if (log.records >= limits.max_records) {
      cut = reader->next(timed);
      break;
    }
    if (!reader->next(timed)) break;
    ++log.records;
    if (timed.unchecked) {  // counted in the parser's errors; its stamp says nothing
      parser.parse_datagram(r.frame, [](const mavlink::Frame&) {});
      continue;
    }
    const uint64_t wall_us = r.time_unix_us;
    const double t_s = clock.t_s(wall_us);
    if (!first_wall_us) first_wall_us = wall_us, first_t_s = t_s, log.first_unix_us = wall_us;
    last_wall_us = wall_us;
    last_t_s = t_s;
    parser.parse_datagram(r.frame, [&](const mavlink::Frame& f) {
      if (f.desc == nullptr) return;  // an id nobody described, its checksum unchecked: counted by the parser
      ++log.frames;
      if (!field_series_of.empty())
        if (const auto it = field_series_of.find(f.msgid); it != field_series_of.end())
          for (const auto& [expression, series] : it->second) {
            const double v = expression->evaluate(f.payload.data());
            if (std::isfinite(v)) add(series->values, t_s, v);
            else ++series->not_finite;
          }
      const bool from_sim = f.sysid == sim_id;
      const bool from_pilot = f.compid == mavlink::kCompIdPathPlanner;  // pilot_record.h: under sim -t or fly trajectory
      switch (f.msgid) {
        case msg::HilSensor::kId: {
          if (!from_sim) break;
          arrive(sensor, t_s, wall_us);
          const auto h = f.as<msg::HilSensor>();
          if ((h.fields_updated & kHilSensorAccelAndGyro) != kHilSensorAccelAndGyro) break;
          log.imu.t_s.push_back(t_s);
          const std::array<float, 3> accel = {h.xacc, h.yacc, h.zacc}, gyro = {h.xgyro, h.ygyro, h.zgyro};
          for (std::size_t k = 0; k < 3; ++k) {
            log.imu.accel_FRD_m_s2[k].push_back(accel[k]);
            log.imu.gyro_FRD_deg_s[k].push_back(gyro[k] * kRadToDeg);
          }
          break;
        }
        case msg::HilGps::kId: {
          if (!from_sim) break;
          arrive(gps, t_s, wall_us);
          const auto g = f.as<msg::HilGps>();
          add_gps(log.sent_gps, t_s, g.fix_type, g.satellites_visible, g.eph, g.epv);
          break;
        }
        case msg::GpsRawInt::kId: {
          const auto g = f.as<msg::GpsRawInt>();
          if (!from_sim) add_gps(log.vehicle_gps, t_s, g.fix_type, g.satellites_visible, g.eph, g.epv);
          break;
        }
        case msg::Odometry::kId: {
          const auto o = f.as<msg::Odometry>();
          if (from_sim && f.compid == kVioComponentId) arrive(vio, t_s, wall_us);
          if (from_sim && o.estimator_type == static_cast<uint8_t>(mavlink::MavEstimatorType::Mocap)) {
            if (!log.truth_rest_down_m && !armed_seen && log.truth.size() == 0) log.truth_rest_down_m = o.z;
            add_point(log.truth, t_s, o.x, o.y, o.z);
            const Eigen::Quaterniond q(o.q[0], o.q[1], o.q[2], o.q[3]);
            const auto e = frames::euler_from(q);
            add_attitude(log.truth_attitude, t_s, e.roll_rad, e.pitch_rad, e.yaw_rad);
            add_velocity(log.truth_velocity, t_s, q.normalized() * Eigen::Vector3d(o.vx, o.vy, o.vz));  // v_NED = R_FRD_to_NED v_FRD
            add_rates(log.truth_rates, t_s, o.rollspeed, o.pitchspeed, o.yawspeed);
          }
          break;
        }
        case msg::PositionTargetLocalNed::kId: {
          const auto sp = f.as<msg::PositionTargetLocalNed>();
          if (from_pilot && from_sim) setpoints_on_truth.push_back(log.setpoint.size());
          add_point(from_pilot ? log.setpoint : vehicle_setpoint, t_s, sp.x, sp.y, sp.z);
          if ((sp.type_mask & kPositionTargetIgnoreVelocity) == 0)
            add_velocity(from_pilot ? log.setpoint_velocity : vehicle_setpoint_velocity, t_s, Eigen::Vector3d(sp.vx, sp.vy, sp.vz));
          break;
        }
        case msg::AttitudeTarget::kId: {
          const auto a = f.as<msg::AttitudeTarget>();
          if (!from_sim && (a.type_mask & kAttitudeTargetIgnoreRates) == 0)
            add_rates(log.rate_setpoint, t_s, a.body_roll_rate, a.body_pitch_rate, a.body_yaw_rate);
          break;
        }
        case msg::ManualControl::kId: {
          const auto m = f.as<msg::ManualControl>();
          add_sticks(log.manual_control, t_s, m.y / 1000.0, m.x / 1000.0, m.z / 1000.0, m.r / 1000.0);
          break;
        }
        case msg::RcChannelsOverride::kId: {
          const auto c = f.as<msg::RcChannelsOverride>();
          if (rc_valid(c.chan1_raw) && rc_valid(c.chan2_raw) && rc_valid(c.chan3_raw) && rc_valid(c.chan4_raw))
            add_sticks(log.rc_override, t_s, rc_stick(c.chan1_raw), rc_stick(c.chan2_raw), rc_stick(c.chan3_raw), rc_stick(c.chan4_raw));
          break;
        }
        case msg::NamedValueFloat::kId: {
          const auto nv = f.as<msg::NamedValueFloat>();
          if (from_pilot && mavlink::text_of(nv.name) == kTrackingErrorName) {
            add(log.tracking_error_m, t_s, nv.value);
            tracking_sum_sq += static_cast<double>(nv.value) * nv.value;
          }
          break;
        }
        case msg::NamedValueInt::kId: {
          const auto nv = f.as<msg::NamedValueInt>();
          if (!from_sim) break;
          const auto name = mavlink::text_of(nv.name);
          if (name == kStatusLateName) log.late_ticks = nv.value;
          if (name == kStatusLockstepName) log.lockstep = nv.value != 0;
          if (name == kStatusLoopLatencyP99Name) log.loop_latency.reported = true;
          for (const auto& [series_name, series] : {std::pair{kStatusLoopLatencyP50Name, &log.loop_latency.p50_us},
                                                    std::pair{kStatusLoopLatencyP99Name, &log.loop_latency.p99_us},
                                                    std::pair{kStatusLoopLatencyMaxName, &log.loop_latency.max_us}})
            if (name == series_name && nv.value >= 0) add(*series, t_s, nv.value);
          break;
        }
        case msg::LocalPositionNed::kId:
          if (!from_sim) {
            const auto p = f.as<msg::LocalPositionNed>();
            add_point(log.estimate, t_s, p.x, p.y, p.z);
            add_velocity(log.estimate_velocity, t_s, Eigen::Vector3d(p.vx, p.vy, p.vz));
          }
          break;
        case msg::Attitude::kId:
          if (!from_sim) {
            const auto a = f.as<msg::Attitude>();
            add_attitude(log.estimate_attitude, t_s, a.roll, a.pitch, a.yaw);
            add_rates(log.estimate_rates, t_s, a.rollspeed, a.pitchspeed, a.yawspeed);
          }
          break;
        case msg::HilActuatorControls::kId: {
          if (from_sim) break;
          arrive(actuators, t_s, wall_us);
          const auto a = f.as<msg::HilActuatorControls>();
          for (std::size_t k = 0; k < log.motors.size(); ++k) add(log.motors[k], t_s, a.controls[k]);
          break;
        }
        case msg::EstimatorStatus::kId: {
          if (from_sim) break;
          const auto e = f.as<msg::EstimatorStatus>();
          const std::array<float, 6> ratios = {e.vel_ratio, e.pos_horiz_ratio, e.pos_vert_ratio, e.mag_ratio, e.hagl_ratio, e.tas_ratio};
          for (std::size_t k = 0; k < ratios.size(); ++k) add(log.ekf_ratios[k], t_s, ratios[k]);
          break;
        }
        case msg::ParamValue::kId: {
          if (from_sim) break;
          const auto pv = f.as<msg::ParamValue>();
          const std::string name(mavlink::text_of(pv.param_id));
          if (log.parameters.size() >= limits.max_parameters && !log.parameters.count(name)) {
            ++parameters_dropped;
            break;
          }
          const double value = param_value_number(pv.param_value, pv.param_type);
          log.parameters[name] = value;
          log.parameters_first.try_emplace(name, value);
          break;
        }
        case msg::Statustext::kId: {
          for (const auto& t : statustexts.on_frame(f, t_s)) statustext_event(t);
          break;
        }
        case msg::Heartbeat::kId: {
          const auto hb = f.as<msg::Heartbeat>();
          if (from_sim || hb.autopilot == kMavAutopilotInvalid || hb.type == kMavTypeGcs) break;
          auto& v = vehicles[f.sysid];
          const bool armed = (hb.base_mode & mavlink::mode_flag::kSafetyArmed) != 0;
          armed_seen = armed_seen || armed;
          const auto mode = telemetry::px4_mode_name(hb.base_mode, hb.custom_mode);
          if (v.armed != armed) event(t_s, Severity::Info, source_name(f, sim_id), armed ? "armed" : "disarmed");
          if (v.mode != mode) event(t_s, Severity::Info, source_name(f, sim_id), "mode " + mode);
          if (!mode_vehicle) mode_vehicle = f.sysid, log.vehicle = VehicleInfo{f.sysid, hb.type, hb.autopilot};
          if (*mode_vehicle == f.sysid && v.mode != mode) {
            if (!log.modes.empty()) log.modes.back().end_s = t_s;
            log.modes.push_back({mode, t_s, t_s});
          }
          v.armed = armed;
          v.mode = mode;
          break;
        }
        default: break;
      }
    });
  }
  for (const auto& t : statustexts.flush()) statustext_event(t);
  std::stable_sort(log.events.begin(), log.events.end(), [](const auto& a, const auto& b) { return a.t_s < b.t_s; });
  if (log.frames == 0) return Error::input("'" + path + "' holds no MAVLink frame of a known message (is it a .tlog?)");
  log.skipped_bytes = reader->stats().skipped_bytes;
  log.segments = reader->timeline().segments;
  log.set_aside_records = reader->timeline().set_aside_records;
  if (log.skipped_bytes > 0) log.skipped.push_back(std::to_string(log.skipped_bytes) + " bytes that were no timestamp + frame (corruption)");
  if (log.parse_errors > 0) log.skipped.push_back(std::to_string(log.parse_errors) + " frames the parser rejected (checksum, unknown id)");
  if (log.set_aside_records > 0)
    log.skipped.push_back(std::to_string(log.set_aside_records) + " records set aside: their timestamp jumped and the next record did not confirm it");
  if (log.segments > 1)
    log.skipped.push_back("the order of the log's " + std::to_string(log.segments) +
                          " segments (its clock jumped back, or ahead more than 60 s: logs joined): they share one time axis");
  log.parse_errors = parser.stats().crc_errors + parser.stats().unknown_ids;
  log.start_s = *first_t_s;
  log.duration_s = *last_t_s - *first_t_s;
  if (!log.modes.empty()) log.modes.back().end_s = *last_t_s;
  log.faults = fault_windows(log.events, log.simulated_time);
  log.wall_duration_s = std::max(0.0, static_cast<double>(*last_wall_us) - static_cast<double>(*first_wall_us)) * 1e-6;
  // One height datum, home (docs/sim.md): the truth and the setpoints flown on it, down by the
  // truth's height at rest; the vehicle's own frames are from home already.
  if (log.truth_rest_down_m) {
    for (double& d : log.truth.down_m) d -= *log.truth_rest_down_m;
    for (std::size_t i : setpoints_on_truth) log.setpoint.down_m[i] -= *log.truth_rest_down_m;
  }
  if (log.setpoint.size() == 0) log.setpoint = std::move(vehicle_setpoint), log.setpoint_velocity = std::move(vehicle_setpoint_velocity);
  if (log.tracking_error_m.size() > 0) {
    TrackingSummary s;
    s.samples = log.tracking_error_m.size();
    s.rms_m = std::sqrt(tracking_sum_sq / static_cast<double>(s.samples));
    s.max_m = *std::max_element(log.tracking_error_m.value.begin(), log.tracking_error_m.value.end());
    log.tracking = s;
  }
  if (log.lockstep) actuators.expected_hz = *log.lockstep ? 1.0 / kStepPeriod_s : kActuatorStreamRate_hz;
  for (const Arrivals* a : {&sensor, &gps, &vio, &actuators})
    if (!a->t_s.empty()) log.paths.push_back(timing_of(*a));
  // What this log cannot show, in words.
  auto lacks = [&](bool missing, const std::string& what) {
    if (missing) log.missing.push_back(what);
  };
  lacks(!log.simulated_time, "the simulator's clock (HIL_SENSOR from a simulator): times are seconds since the first record");
  lacks(log.truth.size() == 0, "ground truth (ODOMETRY with estimator MOCAP from the simulator; hitl sim --record writes it)");
  lacks(log.truth.size() > 0 && !log.truth_rest_down_m,
        "the truth at rest (the vehicle was armed when the truth began): the truth's heights are its body origin's in "
        "the simulator's world, not from home");
  lacks(log.setpoint.size() == 0, "setpoints (POSITION_TARGET_LOCAL_NED; hitl sim -t --record and hitl fly trajectory --report write the pilot's)");
  lacks(log.tracking_error_m.size() == 0, "the tracking error (NAMED_VALUE_FLOAT trk_err; hitl sim -t --record and hitl fly trajectory --report write it)");
  lacks(log.estimate.size() == 0, "the vehicle's position estimate (LOCAL_POSITION_NED)");
  lacks(log.estimate_attitude.size() == 0, "the vehicle's attitude (ATTITUDE)");
  lacks(log.motors[0].size() == 0, "motor commands (HIL_ACTUATOR_CONTROLS)");
  lacks(log.ekf_ratios[0].size() == 0, "EKF test ratios (ESTIMATOR_STATUS)");
  lacks(log.paths.empty(), "the HIL data paths (HIL_SENSOR, HIL_GPS, ODOMETRY, HIL_ACTUATOR_CONTROLS)");
  lacks(!log.late_ticks, "the session's status (NAMED_VALUE_INT sim_late: late ticks)");
  if (!log.late_ticks && !log.loop_latency.reported)
    lacks(true, "the loop latency (no hitl session status in this log: hitl sim --record writes it once a second)");
  else if (!log.loop_latency.reported)
    lacks(true, "the loop latency (NAMED_VALUE_INT sim_lat99 in the session's status: the hitl sim that wrote this log "
                "did not record it; newer ones do)");
  else
    lacks(log.loop_latency.p99_us.size() == 0, "the loop latency (no HIL_SENSOR was answered: sim_lat99 stayed -1)");
  if (cut) log.missing.push_back("records after the first " + std::to_string(limits.max_records) + " (the log was cut there)");
  if (parameters_dropped > 0)
    log.missing.push_back(std::to_string(parameters_dropped) + " PARAM_VALUE of names after the first " + std::to_string(limits.max_parameters));
  if (events_dropped > 0) log.missing.push_back(std::to_string(events_dropped) + " events after the first " + std::to_string(limits.max_events));
  return log;
}

}  // namespace hitl::report
