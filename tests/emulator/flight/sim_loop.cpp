#include "tests/emulator/flight/sim_loop.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "engine/frames/frames.h"

namespace hitl::flight::test {
namespace {
std::uint64_t to_us(double t_s) { return static_cast<std::uint64_t>(std::llround(t_s * 1e6)); }
constexpr double kRadToDeg = 180.0 / std::numbers::pi;
}  // namespace

ImuSample to_input(const sensors::ImuSample& s) { return {to_us(s.time_s), s.accel_FRD_m_s2, s.gyro_FRD_rad_s}; }
MagSample to_input(const sensors::MagSample& s) { return {to_us(s.time_s), s.mag_FRD_gauss}; }
BaroSample to_input(const sensors::BaroSample& s) { return {to_us(s.time_s), s.pressure_Pa, s.temperature_degC}; }
GpsSample to_input(const sensors::GpsSample& s) {
  GpsSample g;
  g.time_us = to_us(s.time_s);
  g.lat_deg = s.lat_deg;
  g.lon_deg = s.lon_deg;
  g.alt_msl_m = s.alt_m;
  g.v_NED_m_s = s.v_NED_m_s;
  g.eph_m = s.eph_m;
  g.epv_m = s.epv_m;
  g.fix_type = s.fix_type;
  g.satellites = s.satellites;
  return g;
}

SimLoop::SimLoop(std::uint64_t seed, const model::VehicleConfig& vehicle, const model::WorldConfig& world,
                 const model::InitialCondition* initial) {
  auto created = model::Multicopter::create(vehicle, world, seed);
  if (!created.ok()) throw std::runtime_error(created.error().message);
  model_ = std::move(created.value());
  if (initial != nullptr) model_->reset(*initial);
  sensors_ = std::make_unique<sensors::SensorSuite>(vehicle, world, seed);
  rest_height_m_ = model_->resting_on_ground().p_ENU_m.z();
  truth_.q_FRD_to_NED = frames::q_FRD_to_NED_from(model_->state().q_FLU_to_ENU);
}

std::uint64_t SimLoop::time_us() const { return to_us(time_s()); }

void SimLoop::step() {
  const ActuatorOutput& a = core_.actuators();
  model_->set_motor_commands({a.u, a.armed});
  const Status st = model_->step();
  if (!st.ok()) throw std::runtime_error(st.error().message);
  const sensors::SensorFrame f = sensors_->sample_due(model_->state());
  truth_ = f.truth;
  if (f.imu) core_.handle_imu(to_input(*f.imu));
  if (f.mag) core_.handle_mag(to_input(*f.mag));
  if (f.baro) core_.handle_baro(to_input(*f.baro));
  if (f.gps) core_.handle_gps(to_input(*f.gps));
  core_.step(time_us());
}

void SimLoop::run_s(double seconds) {
  const auto steps = static_cast<int>(std::lround(seconds / 0.004));
  for (int i = 0; i < steps; ++i) step();
}

double SimLoop::attitude_error_deg() const {
  return core_.estimate().q_FRD_to_NED.angularDistance(truth_.q_FRD_to_NED) * kRadToDeg;
}

double SimLoop::tilt_error_deg() const {
  const Eigen::Vector3d z_est = core_.estimate().q_FRD_to_NED * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d z_true = truth_.q_FRD_to_NED * Eigen::Vector3d::UnitZ();
  return std::acos(std::clamp(z_est.dot(z_true), -1.0, 1.0)) * kRadToDeg;
}

double SimLoop::accel_bias_tilt_deg() const {
  const auto& n = sensors_->imu().accel_noise();
  const Eigen::Vector3d b = n.turn_on_bias() + n.bias();
  return std::atan2(b.head<2>().norm(), 9.80665) * kRadToDeg;
}

}  // namespace hitl::flight::test
