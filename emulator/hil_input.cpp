#include "emulator/hil_input.h"

#include <algorithm>

#include "base/contract/data_rates.h"

namespace hitl::target {

HilSensorInput hil_sensor_input(const mavlink::msg::HilSensor& m) {
  HilSensorInput in;
  in.time_usec = m.time_usec;
  in.accel_FRD_m_s2[0] = m.xacc; in.accel_FRD_m_s2[1] = m.yacc; in.accel_FRD_m_s2[2] = m.zacc;
  in.gyro_FRD_rad_s[0] = m.xgyro; in.gyro_FRD_rad_s[1] = m.ygyro; in.gyro_FRD_rad_s[2] = m.zgyro;
  in.mag_FRD_gauss[0] = m.xmag; in.mag_FRD_gauss[1] = m.ymag; in.mag_FRD_gauss[2] = m.zmag;
  in.abs_pressure_hPa = m.abs_pressure;
  in.diff_pressure_hPa = m.diff_pressure;
  in.pressure_alt_m = m.pressure_alt;
  in.temperature_degC = m.temperature;
  in.fields_updated = m.fields_updated;
  in.id = m.id;
  return in;
}

HilGpsInput hil_gps_input(const mavlink::msg::HilGps& m) {
  HilGpsInput in;
  in.time_usec = m.time_usec;
  in.fix_type = m.fix_type;
  in.lat_degE7 = m.lat;
  in.lon_degE7 = m.lon;
  in.alt_mm = m.alt;
  in.eph_cm = m.eph;
  in.epv_cm = m.epv;
  in.vel_cm_s = m.vel;
  in.vn_cm_s = m.vn;
  in.ve_cm_s = m.ve;
  in.vd_cm_s = m.vd;
  in.cog_cdeg = m.cog;
  in.satellites_visible = m.satellites_visible;
  in.id = m.id;
  return in;
}

uint64_t LockstepClock::on_hil_sensor(uint64_t time_usec, uint64_t now_us) {
  if (!started_ || time_usec < last_sensor_time_us_) {
    if (started_) {
      ++restarts_;
      new_session_text_ = "lockstep: a new simulator session (HIL_SENSOR.time_usec went back from " +
                          std::to_string(last_sensor_time_us_ / 1000) + " ms to " + std::to_string(time_usec / 1000) +
                          " ms); the board's clock carries on from " + std::to_string(now_us / 1000) + " ms";
    }
    started_ = true;
    origin_us_ = time_usec;
    base_us_ = now_us;
  }
  last_sensor_time_us_ = time_usec;
  return std::max(now_us, base_us_ + (time_usec - origin_us_) + kHilImuPublishPeriod_us);
}

std::optional<std::string> LockstepClock::take_new_session_text() {
  auto text = std::move(new_session_text_);
  new_session_text_.reset();
  return text;
}

}  // namespace hitl::target
