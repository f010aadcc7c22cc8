// Series extraction from a tlog written here frame by frame: the simulator's clock, what comes from
// whom, the tracking summary, events, and what a plain log lacks.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>

#include "base/contract/session_status.h"
#include "base/mavlink/enums.h"
#include "base/mavlink/frame_encoder.h"
#include "base/mavlink/messages.h"
#include "base/mavlink/text_field.h"
#include "engine/mavlink/tlog.h"
#include "engine/report/flight_log.h"
#include "engine/report/html.h"
#include "engine/report/plots.h"

namespace hitl::report {
namespace {
namespace msg = mavlink::msg;

class LogWriter {
 public:
  explicit LogWriter(const std::string& path) : writer_(mavlink::TlogWriter::open(path).value()) {}
  template <class M>
  void add(uint64_t wall_us, uint8_t sysid, uint8_t compid, const M& m) {
    auto& enc = encoders_.try_emplace(sysid * 256 + compid, sysid, compid).first->second;
    mavlink::FrameBuffer buf;
    const std::size_t n = enc.encode(m, buf);
    writer_.write(kEpoch_us + wall_us, {buf.data(), n});
  }
  void close() { writer_.flush(); }
  static constexpr uint64_t kEpoch_us = 1'700'000'000'000'000;

 private:
  mavlink::TlogWriter writer_;
  std::map<int, mavlink::FrameEncoder> encoders_;
};

msg::HilSensor sensor_at(uint64_t sim_us) {
  msg::HilSensor s;
  s.time_usec = sim_us;
  return s;
}

msg::NamedValueFloat named(std::string_view name, float v) {
  msg::NamedValueFloat m;
  mavlink::set_text(m.name, name);
  m.value = v;
  return m;
}

msg::NamedValueInt named_int(std::string_view name, int32_t v) {
  msg::NamedValueInt m;
  mavlink::set_text(m.name, name);
  m.value = v;
  return m;
}

msg::Heartbeat heartbeat(bool armed) {
  msg::Heartbeat hb;
  hb.type = 2;       // quadrotor
  hb.autopilot = 12;  // PX4
  hb.base_mode = static_cast<uint8_t>(1 | (armed ? mavlink::mode_flag::kSafetyArmed : 0));
  return hb;
}

TEST(FlightLog, TimesAreTheSimulatorsClockInterpolatedBetweenItsHilSensors) {
  // The simulator runs twice as fast as the wall clock: 4 ms of simulated time per 2 ms of wall.
  const std::string path = ::testing::TempDir() + "clock.tlog";
  {
    LogWriter w(path);
    for (uint64_t k = 0; k <= 100; ++k) {
      w.add(k * 2000, kSimulatorSystemId, 1, sensor_at(k * 4000));
      if (k != 50) continue;
      msg::LocalPositionNed p;
      p.z = -2.0F;
      w.add(101 * 1000, 1, 1, p);  // halfway between wall 100 ms and 102 ms: simulated 202 ms
    }
    w.close();
  }
  auto log = read_flight_log(path);
  ASSERT_TRUE(log) << log.error().message;
  EXPECT_TRUE(log->simulated_time);
  ASSERT_EQ(log->estimate.size(), 1u);
  EXPECT_NEAR(log->estimate.t_s[0], 0.202, 1e-9);
  EXPECT_DOUBLE_EQ(log->estimate.down_m[0], -2.0);
  EXPECT_NEAR(log->duration_s, 0.4, 1e-9);
  EXPECT_NEAR(log->wall_duration_s, 0.2, 1e-9);
  ASSERT_EQ(log->paths.size(), 1u);  // HIL_SENSOR only
  EXPECT_EQ(log->paths[0].name, "HIL_SENSOR");
  EXPECT_EQ(log->paths[0].count, 101u);
  EXPECT_NEAR(log->paths[0].mean_rate_hz, 250.0, 1e-6);  // per simulated second
}

TEST(FlightLog, TruthSetpointsAndTrackingErrorComeFromTheSimulatorAndThePilot) {
  const std::string path = ::testing::TempDir() + "flight.tlog";
  const std::vector<float> errors = {0.1F, 0.5F, 0.2F, 0.8F};
  {
    LogWriter w(path);
    for (uint64_t k = 0; k < 4; ++k) {
      const uint64_t t = k * 4000;
      w.add(t, kSimulatorSystemId, 1, sensor_at(t));
      msg::Odometry truth;
      truth.time_usec = t;
      truth.x = 1.0F * static_cast<float>(k);
      truth.q = {1, 0, 0, 0};
      truth.estimator_type = static_cast<uint8_t>(mavlink::MavEstimatorType::Mocap);
      w.add(t, kSimulatorSystemId, 1, truth);
      msg::Odometry vio = truth;  // VIO to the board: a data path, not the truth
      vio.estimator_type = static_cast<uint8_t>(mavlink::MavEstimatorType::Vio);
      w.add(t, kSimulatorSystemId, kVioComponentId, vio);
      msg::PositionTargetLocalNed sp;
      sp.y = 2.0F;
      w.add(t, kSimulatorSystemId, mavlink::kCompIdPathPlanner, sp);
      w.add(t, kSimulatorSystemId, mavlink::kCompIdPathPlanner, named(kTrackingErrorName, errors[k]));
      w.add(t, 1, 1, named(kTrackingErrorName, 9.0F));  // the vehicle's own value of that name: not the pilot's
      msg::HilActuatorControls a;
      a.controls[2] = 0.5F;
      w.add(t, 1, 1, a);
    }
    w.close();
  }
  auto log = read_flight_log(path);
  ASSERT_TRUE(log) << log.error().message;
  EXPECT_EQ(log->truth.size(), 4u);
  EXPECT_EQ(log->truth_attitude.size(), 4u);
  EXPECT_DOUBLE_EQ(log->truth.north_m[3], 3.0);
  EXPECT_EQ(log->setpoint.size(), 4u);
  EXPECT_DOUBLE_EQ(log->setpoint.east_m[0], 2.0);
  ASSERT_TRUE(log->tracking);
  EXPECT_EQ(log->tracking->samples, 4u);
  double sum_sq = 0;
  for (float e : errors) sum_sq += static_cast<double>(e) * e;
  EXPECT_DOUBLE_EQ(log->tracking->rms_m, std::sqrt(sum_sq / 4));
  EXPECT_DOUBLE_EQ(log->tracking->max_m, static_cast<double>(0.8F));
  EXPECT_EQ(log->motors[2].size(), 4u);
  EXPECT_DOUBLE_EQ(log->motors[2].value[0], 0.5);
  std::vector<std::string> names;
  for (const auto& p : log->paths) names.push_back(p.name);
  EXPECT_EQ(names, (std::vector<std::string>{"HIL_SENSOR", "ODOMETRY (VIO)", "HIL_ACTUATOR_CONTROLS"}));
}

TEST(FlightLog, APlainLogGivesWhatItHasAndSaysWhatItLacks) {
  // A ground station's log: a vehicle's HEARTBEAT, position, attitude and a STATUSTEXT; no simulator.
  const std::string path = ::testing::TempDir() + "plain.tlog";
  {
    LogWriter w(path);
    w.add(0, 1, 1, heartbeat(false));
    msg::Attitude att;
    att.roll = static_cast<float>(M_PI / 2);
    w.add(500'000, 1, 1, att);
    w.add(1'000'000, 1, 1, heartbeat(true));
    msg::Statustext st;
    st.severity = 4;  // warning
    mavlink::set_text(st.text, "Preflight Fail: ekf2 missing data");
    w.add(1'500'000, 1, 1, st);
    msg::LocalPositionNed p;
    w.add(2'000'000, 1, 1, p);
    w.close();
  }
  auto log = read_flight_log(path);
  ASSERT_TRUE(log) << log.error().message;
  EXPECT_FALSE(log->simulated_time);
  EXPECT_DOUBLE_EQ(log->estimate.t_s[0], 2.0);  // seconds since the first record
  EXPECT_NEAR(log->estimate_attitude.roll_deg[0], 90.0, 1e-4);
  EXPECT_EQ(log->truth.size(), 0u);
  EXPECT_FALSE(log->tracking);
  ASSERT_EQ(log->events.size(), 4u);  // disarmed + mode at the first HEARTBEAT, armed, the text
  EXPECT_EQ(log->events[0].text, "disarmed");
  EXPECT_EQ(log->events[2].text, "armed");
  EXPECT_DOUBLE_EQ(log->events[2].t_s, 1.0);
  EXPECT_EQ(log->events[3].text, "Preflight Fail: ekf2 missing data");
  EXPECT_EQ(log->events[3].severity, Severity::Warning);
  EXPECT_EQ(log->events[3].source, "system 1");
  auto lacks = [&](const std::string& start) {
    for (const auto& m : log->missing)
      if (m.rfind(start, 0) == 0) return true;
    return false;
  };
  EXPECT_TRUE(lacks("the simulator's clock"));
  EXPECT_TRUE(lacks("ground truth"));
  EXPECT_TRUE(lacks("setpoints"));
  EXPECT_TRUE(lacks("motor commands"));
  EXPECT_FALSE(lacks("the vehicle's position estimate"));
  EXPECT_TRUE(lacks("the loop latency (no hitl session status in this log"));
}

bool lacks_starting(const FlightLog& log, const std::string& start) {
  for (const auto& m : log.missing)
    if (m.rfind(start, 0) == 0) return true;
  return false;
}

/// 3 s of HIL_SENSOR at 250 Hz with the session's status each second (sim_late, and the loop
/// latency's p50/p99/max so far in us: -1 before the first answer) when `latency` is set.
void write_session(const std::string& path, bool latency) {
  LogWriter w(path);
  for (uint64_t k = 0; k <= 750; ++k) {
    const uint64_t t = k * 4000;
    w.add(t, kSimulatorSystemId, 1, sensor_at(t));
    if (k % 250 != 0) continue;
    const int32_t s = static_cast<int32_t>(k / 250);  // 0, 1, 2, 3
    w.add(t, kSimulatorSystemId, 1, named_int(kStatusLateName, 0));
    if (!latency) continue;
    w.add(t, kSimulatorSystemId, 1, named_int(kStatusLoopLatencyP50Name, s == 0 ? -1 : 500 * s));
    w.add(t, kSimulatorSystemId, 1, named_int(kStatusLoopLatencyP99Name, s == 0 ? -1 : 1000 * s));
    w.add(t, kSimulatorSystemId, 1, named_int(kStatusLoopLatencyMaxName, s == 0 ? -1 : 3000 * s));
    w.add(t, 1, 1, named_int(kStatusLoopLatencyP99Name, 7));  // the vehicle's own value of that name: not the session's
  }
  w.close();
}

TEST(FlightLog, LoopLatencyIsTheSessionsStatusEachSecondAndIsDrawnInMilliseconds) {
  const std::string path = ::testing::TempDir() + "latency.tlog";
  write_session(path, true);
  auto log = read_flight_log(path);
  ASSERT_TRUE(log) << log.error().message;
  // -1 (nothing answered yet) is not a latency: three points, at 1, 2 and 3 s.
  ASSERT_EQ(log->loop_latency.p99_us.size(), 3u);
  EXPECT_EQ(log->loop_latency.p50_us.size(), 3u);
  EXPECT_EQ(log->loop_latency.max_us.size(), 3u);
  EXPECT_NEAR(log->loop_latency.p99_us.t_s[0], 1.0, 1e-9);
  EXPECT_DOUBLE_EQ(log->loop_latency.p99_us.value[2], 3000.0);
  EXPECT_DOUBLE_EQ(log->loop_latency.max_us.value[2], 9000.0);
  EXPECT_FALSE(lacks_starting(*log, "the loop latency"));

  const auto plots = plots_of(*log);
  const auto it = std::find_if(plots.begin(), plots.end(), [](const Plot& p) { return p.id == "loop-latency"; });
  ASSERT_NE(it, plots.end());
  EXPECT_TRUE(it->time_axis);
  ASSERT_EQ(it->series.size(), 3u);
  EXPECT_EQ(it->series[0].title, "p50");
  EXPECT_EQ(it->series[1].title, "p99");
  EXPECT_EQ(it->series[2].title, "max");
  EXPECT_EQ(it->series[1].samples, 3u);
  EXPECT_DOUBLE_EQ(it->series[1].y[2], 3.0);  // ms
}

TEST(FlightLog, ASessionWithoutLoopLatencySaysWhy) {
  // An older hitl sim: the session's status without sim_lat99.
  const std::string older = ::testing::TempDir() + "older.tlog";
  write_session(older, false);
  auto log = read_flight_log(older);
  ASSERT_TRUE(log) << log.error().message;
  EXPECT_TRUE(lacks_starting(*log, "the loop latency (NAMED_VALUE_INT sim_lat99"));
  for (const auto& p : plots_of(*log)) EXPECT_NE(p.id, "loop-latency");

  // Nothing ever answered: sim_lat99 stayed -1.
  const std::string unanswered = ::testing::TempDir() + "unanswered.tlog";
  {
    LogWriter w(unanswered);
    for (uint64_t k = 0; k <= 500; ++k) {
      w.add(k * 4000, kSimulatorSystemId, 1, sensor_at(k * 4000));
      if (k % 250 == 0) w.add(k * 4000, kSimulatorSystemId, 1, named_int(kStatusLoopLatencyP99Name, -1));
    }
    w.close();
  }
  log = read_flight_log(unanswered);
  ASSERT_TRUE(log) << log.error().message;
  EXPECT_TRUE(lacks_starting(*log, "the loop latency (no HIL_SENSOR was answered"));
}

/// The altitude plot's series `title`, as drawn, at the point nearest `t_s`.
double altitude_at(const std::vector<Plot>& plots, const std::string& title, double t_s) {
  const auto it = std::find_if(plots.begin(), plots.end(), [](const Plot& p) { return p.id == "altitude"; });
  if (it == plots.end()) return NAN;
  for (const auto& s : it->series) {
    if (s.title != title || s.x.empty()) continue;
    std::size_t best = 0;
    for (std::size_t i = 0; i < s.x.size(); ++i)
      if (std::abs(s.x[i] - t_s) < std::abs(s.x[best] - t_s)) best = i;
    return s.y[best];
  }
  return NAN;
}

/// A hitl sim -t recording of a hover at 2.5 m as the session writes it: the truth ODOMETRY is the
/// body origin (the centre of gravity, 0.22 m above the ground at rest), the pilot's setpoints are in
/// the truth's frame (the pose it flies on), the vehicle's LOCAL_POSITION_NED is from home (0 on the
/// ground). Disarmed 0-2 s, a climb 2-4 s, the hover 4-10 s; 50 Hz.
void write_hover(const std::string& path, uint8_t pilot_sysid, bool setpoints_in_truth_frame, double rest_cg_m = 0.22) {
  LogWriter w(path);
  constexpr double kHover_m = 2.5;
  for (uint64_t k = 0; k <= 500; ++k) {
    const uint64_t t_us = k * 20'000;
    const double t_s = static_cast<double>(t_us) * 1e-6;
    const double h_m = t_s < 2 ? 0.0 : t_s < 4 ? kHover_m * (t_s - 2) / 2 : kHover_m;  // from home
    w.add(t_us, kSimulatorSystemId, 1, sensor_at(t_us));
    if (k % 50 == 0) w.add(t_us, 1, 1, heartbeat(t_s >= 2));
    msg::Odometry truth;
    truth.time_usec = t_us;
    truth.z = static_cast<float>(-(rest_cg_m + h_m));
    truth.q = {1, 0, 0, 0};
    truth.estimator_type = static_cast<uint8_t>(mavlink::MavEstimatorType::Mocap);
    w.add(t_us, kSimulatorSystemId, 1, truth);
    msg::LocalPositionNed estimate;
    estimate.z = static_cast<float>(-h_m);
    w.add(t_us, 1, 1, estimate);
    if (t_s >= 4) {
      msg::PositionTargetLocalNed sp;
      sp.z = static_cast<float>(-(kHover_m + (setpoints_in_truth_frame ? rest_cg_m : 0.0)));
      w.add(t_us, pilot_sysid, mavlink::kCompIdPathPlanner, sp);
    }
  }
  w.close();
}

TEST(FlightLog, AHoverAt2_5mPlotsTruthSetpointAndEstimateFromHomeWithinCentimetres) {
  // hitl sim -t: the pilot is the simulator's and flies on the truth.
  const std::string path = ::testing::TempDir() + "hover.tlog";
  write_hover(path, kSimulatorSystemId, true);
  auto log = read_flight_log(path);
  ASSERT_TRUE(log) << log.error().message;
  const auto plots = plots_of(*log);
  for (double t_s : {5.0, 7.5, 10.0}) {
    EXPECT_NEAR(altitude_at(plots, "truth", t_s), 2.5, 0.03) << "t=" << t_s;
    EXPECT_NEAR(altitude_at(plots, "setpoint", t_s), 2.5, 0.03) << "t=" << t_s;
    EXPECT_NEAR(altitude_at(plots, "estimate", t_s), 2.5, 0.03) << "t=" << t_s;
  }
  EXPECT_NEAR(altitude_at(plots, "truth", 1.0), 0.0, 0.03) << "at rest: 0.00 m on the ground";
  EXPECT_NEAR(altitude_at(plots, "estimate", 1.0), 0.0, 0.03);
  ASSERT_TRUE(log->truth_rest_down_m);
  EXPECT_NEAR(*log->truth_rest_down_m, -0.22, 1e-6);
  EXPECT_FALSE(lacks_starting(*log, "the truth at rest"));
}

TEST(FlightLog, AGroundStationsPilotFliesOnTheEstimateWhoseDatumIsHomeAlready) {
  // hitl fly trajectory through a session: the pilot (255) flies on the board's estimate.
  const std::string path = ::testing::TempDir() + "hover_gcs.tlog";
  write_hover(path, 255, false);
  auto log = read_flight_log(path);
  ASSERT_TRUE(log) << log.error().message;
  const auto plots = plots_of(*log);
  EXPECT_NEAR(altitude_at(plots, "truth", 7.5), 2.5, 0.03);
  EXPECT_NEAR(altitude_at(plots, "setpoint", 7.5), 2.5, 0.03);
  EXPECT_NEAR(altitude_at(plots, "estimate", 7.5), 2.5, 0.03);
}

TEST(FlightLog, TruthThatBeginsArmedIsLeftAsRecordedAndSaidSo) {
  // A client's recording that begins in flight: no rest to take the datum from.
  const std::string path = ::testing::TempDir() + "armed.tlog";
  {
    LogWriter w(path);
    w.add(0, 1, 1, heartbeat(true));
    msg::Odometry truth;
    truth.z = -2.72F;
    truth.q = {1, 0, 0, 0};
    truth.estimator_type = static_cast<uint8_t>(mavlink::MavEstimatorType::Mocap);
    w.add(1000, kSimulatorSystemId, 1, truth);
    w.close();
  }
  auto log = read_flight_log(path);
  ASSERT_TRUE(log) << log.error().message;
  EXPECT_FALSE(log->truth_rest_down_m);
  EXPECT_FLOAT_EQ(static_cast<float>(log->truth.down_m[0]), -2.72F);
  EXPECT_TRUE(lacks_starting(*log, "the truth at rest (the vehicle was armed when the truth began)"));
}

TEST(FlightLog, AFileWithoutFramesIsBadInputNamed) {
  const std::string path = ::testing::TempDir() + "not_a.tlog";
  {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    std::fputs("this is not a telemetry log at all, just some text\n", f);
    std::fclose(f);
  }
  auto log = read_flight_log(path);
  ASSERT_FALSE(log);
  EXPECT_EQ(log.error().kind, ErrorKind::Input);
  EXPECT_NE(log.error().message.find(path), std::string::npos) << log.error().message;
}

TEST(FlightLog, EventsBeyondTheLimitAreCountedNotKept) {
  const std::string path = ::testing::TempDir() + "events.tlog";
  {
    LogWriter w(path);
    for (uint64_t k = 0; k < 30; ++k) {
      msg::Statustext st;
      mavlink::set_text(st.text, "text " + std::to_string(k));
      w.add(k * 1000, 1, 1, st);
    }
    w.close();
  }
  ReadLimits limits;
  limits.max_events = 10;
  auto log = read_flight_log(path, limits);
  ASSERT_TRUE(log) << log.error().message;
  EXPECT_EQ(log->events.size(), 10u);
  EXPECT_EQ(log->missing.back(), "20 events after the first 10");
}

TEST(FlightLog, ParamValueIsReadByteWiseLastValueKeptAndTheTableSaysWhatDiffers) {
  // PARAM_VALUE from the vehicle (hitl params through a session, a ground station): INT32 byte-wise
  // in the float as PX4 sends it, the last value of each; the simulator's own are not the vehicle's.
  const std::string path = ::testing::TempDir() + "params.tlog";
  auto param = [](std::string_view name, float wire, uint8_t type) {
    msg::ParamValue p;
    mavlink::set_text(p.param_id, name);
    p.param_value = wire;
    p.param_type = type;
    return p;
  };
  auto int32 = [](int32_t v) {
    float f = 0;
    std::memcpy(&f, &v, sizeof f);
    return f;
  };
  {
    LogWriter w(path);
    w.add(0, 1, 1, heartbeat(false));
    w.add(1000, 1, 1, param("SYS_HITL", int32(1), 6));
    w.add(2000, 1, 1, param("CAL_ACC0_ID", int32(1310988), 6));
    w.add(3000, 1, 1, param("MPC_XY_P", 0.95F, 9));
    w.add(4000, 1, 1, param("SYS_HITL", int32(0), 6));  // set later in the flight: the last value stands
    w.add(5000, kSimulatorSystemId, 1, param("SYS_HITL", int32(5), 6));
    w.close();
  }
  auto log = read_flight_log(path);
  ASSERT_TRUE(log) << log.error().message;
  EXPECT_EQ(log->parameters, (std::map<std::string, double>{{"CAL_ACC0_ID", 1310988}, {"MPC_XY_P", 0.95F}, {"SYS_HITL", 0}}));
  // Against the emulated board's defaults (no ULog): SYS_HITL is 1 in the HITL set; MPC_XY_P is not in it.
  const std::string section = parameters_section(*log);
  EXPECT_NE(section.find("<tr><td>SYS_HITL</td><td>0</td><td>1</td></tr>"), std::string::npos) << section;
  EXPECT_EQ(section.find("<td>CAL_ACC0_ID</td>"), std::string::npos) << "at its default";
  EXPECT_NE(section.find("1 of 2 differ; 1 without a known default, not compared."), std::string::npos) << section;
  EXPECT_NE(section.find("base/contract/hitl-defaults.params"), std::string::npos);
  // Set during the log: SYS_HITL 1 -> 0, whatever the defaults say.
  EXPECT_NE(section.find("<table id=\"parameters-changed\"><tr><th>parameter</th><th>value</th><th>first in this log</th></tr>\n"
                         "<tr><td>SYS_HITL</td><td>0</td><td>1</td></tr>"),
            std::string::npos)
      << section;
}

}  // namespace
}  // namespace hitl::report
