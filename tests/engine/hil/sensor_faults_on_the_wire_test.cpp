// The sensor and VIO faults as the flight stack sees them (docs/faults.md): what gyro-bias,
// mag-offset, baro-drift and gps-degrade do to HIL_SENSOR and HIL_GPS at a stand-in board, and
// vio-loss to ODOMETRY at a stand-in VIO server. Noise off, the vehicle at rest: a fault's effect is
// the difference between its window and before it.
#include <gtest/gtest.h>

#include <cmath>

#include "base/mavlink/enums.h"
#include "tests/engine/hil/wire_board.h"

namespace hitl::hil {
namespace {

using test_wire::Arrival;
using test_wire::Board;
using test_wire::Running;

constexpr double kStart_s = 0.5;  ///< every fault here starts then
constexpr double kEps_s = 1e-6;
constexpr uint32_t kMagBits = 64 | 128 | 256;  // HIL_SENSOR_UPDATED_FLAGS XMAG|YMAG|ZMAG
constexpr uint32_t kPressureBit = 512;         // ABS_PRESSURE

/// The mean of `value` over the HIL_SENSORs with `bits` updated, in [from_s, to_s).
template <typename F>
Eigen::Vector3d mean_over(const std::vector<Arrival>& got, double from_s, double to_s, uint32_t bits, F value) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int n = 0;
  for (const auto& a : got)
    if (a.sensor && a.sim_s >= from_s - kEps_s && a.sim_s < to_s - kEps_s && (a.sensor->fields_updated & bits) == bits) {
      sum += value(*a.sensor);
      ++n;
    }
  EXPECT_GT(n, 10) << "HIL_SENSORs in " << from_s << ".." << to_s << " s";
  return n ? Eigen::Vector3d(sum / n) : sum;
}

TEST(SensorFaultsOnTheWire, GyroBiasShiftsHilSensorGyroByTheBias) {
  Board board;
  Running run(board, {"gyro-bias:0.02,-0.01,0.05@0.5"}, /*noise=*/false);
  const auto got = board.receive_until(1.0, 10);
  auto gyro = [](const mavlink::msg::HilSensor& m) { return Eigen::Vector3d(m.xgyro, m.ygyro, m.zgyro); };
  const Eigen::Vector3d shift = mean_over(got, kStart_s, 1.0, 8 | 16 | 32, gyro) - mean_over(got, 0.2, kStart_s, 8 | 16 | 32, gyro);
  EXPECT_NEAR(shift.x(), 0.02, 1e-4);
  EXPECT_NEAR(shift.y(), -0.01, 1e-4);
  EXPECT_NEAR(shift.z(), 0.05, 1e-4);
}

TEST(SensorFaultsOnTheWire, MagOffsetShiftsHilSensorMagByTheOffset) {
  Board board;
  Running run(board, {"mag-offset:0.3,0,-0.1@0.5"}, /*noise=*/false);
  const auto got = board.receive_until(1.0, 10);
  auto mag = [](const mavlink::msg::HilSensor& m) { return Eigen::Vector3d(m.xmag, m.ymag, m.zmag); };
  const Eigen::Vector3d shift = mean_over(got, kStart_s, 1.0, kMagBits, mag) - mean_over(got, 0.2, kStart_s, kMagBits, mag);
  EXPECT_NEAR(shift.x(), 0.3, 1e-4);
  EXPECT_NEAR(shift.y(), 0.0, 1e-4);
  EXPECT_NEAR(shift.z(), -0.1, 1e-4);
}

TEST(SensorFaultsOnTheWire, BaroDriftMovesHilSensorPressureAtItsRate) {
  Board board;
  Running run(board, {"baro-drift:-100@0.5"}, /*noise=*/false);  // -100 Pa/s: as in a climb of about 8 m/s
  const auto got = board.receive_until(1.5, 10);
  double before_hPa = 0, before_alt_m = 0;
  int checked = 0;
  for (const auto& a : got) {
    if (!a.sensor || !(a.sensor->fields_updated & kPressureBit)) continue;
    if (a.sim_s > 0.3 && a.sim_s < kStart_s - kEps_s) before_hPa = a.sensor->abs_pressure, before_alt_m = a.sensor->pressure_alt;
    if (a.sim_s < 0.8 || before_hPa == 0) continue;
    const double offset_Pa = (a.sensor->abs_pressure - before_hPa) * 100.0;
    EXPECT_NEAR(offset_Pa, -100.0 * (a.sim_s - kStart_s), 1.0) << "at " << a.sim_s << " s";
    EXPECT_GT(a.sensor->pressure_alt, before_alt_m + 2.0);  // less pressure: higher
    ++checked;
  }
  EXPECT_GE(checked, 5);  // the barometer samples at 10 Hz: 7 in 0.8..1.5 s
}

TEST(SensorFaultsOnTheWire, GpsDegradeReportsItsFixSatellitesAndAccuracyInHilGps) {
  Board board;
  Running run(board, {"gps-degrade:2,4,5,8@0.5+0.5"}, /*noise=*/false);
  const auto got = board.receive_until(1.5, 10);
  int before = 0, during = 0, after = 0;
  for (const auto& a : got) {
    if (!a.gps) continue;
    const double t = a.gps_sim_s();
    const auto& g = *a.gps;
    if (t >= kStart_s - kEps_s && t < 1.0 - kEps_s) {
      EXPECT_EQ(g.fix_type, 2);
      EXPECT_EQ(g.satellites_visible, 4);
      EXPECT_EQ(g.eph, 500);  // cm
      EXPECT_EQ(g.epv, 800);
      ++during;
    } else {
      EXPECT_EQ(g.fix_type, 3) << "at " << t << " s";
      EXPECT_GT(g.satellites_visible, 4);
      EXPECT_LT(g.eph, 500);
      (t < kStart_s ? before : after) += 1;
    }
  }
  EXPECT_GT(before, 5);
  EXPECT_GT(during, 5);
  EXPECT_GT(after, 5);
}

TEST(SensorFaultsOnTheWire, VioLossSendsNoOdometryInItsWindowAndOdometryAgainAfter) {
  Board board, vio;
  Running run(board, {"vio-loss@0.5+0.5"}, /*noise=*/false, "", test_wire::vio_to(vio));
  const auto got = vio.receive_until(1.5, 10);
  int before = 0, during = 0, after = 0;
  for (const auto& a : got) {
    if (!a.odometry) continue;
    if (a.sim_s < kStart_s - kEps_s) ++before;
    else if (a.sim_s < 1.0 - kEps_s) ++during;
    else ++after;
  }
  EXPECT_GT(before, 5);
  EXPECT_EQ(during, 0);
  EXPECT_GT(after, 5);
}

TEST(SensorFaultsOnTheWire, VioJumpMovesOdometryAndCountsResetsQualityAndDriftAsSet) {
  Board board, vio;
  Running run(board, {"vio-jump:2,-1,0.5@0.5+0.5", "vio-quality:20@0.5+0.5", "vio-drift:1,0,0@1.2"}, /*noise=*/false, "",
              test_wire::vio_to(vio));
  const auto got = vio.receive_until(1.8, 10);
  std::optional<Eigen::Vector3d> before;
  int during = 0, drifting = 0;
  for (const auto& a : got) {
    if (!a.odometry) continue;
    const auto& o = *a.odometry;
    const Eigen::Vector3d p_NED_m(o.x, o.y, o.z);
    if (a.sim_s > 0.3 && a.sim_s < kStart_s - kEps_s) {
      before = p_NED_m;  // at rest on its gear: the same place
      EXPECT_EQ(o.reset_counter, 0);
      EXPECT_EQ(o.quality, 100);
    } else if (a.sim_s >= kStart_s - kEps_s && a.sim_s < 1.0 - kEps_s && before) {
      EXPECT_TRUE((p_NED_m - *before).isApprox(Eigen::Vector3d(2, -1, 0.5), 1e-3)) << (p_NED_m - *before).transpose();
      EXPECT_EQ(o.reset_counter, 1);
      EXPECT_EQ(o.quality, 20);
      ++during;
    } else if (a.sim_s >= 1.0 - kEps_s && before) {
      EXPECT_EQ(o.reset_counter, 2);  // the jump back is a reset too
      EXPECT_EQ(o.quality, 100);
      const double drift_m = a.sim_s >= 1.2 - kEps_s ? 1.0 * (a.sim_s - 1.2) : 0.0;
      EXPECT_NEAR(p_NED_m.x() - before->x(), drift_m, 0.01) << a.sim_s;
      drifting += drift_m > 0.2 ? 1 : 0;
    }
  }
  EXPECT_GT(during, 10);
  EXPECT_GT(drifting, 3);
}

TEST(SensorFaultsOnTheWire, ImuStuckRepeatsOneReadingWhileItLastsAndNoiseScaleWidensTheSpread) {
  Board board;
  Running run(board, {"imu-stuck@0.5+0.3", "imu-noise:5@1+0.5"});  // with noise
  const auto got = board.receive_until(1.5, 10);
  std::optional<mavlink::msg::HilSensor> held;
  int stuck = 0;
  std::vector<double> quiet, loud;  // xgyro, rad/s
  for (const auto& a : got) {
    if (!a.sensor || !(a.sensor->fields_updated & 8)) continue;
    if (a.sim_s >= kStart_s - kEps_s && a.sim_s < 0.8 - kEps_s) {
      if (!held) held = a.sensor;
      EXPECT_EQ(a.sensor->xacc, held->xacc);
      EXPECT_EQ(a.sensor->zgyro, held->zgyro);
      ++stuck;
    }
    if (a.sim_s > 0.2 && a.sim_s < kStart_s) quiet.push_back(a.sensor->xgyro);
    if (a.sim_s > 1.0 && a.sim_s < 1.5 - kEps_s) loud.push_back(a.sensor->xgyro);
  }
  EXPECT_GT(stuck, 60);  // 250 Hz for 0.3 s
  auto sigma = [](const std::vector<double>& v) {
    double m = 0, q = 0;
    for (double x : v) m += x;
    m /= static_cast<double>(v.size());
    for (double x : v) q += (x - m) * (x - m);
    return std::sqrt(q / static_cast<double>(v.size()));
  };
  ASSERT_GT(quiet.size(), 50u);
  ASSERT_GT(loud.size(), 100u);
  EXPECT_NEAR(sigma(loud) / sigma(quiet), 5.0, 1.5);
}

// A sensor unit's fault started by hand (the dashboard) acts only while its unit is on; while it is
// off it is said and not started.
TEST(SensorFaultsOnTheWire, AUnitsFaultStartedByHandStartsOnlyWhileTheUnitIsOn) {
  for (const bool on : {false, true}) {
    SCOPED_TRACE(on ? "rangefinder on" : "rangefinder off");
    Board board;
    Running run(board, {}, /*noise=*/false, "", [on](SessionConfig& c) {
      if (on) sensors::enable_unit(c.sensor_units, 0);
    });
    board.receive_until(0.2, 10);
    auto spec = faults::parse_live_fault("rangefinder-stuck");
    ASSERT_TRUE(spec) << spec.error().message;
    run.session().start_fault(*spec);
    board.receive_until(0.6, 10);
    const auto active = run.snapshot().active_faults;
    EXPECT_EQ(active, on ? std::vector<std::string>{"rangefinder-stuck"} : std::vector<std::string>{});
  }
}

}  // namespace
}  // namespace hitl::hil
