#include "emulator/flight_adapter.h"

#include <cmath>

#include "base/contract/device_ids.h"
#include "emulator/flight/flight_core.h"
#include "emulator/flight/rc_input.h"

namespace hitl::target {
namespace {

mavlink::MavResult to_mav_result(flight::CommandResult r) {
  switch (r) {
    case flight::CommandResult::Accepted: return mavlink::MavResult::Accepted;
    case flight::CommandResult::TemporarilyRejected: return mavlink::MavResult::TemporarilyRejected;
    case flight::CommandResult::Denied: return mavlink::MavResult::Denied;
    case flight::CommandResult::Failed: return mavlink::MavResult::Failed;
  }
  return mavlink::MavResult::Failed;
}

CommandResult reply(const flight::CommandReply& r) { return {to_mav_result(r.result), r.reason}; }

Eigen::Vector3d vec(const float (&v)[3]) { return {v[0], v[1], v[2]}; }

}  // namespace

struct FlightAdapter::Impl {
  flight::FlightCore core;
  std::vector<flight::StatusMessage> said;  ///< the adapter's own denials, for take_messages()
  flight::StickInput sticks;  ///< the last sticks, for channels an override leaves as they were
};

FlightAdapter::FlightAdapter(ParamStore& params) : impl_(std::make_unique<Impl>()), params_(params) {
  for (const auto& info : flight::param_table()) {
    const auto value = info.type == flight::ParamType::Int32
                           ? vehicle::ParamValue::int32(static_cast<int32_t>(std::lround(info.default_value)))
                           : vehicle::ParamValue::real32(static_cast<float>(info.default_value));
    params.add(info.name, value, info.min_value, info.max_value);
  }
  Impl* impl = impl_.get();
  params.on_change([impl](const vehicle::Param& p) {
    if (flight::find_param(p.name) != nullptr) flight::set_param(impl->core.params(), p.name, p.value.as_double());
  });
}

FlightAdapter::~FlightAdapter() = default;

void FlightAdapter::on_imu(const SensorAccel& accel, const SensorGyro& gyro) {
  flight::ImuSample s;
  s.time_us = gyro.timestamp_sample_us;
  s.accel_FRD_m_s2 = vec(accel.accel_FRD_m_s2);
  s.gyro_FRD_rad_s = vec(gyro.gyro_FRD_rad_s);
  impl_->core.handle_imu(s);
}

void FlightAdapter::on_mag(const SensorMag& mag) {
  flight::MagSample s;
  s.time_us = mag.timestamp_sample_us;
  s.mag_FRD_gauss = vec(mag.mag_FRD_gauss);
  if (mag_swing_rad_ != 0) {  // --fault ekf-not-converging: the field turned about body down (FRD z)
    mag_swing_right_ = !mag_swing_right_;
    s.mag_FRD_gauss = Eigen::AngleAxisd(mag_swing_right_ ? mag_swing_rad_ : -mag_swing_rad_, Eigen::Vector3d::UnitZ()) *
                      s.mag_FRD_gauss;
  }
  impl_->core.handle_mag(s);
}

void FlightAdapter::on_baro(const SensorBaro& baro) {
  flight::BaroSample s;
  s.time_us = baro.timestamp_sample_us;
  s.pressure_Pa = baro.pressure_Pa;
  s.temperature_degC = baro.temperature_degC;
  impl_->core.handle_baro(s);
}

void FlightAdapter::on_gps(const SensorGps& gps) {
  flight::GpsSample s;
  s.time_us = gps.timestamp_us;
  s.lat_deg = gps.latitude_deg;
  s.lon_deg = gps.longitude_deg;
  s.alt_msl_m = gps.altitude_msl_m;
  s.v_NED_m_s = {gps.vel_n_m_s, gps.vel_e_m_s, gps.vel_d_m_s};
  s.eph_m = gps.eph_m;
  s.epv_m = gps.epv_m;
  s.fix_type = gps.fix_type;
  s.satellites = gps.satellites_used;
  impl_->core.handle_gps(s);
}

void FlightAdapter::on_rc_override(const std::array<uint16_t, 8>& channels_us, uint64_t now_us) {
  impl_->sticks = flight::sticks_from_rc_override(channels_us, now_us, impl_->sticks);
  impl_->core.handle_sticks(impl_->sticks);
}

void FlightAdapter::on_sticks(double roll, double pitch, double yaw, double throttle, uint64_t now_us) {
  flight::StickInput s;
  s.time_us = now_us;
  s.roll = roll;
  s.pitch = pitch;
  s.yaw = yaw;
  s.throttle = throttle;
  impl_->sticks = s;
  impl_->core.handle_sticks(s);
}

CommandResult FlightAdapter::arm(bool force, uint64_t) {
  if (const auto failure = calibration_failure(); !force && !failure.empty()) {
    impl_->said.push_back({Severity::Error, failure});
    return {mavlink::MavResult::Denied, failure};
  }
  return reply(impl_->core.arm(force));
}

std::string FlightAdapter::calibration_failure() const {
  struct Check {
    const char* param;
    uint32_t device_id;
    const char* sensor;
  };
  static constexpr Check kChecks[] = {{"CAL_ACC0_ID", kDeviceIdImu, "Accel 0"},
                                      {"CAL_GYRO0_ID", kDeviceIdImu, "Gyro 0"},
                                      {"CAL_MAG0_ID", kDeviceIdMag, "Compass 0"}};
  for (const auto& c : kChecks) {
    const auto* p = params_.get(c.param);
    if (p != nullptr && p->as_double() != static_cast<double>(c.device_id))
      return std::string("Preflight Fail: ") + c.sensor + " uncalibrated";
  }
  return "";
}

std::string FlightAdapter::commander_check() const {
  const auto s = state();
  return s.ready_to_arm ? "Preflight check: OK\n" : s.not_ready_reason + "\nPreflight check: FAILED\n";
}
CommandResult FlightAdapter::disarm(bool force, uint64_t) { return reply(impl_->core.disarm(force)); }
CommandResult FlightAdapter::land(uint64_t) { return reply(impl_->core.land()); }

CommandResult FlightAdapter::takeoff(double altitude_amsl_m, uint64_t) {
  flight::TakeoffRequest r;
  r.altitude_m = altitude_amsl_m;  // NaN: MIS_TAKEOFF_ALT above home
  return reply(impl_->core.takeoff(r));
}

CommandResult FlightAdapter::set_mode(uint8_t main_mode, uint8_t sub_mode, uint64_t) {
  const auto mode = flight::flight_mode_from_px4((static_cast<uint32_t>(main_mode) << 16) | (static_cast<uint32_t>(sub_mode) << 24));
  if (!mode) {
    const std::string why = "mode not available on hitl target (Position, Hold, Takeoff, Land)";
    impl_->said.push_back({Severity::Error, why});
    return {mavlink::MavResult::Unsupported, why};
  }
  return reply(impl_->core.set_mode(*mode));
}

std::array<double, 4> FlightAdapter::step(uint64_t now_us) {
  impl_->core.step(now_us);
  return impl_->core.actuators().u;
}

FlightState FlightAdapter::state() const {
  const auto& core = impl_->core;
  const auto& e = core.estimate();
  const auto status = core.estimator_status();
  const auto ready = core.preflight_check();
  FlightState s;
  s.armed = core.armed();
  s.custom_mode = core.custom_mode();
  s.base_mode = core.base_mode();
  s.mode_name = flight::to_string(core.mode());
  s.landed = static_cast<mavlink::MavLandedState>(core.landed_state());
  const std::string calibration = calibration_failure();
  s.ready_to_arm = ready.ready && calibration.empty();
  s.not_ready_reason = calibration.empty() ? ready.reason : calibration;
  s.attitude_valid = e.attitude_valid;
  s.local_valid = e.xy_valid && e.z_valid;
  s.global_valid = e.global_valid;
  s.home_set = core.home().valid;
  s.q_FRD_to_NED = {e.q_FRD_to_NED.w(), e.q_FRD_to_NED.x(), e.q_FRD_to_NED.y(), e.q_FRD_to_NED.z()};
  s.roll_rad = e.roll_rad;
  s.pitch_rad = e.pitch_rad;
  s.yaw_rad = e.yaw_rad;
  s.w_FRD_rad_s = {e.w_FRD_rad_s.x(), e.w_FRD_rad_s.y(), e.w_FRD_rad_s.z()};
  s.p_NED_m = {e.p_NED_m.x(), e.p_NED_m.y(), e.p_NED_m.z()};
  s.v_NED_m_s = {e.v_NED_m_s.x(), e.v_NED_m_s.y(), e.v_NED_m_s.z()};
  s.lat_deg = e.lat_deg;
  s.lon_deg = e.lon_deg;
  s.alt_msl_m = e.alt_msl_m;
  s.home_lat_deg = core.home().lat_deg;
  s.home_lon_deg = core.home().lon_deg;
  s.home_alt_msl_m = core.home().alt_msl_m;
  s.estimator_flags = status.flags;
  s.vel_ratio = status.vel_ratio;
  s.pos_horiz_ratio = status.pos_horiz_ratio;
  s.pos_vert_ratio = status.pos_vert_ratio;
  s.mag_ratio = status.mag_ratio;
  s.pos_horiz_accuracy_m = status.pos_horiz_accuracy_m;
  s.pos_vert_accuracy_m = status.pos_vert_accuracy_m;
  s.motor_commands = core.actuators().u;
  return s;
}

std::vector<flight::StatusMessage> FlightAdapter::take_messages() {
  std::vector<flight::StatusMessage> out = std::move(impl_->said);
  impl_->said.clear();
  for (auto& m : impl_->core.take_messages()) out.push_back(std::move(m));
  return out;
}

std::string FlightAdapter::commander_status() const {
  std::string out;
  for (const auto& l : impl_->core.commander_status_lines()) out += l + "\n";
  return out;
}

std::string FlightAdapter::ekf2_status() const {
  std::string out;
  for (const auto& l : impl_->core.ekf2_status_lines()) out += l + "\n";
  return out;
}

}  // namespace hitl::target
