// The emulated board's HIL input side, as the spec's data flow runs on a VOXL2: HIL_SENSOR into the
// HIL split (target/core), its publications through dsp_hitl (the DSP) into the flight core, whose
// step gives the motor commands; HIL_GPS straight to the flight core's GPS. In lockstep each
// HIL_SENSOR advances the board's clock and gets one HIL_ACTUATOR_CONTROLS back.
#include "emulator/board_impl.h"
#include "target/core/hil_gps.h"

namespace hitl::target {

void Board::Impl::on_hil_sensor(const mavlink::msg::HilSensor& m) {
  ++hil_sensor_received;
  if (config.lockstep) {
    auto sessions = [&] { return lockstep_clock.restarts() + (lockstep_clock.started() ? 1 : 0); };
    const uint64_t before = sessions();
    now_us = lockstep_clock.on_hil_sensor(m.time_usec, now_us);
    // A new simulator session: the streams start with it, so their phase against its steps is the
    // same each run (deterministic replay, docs/replay.md), whenever the board was started.
    if (sessions() != before)
      for (auto* inst : instances()) inst->restart_streams();
  }
  split.on_hil_sensor(hil_sensor_input(m), now_us);
  if (config.lockstep) {
    process_board(now_us);
    // One answer per HIL_SENSOR, as PX4 SITL's lockstep does: sent last in the loop's pass (board.cpp).
    if (answers_owed.size() >= kMaxAnswersOwed) send_owed_answers();  // a burst of HIL_SENSORs (a free run): bounded
    if (!config.faults.no_actuators) answers_owed.push_back(actuator_message());
  }
}

void Board::Impl::send_owed_answers() {
  for (const auto& answer : answers_owed) {
    hil->send(answer);
    ++actuators_sent;
  }
  answers_owed.clear();
}

void Board::Impl::on_hil_gps(const mavlink::msg::HilGps& m) {
  ++hil_gps_received;
  flight->on_gps(to_sensor_gps(hil_gps_input(m), now_us));
}

void Board::Impl::process_board(uint64_t t_us) {
  auto out = split.poll(t_us);
  if (config.faults.dsp_hitl_stalled && dsp.counters().hil_imu_received >= kDspStallAfterImu) out = {};  // --fault: MUORB stops delivering
  if (out.imu) {
    if (auto s = dsp.on_imu(*out.imu, t_us)) {
      flight->on_imu(s->accel, s->gyro);
      motors = flight->step(t_us);
    }
  }
  if (out.mag_baro) {
    const auto s = dsp.on_mag_baro(*out.mag_baro, t_us);
    if (s.mag) flight->on_mag(*s.mag);
    if (s.baro) flight->on_baro(*s.baro);
  }
  say_flight_messages();
}

}  // namespace hitl::target
