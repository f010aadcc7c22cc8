#include "cli/board_stack.h"

namespace hitl::cli {

Expected<campaign::FlightStack::Ports> EmulatedBoardStack::start() {
  target::BoardConfig config;
  config.bind_address = "127.0.0.1";
  config.lockstep = true;
  config.os_picks_ports = true;  // the OS's ports, kept by the board: parallel flights never race for one
  config.gcs_port = 0;           // no GCS instance: nothing talks to it
  auto created = target::Board::create(config);
  if (!created) return created.error();
  board_ = std::move(created.value());
  const auto bound = board_->ports();
  stop_ = false;
  thread_ = std::thread([this] { (void)board_->run(stop_, observer_); });
  return Ports{bound.hil_port, bound.vio_port};
}

void EmulatedBoardStack::stop() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
}

campaign::StackFigures EmulatedBoardStack::figures(const hil::SessionSnapshot& /*session*/) const {  // the board's own
  campaign::StackFigures f;
  if (!board_) return f;
  const auto b = board_->snapshot();
  f.armed = b.armed;
  f.mode = b.mode;
  f.landed_state = b.landed_state;
  f.hil_sensor_received = b.hil_sensor_received;
  f.hil_gps_received = b.hil_gps_received;
  f.odometry_received = b.odometry_received;
  f.actuators_sent = b.actuators_sent;
  f.malformed = b.malformed;
  return f;
}

}  // namespace hitl::cli
