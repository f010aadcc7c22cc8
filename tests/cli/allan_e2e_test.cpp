// Issue 37's Done-when: 10 simulated minutes of the x500 at rest (disarmed on the ground) against
// `hitl target --lockstep`, `hitl sim --lockstep --speed 0`, recorded; `hitl inspect --tlog --allan
// --json` reads back each profile's noise: the white-noise slope within 20 % of the profile's noise
// density and the curve's floor within 50 % of what the profile's noise gives (its bias
// instability, or where white noise meets its random walk), for gyro and accel on every axis; and
// `hitl report` of the same recording plots the Allan deviation with the profile's figures marked.
#include <chrono>
#include <cstdio>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "engine/sensors/vehicle_file.h"
#include "tests/support/json_lines.h"
#include "tests/support/process.h"
#include "tests/support/recorded_flight.h"
#include "tests/support/tools.h"

namespace hitl {
namespace {

using namespace std::chrono_literals;

constexpr int kRest_s = 600;
constexpr double kRate_hz = 250.0;

/// `hitl sim --vehicle FILE` at rest for kRest_s simulated seconds in lockstep with `hitl target`;
/// the recording's path (empty, with a failure, when the run did not end well).
std::string record_rest(const std::string& dir, const std::string& vehicle_file) {
  return test::record_against_target(dir + "/rest.tlog", {"--duration", std::to_string(kRest_s), "--vehicle", vehicle_file}, 180s);
}

/// The Allan deviation the profile's noise gives at tau: white noise (with the LSB's rounding,
/// LSB^2 / 12 per sample), the bias random walk (tau far below its correlation time) and the bias
/// instability's floor.
double modelled_deviation(const model::InertialNoiseConfig& n, double lsb, double tau_s) {
  const double white2 = n.noise_density * n.noise_density + lsb * lsb / 12.0 / kRate_hz;
  const double floor = 0.664 * n.bias_instability;
  return std::sqrt(white2 / tau_s + n.random_walk * n.random_walk * tau_s / 3.0 + floor * floor);
}

using test::read_text;

std::string three_figures(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", v);
  return text;
}

/// `hitl report` of the rest recording: an Allan plot per sensor (issue 37, item 3), the white noise
/// the simulator said its IMU has marked with the profile's name, and its floor where B > 0.
void expect_report_marks(const std::string& tlog, const std::string& profile, const model::ImuConfig& imu) {
  const std::string html = tlog + ".html";
  const auto r = test::run_hitl({"report", tlog, "-o", html});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string page = read_text(html);
  std::filesystem::remove(html);
  for (const char* sensor : {"gyro", "accel"}) {
    const std::string id = std::string("<figure id=\"plot-allan-") + sensor + "\"";
    const auto at = page.find(id);
    ASSERT_NE(at, std::string::npos) << sensor;
    const std::string figure = page.substr(at, page.find("</figure>", at) - at);
    const model::InertialNoiseConfig& n = std::string(sensor) == "gyro" ? imu.gyro : imu.accel;
    EXPECT_NE(figure.find("profile " + profile + ": N/sqrt(tau), N = " + three_figures(n.noise_density)), std::string::npos)
        << sensor << ": " << figure.substr(0, 2000);
    EXPECT_EQ(figure.find("profile " + profile + ": 0.664 B") != std::string::npos, n.bias_instability > 0) << sensor;
    EXPECT_NE(figure.find("fitted N/sqrt(tau)"), std::string::npos) << sensor;
    EXPECT_NE(figure.find("600 s at rest"), std::string::npos) << sensor;
  }
}

/// Records `vehicle_file` at rest and checks what --allan reads back against the file's IMU noise.
void expect_noise_of(const std::string& vehicle_file) {
  auto file = sensors::load_vehicle_file(vehicle_file);
  ASSERT_TRUE(file.ok()) << file.error().message;
  const std::string& profile = file->imu_profile;
  const auto start = std::chrono::steady_clock::now();
  const std::string tlog = record_rest(test::temp_dir(), vehicle_file);
  ASSERT_FALSE(tlog.empty());
  const auto r = test::run_hitl({"--json", "inspect", "--tlog", tlog, "--allan"});
  expect_report_marks(tlog, profile, file->vehicle.sensors.imu);
  std::filesystem::remove(tlog);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = test::last_json_line(r.out);
  std::cerr << profile << ": recorded and read in "
            << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() << " s\n";
  EXPECT_EQ(j["samples"].get<std::size_t>(), static_cast<std::size_t>(kRest_s * kRate_hz));
  EXPECT_NEAR(j["rate_hz"].get<double>(), kRate_hz, 0.01);
  EXPECT_EQ(j["gaps"], 0);
  const model::ImuConfig& imu = file->vehicle.sensors.imu;
  for (const char* sensor : {"gyro", "accel"}) {
    const bool gyro = std::string(sensor) == "gyro";
    const model::InertialNoiseConfig& n = gyro ? imu.gyro : imu.accel;
    const double lsb = gyro ? imu.gyro_resolution_rad_s : imu.accel_resolution_m_s2;
    for (const char* axis : {"x", "y", "z"}) {
      const nlohmann::json& a = j["sensors"][sensor]["axes"][axis];
      const double noise_density = a["noise_density"].get<double>();
      const double bias_instability = a["bias_instability"].get<double>();
      // The floor the profile gives: the modelled curve's minimum over the measured curve's taus.
      double modelled_minimum = 1e300;
      for (const auto& point : a["curve"]) modelled_minimum = std::min(modelled_minimum, modelled_deviation(n, lsb, point[0]));
      const double modelled_bias_instability = modelled_minimum / 0.664;
      std::cerr << profile << " " << sensor << " " << axis << ": noise_density " << noise_density << " (profile "
                << n.noise_density << "), bias_instability " << bias_instability << " at tau " << a["minimum_tau_s"]
                << " s (modelled " << modelled_bias_instability << ", profile " << n.bias_instability << ")\n";
      EXPECT_NEAR(noise_density / n.noise_density, 1.0, 0.2) << sensor << " " << axis;
      EXPECT_NEAR(bias_instability / modelled_bias_instability, 1.0, 0.5) << sensor << " " << axis;
      if (n.bias_instability > 0.0) {
        EXPECT_NEAR(bias_instability / n.bias_instability, 1.0, 0.5) << sensor << " " << axis;
      }
    }
  }
}

TEST(AllanE2E, Icm42688pAtRestShowsItsDatasheetNoise) {
  expect_noise_of(test::source_path("docs/examples/vehicles/x500-voxl2-icm-42688-p.json"));
}

TEST(AllanE2E, GenericAtRestShowsTheOldNoise) {
  const std::string file = test::temp_dir() + "/generic.json";
  std::ofstream(file) << R"({"sensors": {"imu": {"profile": "generic"}}})";
  expect_noise_of(file);
}

TEST(AllanE2E, AFlickerFloorReadsBackAsTheBiasInstability) {
  // The ICM-42688-P with a measured-board-like bias instability set over the profile (TDK publishes
  // none): the floor reads back within 50 %.
  const std::string file = test::temp_dir() + "/flicker.json";
  std::ofstream(file) << R"({"sensors": {"imu": {"profile": "icm-42688-p",
                               "gyro": {"bias_instability": 4.8e-5}, "accel": {"bias_instability": 4e-4}}}})";
  expect_noise_of(file);
}

}  // namespace
}  // namespace hitl

namespace hitl {
namespace {

TEST(AllanE2E, RefusesWhatItCannotRead) {
  const auto no_tlog = test::run_hitl({"inspect", "--port", "1", "--allan"});
  EXPECT_EQ(no_tlog.exit_code, 2);
  EXPECT_NE(no_tlog.err.find("--allan reads a recording: give --tlog FILE"), std::string::npos) << no_tlog.err;
  const std::string dir = test::temp_dir();
  std::ofstream(dir + "/empty.tlog").flush();
  const auto empty = test::run_hitl({"inspect", "--tlog", dir + "/empty.tlog", "--allan"});
  EXPECT_EQ(empty.exit_code, 2);
  EXPECT_NE(empty.err.find("empty.tlog' is empty"), std::string::npos) << empty.err;
  std::ofstream(dir + "/text.tlog") << "not a telemetry log at all, just some words to be read as records";
  const auto text = test::run_hitl({"inspect", "--tlog", dir + "/text.tlog", "--allan"});
  EXPECT_EQ(text.exit_code, 2);
  EXPECT_NE(text.err.find("text.tlog'"), std::string::npos) << text.err;
  const auto with_show = test::run_hitl({"inspect", "--tlog", dir + "/text.tlog", "--allan", "--show", "HEARTBEAT"});
  EXPECT_EQ(with_show.exit_code, 2);
  EXPECT_NE(with_show.err.find("does not go with"), std::string::npos) << with_show.err;
}

}  // namespace
}  // namespace hitl
