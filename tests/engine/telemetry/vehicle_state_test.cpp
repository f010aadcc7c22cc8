// The dashboard's telemetry: health grades, stream meters, the dsp_hitl meter, the vehicle's
// telemetry folded from frames, the estimate against the truth, PX4 mode names, EKF flags.
#include <gtest/gtest.h>

#include <cmath>

#include "base/mavlink/enums.h"
#include "base/mavlink/frame_encoder.h"
#include "base/mavlink/frame_parser.h"
#include "base/mavlink/messages.h"
#include "engine/telemetry/dsp_hitl_meter.h"
#include "engine/telemetry/estimate_error.h"
#include "engine/telemetry/estimator_flags.h"
#include "engine/telemetry/health.h"
#include "engine/telemetry/px4_mode.h"
#include "engine/telemetry/stream_meter.h"
#include "engine/telemetry/vehicle_telemetry.h"

namespace hitl::telemetry {
namespace {

namespace msg = mavlink::msg;

TEST(Health, FiveAndTwentyPercent) {
  EXPECT_EQ(rate_health(250, 250, false), Health::Good);
  EXPECT_EQ(rate_health(250, 237.5, false), Health::Good);     // -5 %
  EXPECT_EQ(rate_health(250, 262.5, false), Health::Good);     // +5 %
  EXPECT_EQ(rate_health(250, 237.0, false), Health::Degraded);
  EXPECT_EQ(rate_health(250, 200.0, false), Health::Degraded);  // -20 %
  EXPECT_EQ(rate_health(250, 199.0, false), Health::Bad);
  EXPECT_EQ(rate_health(250, 400.0, false), Health::Bad);       // too fast is wrong too
  EXPECT_EQ(rate_health(250, 250, true), Health::Bad);          // stale
  EXPECT_EQ(rate_health(250, NAN, false), Health::Bad);
  EXPECT_EQ(rate_health(0, 12.0, false), Health::Good);         // nothing expected
  EXPECT_EQ(worse(Health::Good, Health::Degraded), Health::Degraded);
  EXPECT_EQ(worse(Health::Bad, Health::Degraded), Health::Bad);
  EXPECT_STREQ(to_string(Health::Degraded), "warn");
}

TEST(StreamMeter, RateJitterAndGap) {
  StreamMeter m;
  double t = 10.0;
  for (int i = 0; i < 250; ++i) {  // alternating 3 and 5 ms: 250 Hz, intervals' std 1 ms
    m.arrival(t);
    t += (i % 2 == 0) ? 0.003 : 0.005;
  }
  m.roll(10.0 + 1.0);
  const auto s = m.stats(11.0);
  EXPECT_EQ(s.count, 250u);
  EXPECT_NEAR(s.rate_hz, 250.0, 0.5);
  EXPECT_NEAR(s.jitter_ms, 1.0, 0.01);
  EXPECT_NEAR(s.max_gap_ms, 5.0, 1e-6);
  EXPECT_NEAR(s.since_last_s, 11.0 - (t - 0.005), 0.004);
  // The next window is empty: rate 0, and the last arrival gets older.
  m.roll(12.0);
  EXPECT_EQ(m.stats(12.0).rate_hz, 0.0);
  EXPECT_EQ(m.stats(12.0).count, 250u);
  EXPECT_LT(StreamMeter().stats(1.0).since_last_s, 0);  // never
}

target::DspHitlStatusReport report(uint64_t imu, uint64_t baro, bool running = true) {
  target::DspHitlStatusReport r;
  r.running = running;
  r.counters.hil_imu_received = imu;
  r.counters.imu_published = imu;
  r.counters.hil_mag_baro_received = imu / 2;
  r.counters.mag_published = imu / 5;
  r.counters.baro_published = baro;
  return r;
}

TEST(DspHitlMeter, RatesFromDeltasAndStalls) {
  DspHitlMeter m({250, 250, 100, 50, 10});
  EXPECT_EQ(m.view(0).state, DspHitlView::State::Waiting);
  m.on_report(report(1000, 40), 100.0);
  auto v = m.view(100.2);
  EXPECT_EQ(v.state, DspHitlView::State::Available);
  EXPECT_FALSE(v.counters[0].rate_hz.has_value());  // one poll: no rate yet
  EXPECT_STREQ(v.counters[0].name, "HIL sensor_imu received");
  m.on_report(report(1250, 40), 101.0);
  v = m.view(101.5);
  ASSERT_TRUE(v.counters[0].rate_hz.has_value());
  EXPECT_NEAR(*v.counters[0].rate_hz, 250.0, 1e-9);
  EXPECT_NEAR(*v.counters[2].rate_hz, 125.0, 1e-9);
  EXPECT_FALSE(v.counters[0].stalled);
  EXPECT_TRUE(v.counters[4].stalled);  // BARO did not move
  EXPECT_EQ(v.counters[4].expected_hz, 10.0);
  EXPECT_NEAR(v.age_s, 0.5, 1e-9);
  // Over several polls a slow counter's one-count jitter averages out: 10, 11, 9, 10 in 4 s.
  DspHitlMeter w({250, 250, 100, 50, 10});
  uint64_t baro = 0;
  const uint64_t steps[] = {0, 10, 11, 9, 10};
  for (int k = 0; k < 5; ++k) w.on_report(report(250u * static_cast<unsigned>(k), baro += steps[k]), 200.0 + k);
  EXPECT_NEAR(*w.view(204.0).counters[4].rate_hz, 10.0, 1e-9);
  EXPECT_NEAR(*w.view(204.0).counters[0].rate_hz, 250.0, 1e-9);
  // A counter that went back (dsp_hitl restarted): no rate, no stall mark.
  m.on_report(report(10, 1), 102.0);
  v = m.view(102.0);
  EXPECT_FALSE(v.counters[0].rate_hz.has_value());
  EXPECT_FALSE(v.counters[4].stalled);
  // No dsp_hitl on the board: the reason replaces the counters.
  m.on_unavailable("no dsp_hitl on this board (nsh: qshell: command not found)");
  v = m.view(103.0);
  EXPECT_EQ(v.state, DspHitlView::State::Unavailable);
  EXPECT_NE(v.reason.find("no dsp_hitl"), std::string::npos);
}

/// Encodes a message and parses it back into a Frame, as it would arrive.
template <class M>
mavlink::Frame frame_of(const M& message, uint8_t sysid = 1) {
  static const auto set = mavlink::MessageSet::compiled();
  mavlink::FrameEncoder encoder(sysid, 1);
  mavlink::FrameBuffer buf;
  const std::size_t n = encoder.encode(message, buf);
  mavlink::FrameParser parser(set);
  mavlink::Frame out;
  parser.parse_datagram({buf.data(), n}, [&](const mavlink::Frame& f) { out = f; });
  return out;
}

TEST(DspHitlMeter, TheSpecsRatesForWhoeverDoesNotKnowTheSimulator) {
  // hitl doctor and hitl bridge's dashboard: the spec's table, not a vehicle model's defaults.
  const DspHitlExpectedRates r = spec_dsp_hitl_expected_rates();
  EXPECT_DOUBLE_EQ(r.imu_received_hz, 250);
  EXPECT_DOUBLE_EQ(r.imu_published_hz, 250);
  EXPECT_DOUBLE_EQ(r.mag_baro_received_hz, 100);
  EXPECT_DOUBLE_EQ(r.mag_published_hz, 50);
  EXPECT_DOUBLE_EQ(r.baro_published_hz, 10);
}

TEST(VehicleTelemetry, FoldsTheAutopilotsMessages) {
  VehicleTelemetryTracker t;
  EXPECT_FALSE(t.state().heartbeat);
  msg::Heartbeat hb;
  hb.autopilot = static_cast<uint8_t>(mavlink::MavAutopilot::Px4);
  hb.base_mode = mavlink::mode_flag::kCustomModeEnabled | mavlink::mode_flag::kSafetyArmed;
  hb.custom_mode = 3u << 16;
  t.on_frame(frame_of(hb), 1.0);
  EXPECT_TRUE(t.state().armed);
  EXPECT_EQ(t.state().mode, "Position");
  // A ground station's HEARTBEAT (autopilot invalid) changes nothing.
  msg::Heartbeat gcs;
  gcs.autopilot = static_cast<uint8_t>(mavlink::MavAutopilot::Invalid);
  t.on_frame(frame_of(gcs, 255), 1.1);
  EXPECT_TRUE(t.state().armed);

  msg::ExtendedSysState ess;
  ess.landed_state = static_cast<uint8_t>(mavlink::MavLandedState::InAir);
  t.on_frame(frame_of(ess), 1.2);
  EXPECT_EQ(*t.state().landed, "in air");
  EXPECT_TRUE(t.state().in_air);

  msg::SysStatus ss;
  ss.onboard_control_sensors_present = mavlink::sys_status::kPrearmCheck;
  ss.onboard_control_sensors_health = mavlink::sys_status::kPrearmCheck;
  ss.voltage_battery = 12000;
  ss.current_battery = -1;
  ss.battery_remaining = 50;
  t.on_frame(frame_of(ss), 1.3);
  EXPECT_TRUE(*t.state().ready_to_arm);
  EXPECT_DOUBLE_EQ(*t.state().battery_V, 12.0);
  EXPECT_FALSE(t.state().battery_A.has_value());  // -1: not measured

  msg::BatteryStatus bs;  // wins over SYS_STATUS from now on
  bs.voltages.fill(UINT16_MAX);
  for (int c = 0; c < 4; ++c) bs.voltages[static_cast<std::size_t>(c)] = 4200;
  bs.current_battery = 500;
  bs.battery_remaining = 100;
  t.on_frame(frame_of(bs), 1.4);
  t.on_frame(frame_of(ss), 1.5);
  EXPECT_DOUBLE_EQ(*t.state().battery_V, 16.8);
  EXPECT_DOUBLE_EQ(*t.state().battery_A, 5.0);
  EXPECT_DOUBLE_EQ(*t.state().battery_remaining_pct, 100.0);

  msg::EstimatorStatus es;
  es.flags = mavlink::estimator_status::kAttitude | mavlink::estimator_status::kGpsGlitch;
  es.vel_ratio = 0.3f;
  t.on_frame(frame_of(es), 1.6);
  ASSERT_TRUE(t.state().estimator.has_value());
  EXPECT_EQ(t.state().estimator->flags, es.flags);
  EXPECT_FLOAT_EQ(static_cast<float>(t.state().estimator->vel_ratio), 0.3f);

  msg::LocalPositionNed lp;
  lp.z = -2.5f;
  t.on_frame(frame_of(lp), 1.7);
  EXPECT_DOUBLE_EQ((*t.state().p_NED_m)[2], -2.5);
  EXPECT_DOUBLE_EQ(t.state().last_heard_s.at(msg::LocalPositionNed::kId), 1.7);
}

TEST(EstimateError, PositionAndAttitude) {
  EstimateErrorMeter m;
  TruthPose truth;
  truth.p_NED_m = {1.0, 2.0, -3.0};
  m.on_position({1.3, 2.4, -2.9}, truth);
  EXPECT_NEAR(m.error().horizontal_m, 0.5, 1e-9);
  EXPECT_NEAR(m.error().vertical_m, 0.1, 1e-9);
  m.on_position({NAN, 0, 0}, truth);  // from the network: ignored
  EXPECT_EQ(m.error().position_samples, 1u);
  // 90 degrees of yaw apart; a quaternion and its negative are the same attitude.
  const double h = std::sqrt(0.5);
  m.on_attitude({h, 0, 0, h}, truth);
  EXPECT_NEAR(m.error().attitude_deg, 90.0, 1e-6);
  m.on_attitude({-1, 0, 0, 0}, truth);
  EXPECT_NEAR(m.error().attitude_deg, 0.0, 1e-6);
  EXPECT_NEAR(m.error().attitude_rms_deg, std::sqrt(90.0 * 90.0 / 2), 1e-6);
  EXPECT_TRUE(std::isnan(attitude_difference_deg({0, 0, 0, 0}, truth.q_FRD_to_NED)));
}

TEST(Px4Mode, NamesLikeQGroundControl) {
  const uint8_t custom = mavlink::mode_flag::kCustomModeEnabled;
  EXPECT_EQ(px4_mode_name(custom, 3u << 16), "Position");
  EXPECT_EQ(px4_mode_name(custom, (4u << 16) | (3u << 24)), "Hold");
  EXPECT_EQ(px4_mode_name(custom, (4u << 16) | (2u << 24)), "Takeoff");
  EXPECT_EQ(px4_mode_name(custom, (4u << 16) | (6u << 24)), "Land");
  EXPECT_EQ(px4_mode_name(custom, 7u << 16), "Stabilized");
  EXPECT_EQ(px4_mode_name(custom, 0x00630000u), "custom 0x00630000");
  EXPECT_EQ(px4_mode_name(0, 3u << 16), "no custom mode");
}

TEST(EstimatorFlags, InWordsFaultsMarked) {
  const auto flags = estimator_flags(mavlink::estimator_status::kAttitude | mavlink::estimator_status::kGpsGlitch);
  ASSERT_EQ(flags.size(), 12u);
  EXPECT_STREQ(flags[0].word, "attitude");
  EXPECT_TRUE(flags[0].set);
  EXPECT_FALSE(flags[0].fault);
  EXPECT_FALSE(flags[1].set);
  EXPECT_STREQ(flags[10].word, "GPS glitch");
  EXPECT_TRUE(flags[10].set);
  EXPECT_TRUE(flags[10].fault);
}

}  // namespace
}  // namespace hitl::telemetry
