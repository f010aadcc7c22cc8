// Control allocation for the x500 from the CA_ROTORi_PX/PY/KM geometry, as PX4's
// ActuatorEffectivenessRotors + ControlAllocationPseudoInverse do it:
//   effectiveness B (per motor i, thrust coefficient 1, rotor axis -z FRD):
//     roll = -PY_i,  pitch = +PX_i,  yaw = KM_i,  thrust = 1
//   mix M = pinv(B), columns normalized PX4's way (roll and pitch by the same RMS-based scale, yaw by
//   its largest entry, thrust by its mean), so torque commands are -1..1 and thrust 0..1.
//   Per-motor thrust t = T + M_rp (roll, pitch) + k M_y yaw, with roll/pitch scaled down to fit and
//   the collective shifted to keep them (thrust and roll/pitch before yaw), k in 0..1 the yaw that
//   still fits; then the motor command inverts THR_MDL_FAC's thrust curve:
//     t = (1 - f) u + f u^2   (f = 1: u = sqrt(t), the gz motor's thrust = kF (1000 u)^2)
// Motor order (PX4): 0 front-right CCW, 1 back-left CCW, 2 front-left CW, 3 back-right CW.
#pragma once

#include <array>

#include <Eigen/Core>

#include "emulator/flight/flight_params.h"

namespace hitl::flight {

struct RotorGeometry {
  double px_FRD_m = 0.0;
  double py_FRD_m = 0.0;
  double km = 0.0;  ///< > 0: counter-clockwise (seen from above); its drag yaws the body clockwise (+z FRD)
  bool operator==(const RotorGeometry&) const = default;
};
using QuadGeometry = std::array<RotorGeometry, 4>;

QuadGeometry geometry_from(const FlightParams& params);

struct MixerOutput {
  std::array<double, 4> thrust{};  ///< per-motor thrust, fraction of one motor's maximum
  std::array<double, 4> u{};       ///< motor commands 0..1
  std::array<bool, 3> saturated_positive{};  ///< roll, pitch, yaw could not get all they asked for
  std::array<bool, 3> saturated_negative{};
};

class Mixer {
 public:
  explicit Mixer(const QuadGeometry& geometry);
  /// torque: normalized roll, pitch, yaw (FRD); collective: 0..1.
  MixerOutput mix(const Eigen::Vector3d& torque, double collective, double thr_mdl_fac) const;
  const QuadGeometry& geometry() const { return geometry_; }
  /// Columns roll, pitch, yaw, thrust; row per motor.
  const Eigen::Matrix4d& mix_matrix() const { return mix_; }

 private:
  QuadGeometry geometry_;
  Eigen::Matrix4d mix_;
};

/// Motor command u for a thrust fraction t under t = (1 - f) u + f u^2.
double motor_command_from_thrust(double thrust_fraction, double thr_mdl_fac);

}  // namespace hitl::flight
