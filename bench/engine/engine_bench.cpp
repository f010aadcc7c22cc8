// Cost of one 4 ms step: physics alone, sensors alone, physics + all sensors (what `hitl sim` does
// per tick), with inputs changing every step from a small hover controller. The `rtf` counter is
// the headless real-time factor: simulated seconds per wall second on one core.
// Run: build/bench/engine/hitl_engine_bench
#include <algorithm>
#include <cstdlib>

#include <benchmark/benchmark.h>

#include "engine/model/multicopter.h"
#include "engine/model/x500_defaults.h"
#include "engine/sensors/sensor_suite.h"

namespace {

using namespace hitl;

/// A crude PD hover controller on altitude and attitude, so inputs change every step as with PX4.
model::MotorCommands hover_controller(const model::VehicleState& s, double u_hover) {
  const Eigen::Vector3d z_body_ENU = s.q_FLU_to_ENU * Eigen::Vector3d::UnitZ();
  const double thrust = u_hover + 0.1 * (2.0 - s.p_ENU_m.z()) - 0.1 * s.v_ENU_m_s.z();
  // Tilt error in body axes: roll about x, pitch about y (FLU); derivative from body rates.
  const Eigen::Vector3d tilt_FLU = s.q_FLU_to_ENU.conjugate() * z_body_ENU.cross(Eigen::Vector3d::UnitZ());
  const double roll = 0.5 * tilt_FLU.x() - 0.05 * s.w_FLU_rad_s.x();
  const double pitch = 0.5 * tilt_FLU.y() - 0.05 * s.w_FLU_rad_s.y();
  const double yaw = -0.05 * s.w_FLU_rad_s.z();
  // Mixer, PX4 order: 0 FR CCW, 1 BL CCW, 2 FL CW, 3 BR CW (FLU: +roll = right side up, +pitch = nose down).
  model::MotorCommands c;
  c.armed = true;
  c.u = {thrust + roll - pitch - yaw, thrust - roll + pitch - yaw, thrust - roll - pitch + yaw,
         thrust + roll + pitch + yaw};
  for (double& u : c.u) u = std::clamp(u, 0.0, 1.0);
  return c;
}

struct Fixture {
  Fixture()
      : vehicle(model::x500_vehicle_config()),
        world(model::default_world_config()),
        plant(std::move(model::Multicopter::create(vehicle, world, 1).value())),
        sensors(vehicle, world, 1),
        u_hover(model::hover_command(vehicle, world)) {}
  void step_physics() {
    plant->set_motor_commands(hover_controller(plant->state(), u_hover));
    if (!plant->step().ok()) std::abort();
  }
  model::VehicleConfig vehicle;
  model::WorldConfig world;
  std::unique_ptr<model::Multicopter> plant;
  sensors::SensorSuite sensors;
  double u_hover;
};

void report(benchmark::State& state, double step_s) {
  state.counters["rtf"] = benchmark::Counter(static_cast<double>(state.iterations()) * step_s, benchmark::Counter::kIsRate);
}

void BM_PhysicsStep(benchmark::State& state) {
  Fixture f;
  for (auto _ : state) f.step_physics();
  report(state, f.world.physics.step_s);
}
BENCHMARK(BM_PhysicsStep)->Unit(benchmark::kMicrosecond);

void BM_SensorsAtRest(benchmark::State& state) {
  Fixture f;
  model::VehicleState s = f.plant->state();
  for (auto _ : state) {
    s.time_s += f.world.physics.step_s;
    benchmark::DoNotOptimize(f.sensors.sample_due(s));
  }
  report(state, f.world.physics.step_s);
}
BENCHMARK(BM_SensorsAtRest)->Unit(benchmark::kMicrosecond);

void BM_PhysicsAndAllSensorsStep(benchmark::State& state) {
  Fixture f;
  for (auto _ : state) {
    f.step_physics();
    benchmark::DoNotOptimize(f.sensors.sample_due(f.plant->state()));
  }
  report(state, f.world.physics.step_s);
}
BENCHMARK(BM_PhysicsAndAllSensorsStep)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
