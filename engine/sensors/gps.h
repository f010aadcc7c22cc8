// GPS receiver: WGS-84 position from the local position and home (GeographicLib), NED velocity,
// ground speed, course over ground, eph/epv, 3D fix, satellites. Errors per axis (E, N, U):
//   position = truth + e + white,  e: Gauss-Markov with stationary sigma (horizontal/vertical)
//              and correlation time (a slowly wandering offset, like a real receiver's)
//   velocity = truth + velocity_noise N(0,1)
//   eph, epv  the constants, or with accuracy_follows_error the RMS of the error now (wander and
//             white noise) as a receiver's own estimate moves with it
// With delay_s > 0 each sample reports the fix taken delay_s earlier.
#pragma once

#include <cstdint>
#include <deque>

#include <Eigen/Core>

#include "engine/model/random_stream.h"
#include "engine/model/vehicle_config.h"
#include "engine/model/vehicle_state.h"
#include "engine/model/world_config.h"
#include "engine/sensors/geodesy.h"
#include "engine/sensors/samples.h"

namespace hitl::sensors {

class Gps {
 public:
  Gps(const model::GpsConfig& config, const model::HomeConfig& home, std::uint64_t seed);
  GpsSample sample(const model::VehicleState& state, double t_s);
  void reset();
  double rate_hz() const { return config_.rate_hz; }
  /// The current wandering position error, ENU [m].
  const Eigen::Vector3d& position_error_ENU_m() const { return error_ENU_m_; }
  /// The reported position error (wander and white noise) and velocity noise x k from the next
  /// fix (the gps-noise fault; 1: as configured). The processes draw as before.
  void set_noise_scale(double k) { noise_scale_ = k; }

 private:
  GpsSample measure(const model::VehicleState& state, double t_s);

  model::GpsConfig config_;
  LocalGeodesy geodesy_;
  std::uint64_t seed_;
  model::RandomStream rng_;
  Eigen::Vector3d error_ENU_m_ = Eigen::Vector3d::Zero();
  double last_t_s_ = -1.0;
  std::deque<GpsSample> pending_;  ///< fixes not yet old enough to report (delay)
  double noise_scale_ = 1.0;
};

/// Course over ground, 0..360 deg from north towards east, of a NED velocity.
double course_over_ground_deg(const Eigen::Vector3d& v_NED_m_s);

}  // namespace hitl::sensors
