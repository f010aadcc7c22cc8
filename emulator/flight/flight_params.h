// Every tunable of the flight core under its PX4 name, as the PARAM protocol sees it (float or
// int32). The struct's initializers are the defaults; param_table() lists name, type, default,
// range, unit and member for PARAM_REQUEST_LIST / PARAM_SET. Names without a PX4 counterpart carry
// the HITL_ prefix.
#pragma once

#include <cstdint>
#include <numbers>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace hitl::flight {

/// Angles in the parameters are in degrees (as PX4's); the controllers work in radians.
inline constexpr double kDegToRad = std::numbers::pi / 180.0;

struct FlightParams {
  // Position controller (mc_pos_control)
  float MPC_XY_P = 0.95f;           ///< 1/s
  float MPC_Z_P = 1.0f;             ///< 1/s
  float MPC_XY_VEL_P_ACC = 1.8f;    ///< 1/s
  float MPC_XY_VEL_I_ACC = 0.4f;    ///< 1/s^2
  float MPC_XY_VEL_D_ACC = 0.2f;    ///< -
  float MPC_Z_VEL_P_ACC = 4.0f;     ///< 1/s
  float MPC_Z_VEL_I_ACC = 2.0f;     ///< 1/s^2
  float MPC_Z_VEL_D_ACC = 0.0f;     ///< -
  float MPC_THR_HOVER = 0.59f;      ///< normalized thrust; x500: 20.24 N / 34.19 N
  float MPC_THR_MIN = 0.12f;
  float MPC_THR_MAX = 1.0f;
  float MPC_THR_XY_MARG = 0.3f;
  float MPC_TILTMAX_AIR = 45.0f;    ///< deg
  float MPC_XY_VEL_MAX = 12.0f;     ///< m/s
  float MPC_VEL_MANUAL = 10.0f;     ///< m/s, full stick in position mode
  float MPC_Z_VEL_MAX_UP = 3.0f;    ///< m/s
  float MPC_Z_VEL_MAX_DN = 1.5f;    ///< m/s
  float MPC_ACC_HOR = 3.0f;         ///< m/s^2, stick velocity slew
  float MPC_ACC_UP_MAX = 4.0f;      ///< m/s^2, stick vertical velocity slew
  float MPC_HOLD_DZ = 0.1f;         ///< stick deadzone
  float MPC_MAN_Y_MAX = 150.0f;     ///< deg/s, full yaw stick
  float MPC_MAN_TILT_MAX = 35.0f;   ///< deg, full roll/pitch stick in Stabilized
  float MPC_MANTHR_MIN = 0.08f;     ///< Stabilized thrust at zero throttle
  float MPC_LAND_SPEED = 0.7f;      ///< m/s
  float MPC_TKO_SPEED = 1.5f;       ///< m/s
  float MIS_TAKEOFF_ALT = 2.5f;     ///< m above home
  // Attitude and rate controllers (mc_att_control, mc_rate_control)
  float MC_ROLL_P = 6.5f;           ///< 1/s
  float MC_PITCH_P = 6.5f;
  float MC_YAW_P = 2.8f;
  float MC_YAW_WEIGHT = 0.4f;
  float MC_ROLLRATE_MAX = 220.0f;   ///< deg/s
  float MC_PITCHRATE_MAX = 220.0f;
  float MC_YAWRATE_MAX = 200.0f;
  float MC_ROLLRATE_P = 0.15f;
  float MC_ROLLRATE_I = 0.2f;
  float MC_ROLLRATE_D = 0.003f;
  float MC_RR_INT_LIM = 0.3f;
  float MC_PITCHRATE_P = 0.15f;
  float MC_PITCHRATE_I = 0.2f;
  float MC_PITCHRATE_D = 0.003f;
  float MC_PR_INT_LIM = 0.3f;
  float MC_YAWRATE_P = 0.2f;
  float MC_YAWRATE_I = 0.1f;
  float MC_YAWRATE_D = 0.0f;
  float MC_YR_INT_LIM = 0.3f;
  // Control allocation: the spec's x500 geometry (FRD m; KM > 0 counter-clockwise)
  std::int32_t CA_ROTOR_COUNT = 4;
  float CA_ROTOR0_PX = 0.174f, CA_ROTOR0_PY = 0.174f, CA_ROTOR0_KM = 0.05f;
  float CA_ROTOR1_PX = -0.174f, CA_ROTOR1_PY = -0.174f, CA_ROTOR1_KM = 0.05f;
  float CA_ROTOR2_PX = 0.174f, CA_ROTOR2_PY = -0.174f, CA_ROTOR2_KM = -0.05f;
  float CA_ROTOR3_PX = -0.174f, CA_ROTOR3_PY = 0.174f, CA_ROTOR3_KM = -0.05f;
  float THR_MDL_FAC = 1.0f;         ///< thrust = (1-f) u + f u^2; the gz motor is f = 1
  float HITL_MOT_IDLE = 0.1f;       ///< motor command while armed on the ground (spins, no lift)
  // Commander and land detector
  float COM_DISARM_LAND = 2.0f;     ///< s after touchdown; <= 0 off
  float COM_DISARM_PRFLT = 10.0f;   ///< s armed without takeoff; <= 0 off
  float COM_RC_LOSS_T = 0.5f;       ///< s without sticks -> sticks centred
  std::int32_t COM_RC_OVERRIDE = 1; ///< bit 0: sticks take over from auto modes (hold)
  float COM_RC_STICK_OV = 30.0f;    ///< % stick deflection for that take-over
  // No COM_ARM_EKF_POS/VEL/HGT/YAW: PX4 v1.16 removed them (PR #23411); the estimator's preflight
  // check uses EKF2's fixed test-ratio limit instead (estimator.cpp, kPreflightTestRatioMax).
  float LNDMC_Z_VEL_MAX = 0.5f;     ///< m/s
  float LNDMC_XY_VEL_MAX = 1.5f;    ///< m/s
  float LNDMC_TRIG_TIME = 1.0f;     ///< s, maybe-landed -> landed
  // Estimator
  float EKF2_MAG_DECL = 3.2737f;    ///< deg, east positive (WMM at PX4's SITL home)
  float HITL_MAG_INCL = -100.0f;    ///< deg, down positive (63.1442 at home); < -90: heading-only (default)
  float EKF2_REQ_EPH = 3.0f;        ///< m
  std::int32_t EKF2_REQ_NSATS = 6;
  float EKF2_REQ_GPS_H = 5.0f;      ///< s of GPS fusion before "position valid" (PX4: 10)
  float EKF2_GPS_P_NOISE = 0.5f;    ///< m
  float EKF2_GPS_V_NOISE = 0.3f;    ///< m/s
  float EKF2_BARO_NOISE = 0.3f;     ///< m
  float EKF2_HEAD_NOISE = 0.3f;     ///< rad
  float EKF2_ACC_NOISE = 0.35f;     ///< m/s^2 process noise
  float EKF2_ACC_B_NOISE = 0.003f;  ///< m/s^3
  float EKF2_GPS_P_GATE = 5.0f;     ///< sigma
  float EKF2_GPS_V_GATE = 5.0f;
  float EKF2_BARO_GATE = 5.0f;
  float EKF2_MAG_GATE = 3.0f;
  float ATT_W_ACC = 0.2f;           ///< attitude_estimator_q gains, in flight
  float ATT_W_MAG = 0.1f;
  float ATT_W_GYRO_BIAS = 0.1f;
  float ATT_BIAS_MAX = 0.05f;       ///< rad/s
  std::int32_t ATT_ACC_COMP = 1;    ///< remove the estimated motion acceleration from the accel
  float HITL_ATT_ALIGN = 10.0f;    ///< gain multiplier while disarmed (fast levelling and gyro bias)
};

enum class ParamType { Float, Int32 };

struct ParamInfo {
  const char* name;  ///< at most 16 characters (PARAM_VALUE param_id)
  ParamType type;
  double default_value;
  double min_value;
  double max_value;
  const char* unit;
  float FlightParams::* f = nullptr;         ///< set for Float
  std::int32_t FlightParams::* i = nullptr;  ///< set for Int32
};

/// All parameters in a stable order (PARAM_VALUE param_index = position here).
std::span<const ParamInfo> param_table();
const ParamInfo* find_param(std::string_view name);
std::optional<double> get_param(const FlightParams& params, std::string_view name);

enum class ParamResult { Success, UnknownName, OutOfRange, NotANumber };
std::string to_string(ParamResult result);
/// Sets by name; Int32 values are rounded. The value is checked against the table's range.
ParamResult set_param(FlightParams& params, std::string_view name, double value);

}  // namespace hitl::flight
