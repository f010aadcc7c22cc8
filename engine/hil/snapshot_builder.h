// Builds a SessionSnapshot from the session's parts: what each part counts, read in one place.
// The truth position and attitude go to the wire's NED/FRD through engine/frames.
#pragma once

#include "engine/hil/client_services.h"
#include "engine/hil/data_paths.h"
#include "engine/hil/pacer.h"
#include "engine/hil/session_snapshot.h"
#include "engine/hil/stack_link.h"
#include "engine/hil/traffic.h"
#include "base/mavlink/message_set.h"
#include "engine/model/touchdown_monitor.h"
#include "engine/model/vehicle_state.h"
#include "engine/sensors/sensor_suite.h"
#include "engine/vehicle/trajectory_flight.h"

namespace hitl::hil {

/// Everything a snapshot is read from; pilot may be null (no -t).
struct SnapshotSources {
  const SessionConfig& config;
  const mavlink::MessageSet& messages;
  const model::VehicleState& state;
  double rest_altitude_m = 0;  ///< the body origin's height at rest at home: altitude 0
  double sim_time_s = 0;       ///< across resets
  double wall_time_s = 0;      ///< since the start
  double recent_real_time_factor = 0;
  const Traffic& traffic;
  const StackLink& stack;
  const ClientServices& clients;
  const PacerStats& pacer;
  const sensors::SensorSuite& sensors;
  const model::TouchdownMonitor& touchdowns;
  const vehicle::TrajectoryFlight* pilot = nullptr;
  std::vector<DataPathStats> paths;
  bool paused = false;
  uint64_t resets = 0;
  std::string record_error;
};

SessionSnapshot make_snapshot(const SnapshotSources& in);

}  // namespace hitl::hil
