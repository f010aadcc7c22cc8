// The flight core closed around the real engine in process: the Simbody x500 and its sensors at
// 4 ms lockstep, engine samples converted to the flight core's input structs, its motor commands fed
// back before each physics step. No network, no clocks: a seed makes a run.
#pragma once

#include <cstdint>
#include <memory>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "emulator/flight/flight_core.h"
#include "engine/model/multicopter.h"
#include "engine/model/x500_defaults.h"
#include "engine/sensors/sensor_suite.h"

namespace hitl::flight::test {

ImuSample to_input(const sensors::ImuSample& s);
MagSample to_input(const sensors::MagSample& s);
BaroSample to_input(const sensors::BaroSample& s);
GpsSample to_input(const sensors::GpsSample& s);

class SimLoop {
 public:
  explicit SimLoop(std::uint64_t seed, const model::VehicleConfig& vehicle = model::x500_vehicle_config(),
                   const model::WorldConfig& world = model::default_world_config(),
                   const model::InitialCondition* initial = nullptr);
  /// One 4 ms step: commands -> physics -> sensors -> flight core.
  void step();
  void run_s(double seconds);
  /// Steps until pred() or the time runs out; true if pred() became true.
  template <typename Pred>
  bool run_until(Pred pred, double timeout_s) {
    const double end_s = time_s() + timeout_s;
    while (time_s() < end_s) {
      step();
      if (pred()) return true;
    }
    return false;
  }

  double time_s() const { return model_->state().time_s; }
  std::uint64_t time_us() const;
  FlightCore& core() { return core_; }
  model::Multicopter& model() { return *model_; }
  sensors::SensorSuite& sensors() { return *sensors_; }
  const sensors::GroundTruth& truth() const { return truth_; }
  /// Height of the base origin above its resting height at home [m] (truth).
  double truth_height_m() const { return -truth_.p_NED_m.z() - rest_height_m_; }
  double rest_height_m() const { return rest_height_m_; }
  /// Angle between estimated and true attitude [deg]; tilt part only [deg].
  double attitude_error_deg() const;
  double tilt_error_deg() const;
  /// Tilt the accelerometer's bias alone explains (unobservable at rest) [deg].
  double accel_bias_tilt_deg() const;

 private:
  std::unique_ptr<model::Multicopter> model_;
  std::unique_ptr<sensors::SensorSuite> sensors_;
  FlightCore core_;
  sensors::GroundTruth truth_;
  double rest_height_m_ = 0.0;
};

}  // namespace hitl::flight::test
