#include "emulator/flight/estimator.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace hitl::flight {
namespace {

constexpr double kAlignTime_s = 4.0;          // fast-gain levelling and gyro bias settle in ~4 s
constexpr double kGpsChecksBeforeOrigin_s = 1.0;
constexpr double kGpsPosResetAfter_s = 5.0;   // continuous rejection -> reset to GPS
constexpr int kBaroRefSamples = 10;           // 1 s at 10 Hz
constexpr double kAccelClip_m_s2 = 150.0;     // ~16 g full scale
constexpr double kMotionAccelBaseline_s = 0.5;
constexpr double kPreflightTestRatioMax = 0.5;  // PX4 v1.16 EKF2: kMinTestRatioPreflight

double seconds(std::uint64_t later_us, std::uint64_t earlier_us) {
  return later_us >= earlier_us ? static_cast<double>(later_us - earlier_us) * 1e-6 : 0.0;
}

}  // namespace

double Estimator::age_s(std::uint64_t t_us) const { return seconds(now_us_, t_us); }
bool Estimator::recent(std::uint64_t t_us, double window_s) const { return age_s(t_us) <= window_s; }

void Estimator::handle_imu(const ImuSample& sample) {
  const double dt_s = imu_seen_ ? std::clamp(seconds(sample.time_us, last_imu_us_), 1e-4, 0.05) : 0.004;
  imu_seen_ = true;
  last_imu_us_ = sample.time_us;
  now_us_ = std::max(now_us_, sample.time_us);
  last_accel_FRD_m_s2_ = sample.accel_FRD_m_s2;
  have_accel_ = true;
  if (sample.accel_FRD_m_s2.cwiseAbs().maxCoeff() > kAccelClip_m_s2) {
    clip_seen_ = true;
    last_clip_us_ = sample.time_us;
  }
  if (!attitude_.initialized()) return;  // waits for the first magnetometer sample

  const double align = armed_ ? 1.0 : static_cast<double>(params_.HITL_ATT_ALIGN);
  AttitudeGains gains;
  gains.w_acc = params_.ATT_W_ACC * align;
  gains.w_mag = params_.ATT_W_MAG * align;
  gains.w_gyro_bias = params_.ATT_W_GYRO_BIAS * align;
  gains.bias_max_rad_s = params_.ATT_BIAS_MAX;
  if (params_.HITL_MAG_INCL > -90.0f) gains.inclination_rad = params_.HITL_MAG_INCL * kDegToRad;
  const bool compensate = armed_ && params_.ATT_ACC_COMP != 0 && recent(last_gps_fused_us_, 0.5);
  attitude_.update(sample.gyro_FRD_rad_s, sample.accel_FRD_m_s2,
                   compensate ? a_motion_NED_m_s2_ : Eigen::Vector3d::Zero(), dt_s, gains);

  // Specific force to NED, gravity removed: the kinematic acceleration (plus bias).
  const Eigen::Vector3d a_NED_m_s2 =
      attitude_.q_FRD_to_NED() * sample.accel_FRD_m_s2 + Eigen::Vector3d(0.0, 0.0, kGravity_m_s2);
  const double q_acc = params_.EKF2_ACC_NOISE, q_bias = params_.EKF2_ACC_B_NOISE;
  if (projection_.valid()) {
    axis_[0].predict(a_NED_m_s2.x(), dt_s, q_acc, q_bias);
    axis_[1].predict(a_NED_m_s2.y(), dt_s, q_acc, q_bias);
  }
  if (z_initialized_) axis_[2].predict(a_NED_m_s2.z(), dt_s, q_acc, q_bias);
  publish();
  const double alpha = dt_s / (0.02 + dt_s);
  const Eigen::Vector3d bias(axis_[0].bias(), axis_[1].bias(), axis_[2].bias());
  a_NED_filtered_m_s2_ += alpha * ((a_NED_m_s2 - bias) - a_NED_filtered_m_s2_);
  estimate_.a_NED_m_s2 = a_NED_filtered_m_s2_;
}

void Estimator::handle_mag(const MagSample& sample) {
  mag_seen_ = true;
  last_mag_us_ = sample.time_us;
  now_us_ = std::max(now_us_, sample.time_us);
  const double declination_rad = params_.EKF2_MAG_DECL * kDegToRad;
  if (!attitude_.initialized()) {
    if (!have_accel_) return;
    attitude_.initialize(last_accel_FRD_m_s2_, sample.mag_FRD_gauss, declination_rad);
    attitude_init_us_ = sample.time_us;
    return;
  }
  attitude_.set_mag(sample.mag_FRD_gauss, declination_rad);
  const double innov = attitude_.mag_heading_innovation_rad();
  const double gate = params_.EKF2_MAG_GATE * params_.EKF2_HEAD_NOISE;
  mag_ratio_ = innov * innov / (gate * gate);
}

void Estimator::handle_baro(const BaroSample& sample) {
  baro_seen_ = true;
  last_baro_us_ = sample.time_us;
  now_us_ = std::max(now_us_, sample.time_us);
  const double h_m = isa_altitude_m(sample.pressure_Pa);
  if (!z_initialized_) {
    baro_ref_sum_m_ += h_m;
    if (++baro_ref_count_ < kBaroRefSamples) return;
    baro_ref_m_ = baro_ref_sum_m_ / baro_ref_count_;
    const double noise = params_.EKF2_BARO_NOISE;
    axis_[2].reset(-(h_m - baro_ref_m_), 0.0, noise * noise, 0.25, 0.1 * 0.1);
    z_initialized_ = true;
    return;
  }
  const double noise = params_.EKF2_BARO_NOISE;
  const Innovation r = axis_[2].fuse_position(-(h_m - baro_ref_m_), noise * noise, params_.EKF2_BARO_GATE);
  pos_vert_ratio_ = r.test_ratio;
}

void Estimator::update_motion_acceleration(const GpsSample& sample) {
  // Velocity difference over >= 0.5 s: the GPS velocity noise differentiated over one 33 ms sample
  // would be ~4 m/s^2; over 0.5 s it is ~0.3 m/s^2.
  gps_velocity_history_.emplace_back(sample.time_us, sample.v_NED_m_s);
  while (gps_velocity_history_.size() > 2 &&
         seconds(sample.time_us, gps_velocity_history_[1].first) >= kMotionAccelBaseline_s) {
    gps_velocity_history_.pop_front();
  }
  const auto& [t_old_us, v_old] = gps_velocity_history_.front();
  const double span_s = seconds(sample.time_us, t_old_us);
  if (span_s >= 0.5 * kMotionAccelBaseline_s) a_motion_NED_m_s2_ = (sample.v_NED_m_s - v_old) / span_s;
}

void Estimator::handle_gps(const GpsSample& sample) {
  gps_seen_ = true;
  last_gps_us_ = sample.time_us;
  last_gps_ = sample;
  now_us_ = std::max(now_us_, sample.time_us);
  const bool quality = sample.fix_type >= 3 && sample.eph_m <= params_.EKF2_REQ_EPH &&
                       sample.satellites >= params_.EKF2_REQ_NSATS;
  if (quality && !gps_checks_passing_) gps_checks_pass_since_us_ = sample.time_us;
  gps_checks_passing_ = quality;
  if (sample.fix_type < 3) return;
  update_motion_acceleration(sample);

  if (!projection_.valid()) {
    if (!quality || !z_initialized_ || !attitude_.initialized()) return;
    if (seconds(sample.time_us, gps_checks_pass_since_us_) < kGpsChecksBeforeOrigin_s) return;
    projection_ = LocalProjection(sample.lat_deg, sample.lon_deg);
    origin_alt_msl_m_ = sample.alt_msl_m + axis_[2].p();  // alt_msl = origin_alt - p_D
    const double p_var = std::pow(std::max<double>(params_.EKF2_GPS_P_NOISE, sample.eph_m), 2);
    const double v_var = std::pow(params_.EKF2_GPS_V_NOISE, 2);
    axis_[0].reset(0.0, sample.v_NED_m_s.x(), p_var, v_var, 0.1 * 0.1);
    axis_[1].reset(0.0, sample.v_NED_m_s.y(), p_var, v_var, 0.1 * 0.1);
    gps_fusing_since_us_ = sample.time_us;
    last_gps_fused_us_ = sample.time_us;
    return;
  }

  const Eigen::Vector2d p_NE_m = projection_.to_NE_m(sample.lat_deg, sample.lon_deg);
  const double p_noise_var = std::pow(std::max<double>(params_.EKF2_GPS_P_NOISE, sample.eph_m), 2);
  const double v_noise_var = std::pow(params_.EKF2_GPS_V_NOISE, 2);
  const double p_gate = params_.EKF2_GPS_P_GATE, v_gate = params_.EKF2_GPS_V_GATE;
  Innovation v[3];
  for (int i = 0; i < 3; ++i) {
    if (i == 2 && !z_initialized_) continue;
    v[i] = axis_[i].fuse_velocity(sample.v_NED_m_s[i], v_noise_var, v_gate);
  }
  vel_ratio_ = std::max({v[0].test_ratio, v[1].test_ratio, v[2].test_ratio});
  const Innovation pn = axis_[0].fuse_position(p_NE_m.x(), p_noise_var, p_gate);
  const Innovation pe = axis_[1].fuse_position(p_NE_m.y(), p_noise_var, p_gate);
  pos_horiz_ratio_ = std::max(pn.test_ratio, pe.test_ratio);
  if (pn.fused && pe.fused) {
    gps_rejecting_ = false;
    last_gps_fused_us_ = sample.time_us;
  } else {
    last_gps_rejected_us_ = sample.time_us;
    if (!gps_rejecting_) gps_pos_rejected_since_us_ = sample.time_us;
    gps_rejecting_ = true;
    if (seconds(sample.time_us, gps_pos_rejected_since_us_) > kGpsPosResetAfter_s) {
      axis_[0].reset_position(p_NE_m.x(), p_noise_var);
      axis_[1].reset_position(p_NE_m.y(), p_noise_var);
      gps_rejecting_ = false;
      last_gps_fused_us_ = sample.time_us;
    }
  }
}

void Estimator::publish() {
  Estimate& e = estimate_;
  e.time_us = last_imu_us_;
  e.q_FRD_to_NED = attitude_.q_FRD_to_NED();
  const Eigen::Matrix3d R = e.q_FRD_to_NED.toRotationMatrix();
  e.roll_rad = std::atan2(R(2, 1), R(2, 2));
  e.pitch_rad = std::asin(std::clamp(-R(2, 0), -1.0, 1.0));
  e.yaw_rad = std::atan2(R(1, 0), R(0, 0));
  e.w_FRD_rad_s = attitude_.rates_FRD_rad_s();
  e.gyro_bias_FRD_rad_s = attitude_.gyro_bias_FRD_rad_s();
  e.attitude_valid = attitude_.initialized() && seconds(now_us_, attitude_init_us_) >= kAlignTime_s;
  const bool xy = projection_.valid();
  e.p_NED_m = {xy ? axis_[0].p() : 0.0, xy ? axis_[1].p() : 0.0, z_initialized_ ? axis_[2].p() : 0.0};
  e.v_NED_m_s = {xy ? axis_[0].v() : 0.0, xy ? axis_[1].v() : 0.0, z_initialized_ ? axis_[2].v() : 0.0};
  e.accel_bias_NED_m_s2 = {axis_[0].bias(), axis_[1].bias(), axis_[2].bias()};
  e.xy_valid = xy && recent(last_gps_fused_us_, 1.0);
  e.v_xy_valid = e.xy_valid;
  e.z_valid = z_initialized_ && recent(last_baro_us_, 1.0);
  e.v_z_valid = e.z_valid;
  e.global_valid = xy;
  e.eph_m = xy ? std::sqrt(axis_[0].p_var() + axis_[1].p_var()) : 99.0;
  e.epv_m = z_initialized_ ? std::sqrt(axis_[2].p_var()) : 99.0;
  e.evh_m_s = xy ? std::sqrt(axis_[0].v_var() + axis_[1].v_var()) : 99.0;
  e.evv_m_s = z_initialized_ ? std::sqrt(axis_[2].v_var()) : 99.0;
  if (xy) {
    const LatLon ll = projection_.to_lat_lon(e.p_NED_m.head<2>());
    e.lat_deg = ll.lat_deg;
    e.lon_deg = ll.lon_deg;
    e.alt_msl_m = origin_alt_msl_m_ - e.p_NED_m.z();
    e.origin_lat_deg = projection_.origin().lat_deg;
    e.origin_lon_deg = projection_.origin().lon_deg;
    e.origin_alt_msl_m = origin_alt_msl_m_;
  }
}

EstimatorStatus Estimator::status() const {
  using namespace estimator_flags;
  EstimatorStatus s;
  s.time_us = now_us_;
  const Estimate& e = estimate_;
  if (e.attitude_valid) s.flags |= kAttitude;
  if (e.v_xy_valid) s.flags |= kVelocityHoriz | kPosHorizRel;
  if (e.v_z_valid) s.flags |= kVelocityVert | kPosVertAbs;
  const bool gps_long_enough =
      projection_.valid() && seconds(now_us_, gps_fusing_since_us_) >= params_.EKF2_REQ_GPS_H;
  if (e.xy_valid && gps_long_enough && pos_horiz_ratio_ < 1.0) s.flags |= kPosHorizAbs;
  if (e.attitude_valid && !e.xy_valid) s.flags |= kConstPosMode;
  const bool gps_ok_now = gps_seen_ && recent(last_gps_us_, 1.0) && gps_checks_passing_;
  if (gps_ok_now) s.flags |= kPredPosHorizRel | kPredPosHorizAbs;
  if (last_gps_rejected_us_ != 0 && recent(last_gps_rejected_us_, 1.0)) s.flags |= kGpsGlitch;
  if (clip_seen_ && recent(last_clip_us_, 1.0)) s.flags |= kAccelError;
  s.vel_ratio = vel_ratio_;
  s.pos_horiz_ratio = pos_horiz_ratio_;
  s.pos_vert_ratio = pos_vert_ratio_;
  s.mag_ratio = mag_ratio_;
  s.pos_horiz_accuracy_m = e.eph_m;
  s.pos_vert_accuracy_m = e.epv_m;
  return s;
}

Readiness Estimator::preflight_check() const {
  const auto fail = [](const char* what) { return Readiness{false, std::string("Preflight Fail: ") + what}; };
  if (!imu_seen_ || !recent(last_imu_us_, 0.5)) return fail("ekf2 missing data");
  if (!mag_seen_ || !recent(last_mag_us_, 1.0)) return fail("Compass Sensor 0 missing");
  if (!baro_seen_ || !recent(last_baro_us_, 1.0)) return fail("Barometer 0 missing");
  if (!estimate_.attitude_valid || !z_initialized_) return fail("ekf2 not aligned");
  if (!gps_seen_ || !recent(last_gps_us_, 1.0) || last_gps_.fix_type < 3) return fail("no GPS fix");
  if (last_gps_.satellites < params_.EKF2_REQ_NSATS) return fail("not enough GPS Satellites");
  if (last_gps_.eph_m > params_.EKF2_REQ_EPH) return fail("GPS Horizontal Pos Error too high");
  const EstimatorStatus s = status();
  if ((s.flags & estimator_flags::kPosHorizAbs) == 0) return fail("ekf2 GPS checks pending");
  // PX4 v1.16: EKF2 flags a preflight innovation failure above a fixed test ratio (PR #23411
  // removed the COM_ARM_EKF_* limits); commander refuses to arm on those flags.
  if (s.pos_horiz_ratio > kPreflightTestRatioMax) return fail("Position estimate error");
  if (s.vel_ratio > kPreflightTestRatioMax) return fail("Velocity estimate error");
  if (s.pos_vert_ratio > kPreflightTestRatioMax) return fail("Height estimate error");
  if (s.mag_ratio > kPreflightTestRatioMax) return fail("Yaw estimate error");
  if ((s.flags & estimator_flags::kAccelError) != 0) return fail("Accel clipping");
  return {true, ""};
}

std::vector<std::string> Estimator::status_lines() const {
  const Estimate& e = estimate_;
  const EstimatorStatus s = status();
  std::vector<std::string> lines;
  char buf[200];
  std::snprintf(buf, sizeof(buf), "ekf2: attitude %s, flags 0x%04x, gps %s, origin %s",
                e.attitude_valid ? "aligned" : "aligning", static_cast<unsigned>(s.flags),
                gps_checks_passing_ ? "checks passing" : "checks failing", projection_.valid() ? "set" : "not set");
  lines.emplace_back(buf);
  std::snprintf(buf, sizeof(buf), "  roll %.2f pitch %.2f yaw %.2f deg, gyro bias %.4f %.4f %.4f rad/s",
                e.roll_rad / kDegToRad, e.pitch_rad / kDegToRad, e.yaw_rad / kDegToRad, e.gyro_bias_FRD_rad_s.x(),
                e.gyro_bias_FRD_rad_s.y(), e.gyro_bias_FRD_rad_s.z());
  lines.emplace_back(buf);
  std::snprintf(buf, sizeof(buf), "  pos NED %.2f %.2f %.2f m, vel NED %.2f %.2f %.2f m/s", e.p_NED_m.x(),
                e.p_NED_m.y(), e.p_NED_m.z(), e.v_NED_m_s.x(), e.v_NED_m_s.y(), e.v_NED_m_s.z());
  lines.emplace_back(buf);
  std::snprintf(buf, sizeof(buf), "  test ratios: vel %.3f pos %.3f hgt %.3f mag %.3f; eph %.2f m epv %.2f m",
                s.vel_ratio, s.pos_horiz_ratio, s.pos_vert_ratio, s.mag_ratio, e.eph_m, e.epv_m);
  lines.emplace_back(buf);
  const Readiness r = preflight_check();
  lines.push_back(r.ready ? "  preflight: pass" : "  preflight: " + r.reason);
  return lines;
}

}  // namespace hitl::flight
