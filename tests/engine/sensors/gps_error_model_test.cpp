// The GPS receiver's error model (engine/sensors/gps.h) with the u-blox M10 profile: per axis a
// first-order Gauss-Markov wander whose stationary sigma and correlation time read back from a long
// simulated run (12 000 s at 30 Hz, 200 correlation times), the vertical larger than the horizontal,
// eph/epv that move with the error, the same stream for the same seed; and the generic receiver's
// constant eph/epv, as before.
#include <cmath>
#include <iostream>
#include <numeric>
#include <vector>

#include <gtest/gtest.h>

#include "engine/model/vehicle_state.h"
#include "engine/model/x500_defaults.h"
#include "engine/sensors/geodesy.h"
#include "engine/sensors/gps.h"
#include "engine/sensors/sensor_profiles.h"

namespace hitl::sensors {
namespace {

constexpr double kRate_hz = 30.0;

model::GpsConfig ublox_m10() {
  auto vehicle = apply_profile("gps", "u-blox-m10", model::x500_vehicle_config());
  EXPECT_TRUE(vehicle.ok());
  return vehicle->sensors.gps;
}

model::VehicleState at_rest() {
  model::VehicleState s;
  s.p_ENU_m = {0.0, 0.0, 0.0};
  return s;
}

double sigma_of(const std::vector<double>& x) {
  const double mean = std::accumulate(x.begin(), x.end(), 0.0) / static_cast<double>(x.size());
  double sum2 = 0.0;
  for (double v : x) sum2 += (v - mean) * (v - mean);
  return std::sqrt(sum2 / static_cast<double>(x.size()));
}

/// The correlation time of a first-order Gauss-Markov series: its autocorrelation at `lag` samples
/// is exp(-lag dt / tau).
double correlation_time_s(const std::vector<double>& x, std::size_t lag) {
  const double mean = std::accumulate(x.begin(), x.end(), 0.0) / static_cast<double>(x.size());
  double c0 = 0.0, cl = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) c0 += (x[i] - mean) * (x[i] - mean);
  for (std::size_t i = 0; i + lag < x.size(); ++i) cl += (x[i] - mean) * (x[i + lag] - mean);
  const double rho = (cl / static_cast<double>(x.size() - lag)) / (c0 / static_cast<double>(x.size()));
  return -static_cast<double>(lag) / kRate_hz / std::log(rho);
}

struct GpsRun {
  std::vector<double> error[3];  ///< E, N, U of the reported position against the truth [m]
  std::vector<double> eph, epv, v_north;
};

GpsRun record_fixes(const model::GpsConfig& config, std::uint64_t seed, double duration_s) {
  const model::HomeConfig home = model::default_world_config().home;
  Gps gps(config, home, seed);
  LocalGeodesy geodesy(home);
  GpsRun r;
  const auto n = static_cast<std::size_t>(duration_s * kRate_hz);
  for (std::size_t k = 1; k <= n; ++k) {
    const GpsSample g = gps.sample(at_rest(), static_cast<double>(k) / kRate_hz);
    const Eigen::Vector3d p = geodesy.to_local_ENU_m({g.lat_deg, g.lon_deg, g.alt_m});
    for (int i = 0; i < 3; ++i) r.error[i].push_back(p[i]);
    r.eph.push_back(g.eph_m);
    r.epv.push_back(g.epv_m);
    r.v_north.push_back(g.v_NED_m_s.x());
  }
  return r;
}

TEST(GpsErrorModel, UbloxM10WanderHasItsSigmaAndCorrelationTime) {
  const model::GpsConfig config = ublox_m10();
  const double tau_s = config.error_correlation_time_s;
  const GpsRun r = record_fixes(config, 37, 200.0 * tau_s);
  const double sigmas[3] = {config.horizontal_error_sigma_m, config.horizontal_error_sigma_m, config.vertical_error_sigma_m};
  const double white[3] = {config.horizontal_noise_m, config.horizontal_noise_m, config.vertical_noise_m};
  for (int i = 0; i < 3; ++i) {
    // The reported position's error: the wander and the white noise, sigmas added in squares.
    const double expected = std::hypot(sigmas[i], white[i]);
    const double tau_measured_s = correlation_time_s(r.error[i], static_cast<std::size_t>(tau_s / 2.0 * kRate_hz));
    std::cerr << "axis " << i << ": sigma " << sigma_of(r.error[i]) << " m (model " << expected << "), correlation time "
              << tau_measured_s << " s (model " << tau_s << ")\n";
    EXPECT_NEAR(sigma_of(r.error[i]), expected, 0.15 * expected) << "axis " << i;
    // Half a correlation time apart the white noise is gone from the autocorrelation's numerator.
    EXPECT_NEAR(correlation_time_s(r.error[i], static_cast<std::size_t>(tau_s / 2.0 * kRate_hz)), tau_s, 0.25 * tau_s)
        << "axis " << i;
  }
  EXPECT_GT(sigma_of(r.error[2]), 1.3 * sigma_of(r.error[0]));  // the vertical larger, as receivers show
  EXPECT_NEAR(sigma_of(r.v_north), config.velocity_noise_m_s, 0.05 * config.velocity_noise_m_s);
}

TEST(GpsErrorModel, EphAndEpvMoveWithTheError) {
  const model::GpsConfig config = ublox_m10();
  const model::HomeConfig home = model::default_world_config().home;
  Gps gps(config, home, 8);
  double eph_min = 1e9, eph_max = 0, epv_min = 1e9, epv_max = 0;
  for (int k = 1; k <= 30 * 600; ++k) {
    const GpsSample g = gps.sample(at_rest(), k / kRate_hz);
    const Eigen::Vector3d& e = gps.position_error_ENU_m();
    EXPECT_DOUBLE_EQ(g.eph_m, std::sqrt(e.head<2>().squaredNorm() + 2.0 * config.horizontal_noise_m * config.horizontal_noise_m));
    EXPECT_DOUBLE_EQ(g.epv_m, std::sqrt(e.z() * e.z() + config.vertical_noise_m * config.vertical_noise_m));
    eph_min = std::min(eph_min, g.eph_m), eph_max = std::max(eph_max, g.eph_m);
    epv_min = std::min(epv_min, g.epv_m), epv_max = std::max(epv_max, g.epv_m);
  }
  EXPECT_GT(eph_max, 3.0 * eph_min);  // not a constant: 10 minutes of a 60 s wander
  EXPECT_GT(epv_max, 3.0 * epv_min);
  // The gps-noise fault's scale raises them with the error it scales.
  Gps scaled(config, home, 8);
  scaled.set_noise_scale(3.0);
  const GpsSample g = scaled.sample(at_rest(), 1.0 / kRate_hz);
  const Eigen::Vector3d& e = scaled.position_error_ENU_m();
  EXPECT_DOUBLE_EQ(g.eph_m, 3.0 * std::sqrt(e.head<2>().squaredNorm() + 2.0 * config.horizontal_noise_m * config.horizontal_noise_m));
}

TEST(GpsErrorModel, TheSameSeedGivesTheSameFixes) {
  const model::GpsConfig config = ublox_m10();
  const GpsRun a = record_fixes(config, 5, 120.0), b = record_fixes(config, 5, 120.0), c = record_fixes(config, 6, 120.0);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(a.error[i], b.error[i]);
  EXPECT_EQ(a.eph, b.eph);
  EXPECT_NE(a.error[0], c.error[0]);
}

TEST(GpsErrorModel, GenericKeepsItsConstantAccuracy) {
  const model::GpsConfig config = model::x500_vehicle_config().sensors.gps;
  EXPECT_FALSE(config.accuracy_follows_error);
  const GpsRun r = record_fixes(config, 3, 60.0);
  for (double eph : r.eph) EXPECT_EQ(eph, config.eph_m);
  for (double epv : r.epv) EXPECT_EQ(epv, config.epv_m);
}

}  // namespace
}  // namespace hitl::sensors
