#include "emulator/flight/flight_params.h"

#include <array>
#include <cmath>

namespace hitl::flight {
namespace {

// One row per FlightParams member, in declaration order; the defaults repeat the initializers
// (flight_params_test checks they agree).
constexpr std::array kTable{
    ParamInfo{"MPC_XY_P", ParamType::Float, 0.95, 0, 2, "1/s", &FlightParams::MPC_XY_P, nullptr},
    ParamInfo{"MPC_Z_P", ParamType::Float, 1.0, 0, 1.5, "1/s", &FlightParams::MPC_Z_P, nullptr},
    ParamInfo{"MPC_XY_VEL_P_ACC", ParamType::Float, 1.8, 1.2, 5, "1/s", &FlightParams::MPC_XY_VEL_P_ACC, nullptr},
    ParamInfo{"MPC_XY_VEL_I_ACC", ParamType::Float, 0.4, 0, 60, "1/s^2", &FlightParams::MPC_XY_VEL_I_ACC, nullptr},
    ParamInfo{"MPC_XY_VEL_D_ACC", ParamType::Float, 0.2, 0.1, 2, "", &FlightParams::MPC_XY_VEL_D_ACC, nullptr},
    ParamInfo{"MPC_Z_VEL_P_ACC", ParamType::Float, 4.0, 2, 15, "1/s", &FlightParams::MPC_Z_VEL_P_ACC, nullptr},
    ParamInfo{"MPC_Z_VEL_I_ACC", ParamType::Float, 2.0, 0.2, 3, "1/s^2", &FlightParams::MPC_Z_VEL_I_ACC, nullptr},
    ParamInfo{"MPC_Z_VEL_D_ACC", ParamType::Float, 0.0, 0, 2, "", &FlightParams::MPC_Z_VEL_D_ACC, nullptr},
    ParamInfo{"MPC_THR_HOVER", ParamType::Float, 0.59, 0.1, 0.8, "", &FlightParams::MPC_THR_HOVER, nullptr},
    ParamInfo{"MPC_THR_MIN", ParamType::Float, 0.12, 0.05, 1, "", &FlightParams::MPC_THR_MIN, nullptr},
    ParamInfo{"MPC_THR_MAX", ParamType::Float, 1.0, 0, 1, "", &FlightParams::MPC_THR_MAX, nullptr},
    ParamInfo{"MPC_THR_XY_MARG", ParamType::Float, 0.3, 0, 0.5, "", &FlightParams::MPC_THR_XY_MARG, nullptr},
    ParamInfo{"MPC_TILTMAX_AIR", ParamType::Float, 45.0, 20, 89, "deg", &FlightParams::MPC_TILTMAX_AIR, nullptr},
    ParamInfo{"MPC_XY_VEL_MAX", ParamType::Float, 12.0, 0, 20, "m/s", &FlightParams::MPC_XY_VEL_MAX, nullptr},
    ParamInfo{"MPC_VEL_MANUAL", ParamType::Float, 10.0, 0.5, 20, "m/s", &FlightParams::MPC_VEL_MANUAL, nullptr},
    ParamInfo{"MPC_Z_VEL_MAX_UP", ParamType::Float, 3.0, 0.5, 8, "m/s", &FlightParams::MPC_Z_VEL_MAX_UP, nullptr},
    ParamInfo{"MPC_Z_VEL_MAX_DN", ParamType::Float, 1.5, 0.5, 4, "m/s", &FlightParams::MPC_Z_VEL_MAX_DN, nullptr},
    ParamInfo{"MPC_ACC_HOR", ParamType::Float, 3.0, 1, 15, "m/s^2", &FlightParams::MPC_ACC_HOR, nullptr},
    ParamInfo{"MPC_ACC_UP_MAX", ParamType::Float, 4.0, 1, 15, "m/s^2", &FlightParams::MPC_ACC_UP_MAX, nullptr},
    ParamInfo{"MPC_HOLD_DZ", ParamType::Float, 0.1, 0, 1, "", &FlightParams::MPC_HOLD_DZ, nullptr},
    ParamInfo{"MPC_MAN_Y_MAX", ParamType::Float, 150.0, 0, 400, "deg/s", &FlightParams::MPC_MAN_Y_MAX, nullptr},
    ParamInfo{"MPC_MAN_TILT_MAX", ParamType::Float, 35.0, 0, 90, "deg", &FlightParams::MPC_MAN_TILT_MAX, nullptr},
    ParamInfo{"MPC_MANTHR_MIN", ParamType::Float, 0.08, 0, 1, "", &FlightParams::MPC_MANTHR_MIN, nullptr},
    ParamInfo{"MPC_LAND_SPEED", ParamType::Float, 0.7, 0.3, 4, "m/s", &FlightParams::MPC_LAND_SPEED, nullptr},
    ParamInfo{"MPC_TKO_SPEED", ParamType::Float, 1.5, 0.5, 5, "m/s", &FlightParams::MPC_TKO_SPEED, nullptr},
    ParamInfo{"MIS_TAKEOFF_ALT", ParamType::Float, 2.5, 0, 80, "m", &FlightParams::MIS_TAKEOFF_ALT, nullptr},
    ParamInfo{"MC_ROLL_P", ParamType::Float, 6.5, 0, 12, "1/s", &FlightParams::MC_ROLL_P, nullptr},
    ParamInfo{"MC_PITCH_P", ParamType::Float, 6.5, 0, 12, "1/s", &FlightParams::MC_PITCH_P, nullptr},
    ParamInfo{"MC_YAW_P", ParamType::Float, 2.8, 0, 5, "1/s", &FlightParams::MC_YAW_P, nullptr},
    ParamInfo{"MC_YAW_WEIGHT", ParamType::Float, 0.4, 0, 1, "", &FlightParams::MC_YAW_WEIGHT, nullptr},
    ParamInfo{"MC_ROLLRATE_MAX", ParamType::Float, 220.0, 0, 1800, "deg/s", &FlightParams::MC_ROLLRATE_MAX, nullptr},
    ParamInfo{"MC_PITCHRATE_MAX", ParamType::Float, 220.0, 0, 1800, "deg/s", &FlightParams::MC_PITCHRATE_MAX, nullptr},
    ParamInfo{"MC_YAWRATE_MAX", ParamType::Float, 200.0, 0, 1800, "deg/s", &FlightParams::MC_YAWRATE_MAX, nullptr},
    ParamInfo{"MC_ROLLRATE_P", ParamType::Float, 0.15, 0.01, 0.5, "", &FlightParams::MC_ROLLRATE_P, nullptr},
    ParamInfo{"MC_ROLLRATE_I", ParamType::Float, 0.2, 0, 10, "", &FlightParams::MC_ROLLRATE_I, nullptr},
    ParamInfo{"MC_ROLLRATE_D", ParamType::Float, 0.003, 0, 0.01, "", &FlightParams::MC_ROLLRATE_D, nullptr},
    ParamInfo{"MC_RR_INT_LIM", ParamType::Float, 0.3, 0, 1, "", &FlightParams::MC_RR_INT_LIM, nullptr},
    ParamInfo{"MC_PITCHRATE_P", ParamType::Float, 0.15, 0.01, 0.6, "", &FlightParams::MC_PITCHRATE_P, nullptr},
    ParamInfo{"MC_PITCHRATE_I", ParamType::Float, 0.2, 0, 10, "", &FlightParams::MC_PITCHRATE_I, nullptr},
    ParamInfo{"MC_PITCHRATE_D", ParamType::Float, 0.003, 0, 0.01, "", &FlightParams::MC_PITCHRATE_D, nullptr},
    ParamInfo{"MC_PR_INT_LIM", ParamType::Float, 0.3, 0, 1, "", &FlightParams::MC_PR_INT_LIM, nullptr},
    ParamInfo{"MC_YAWRATE_P", ParamType::Float, 0.2, 0, 0.6, "", &FlightParams::MC_YAWRATE_P, nullptr},
    ParamInfo{"MC_YAWRATE_I", ParamType::Float, 0.1, 0, 10, "", &FlightParams::MC_YAWRATE_I, nullptr},
    ParamInfo{"MC_YAWRATE_D", ParamType::Float, 0.0, 0, 0.01, "", &FlightParams::MC_YAWRATE_D, nullptr},
    ParamInfo{"MC_YR_INT_LIM", ParamType::Float, 0.3, 0, 1, "", &FlightParams::MC_YR_INT_LIM, nullptr},
    ParamInfo{"CA_ROTOR_COUNT", ParamType::Int32, 4, 4, 4, "", nullptr, &FlightParams::CA_ROTOR_COUNT},
    ParamInfo{"CA_ROTOR0_PX", ParamType::Float, 0.174, -100, 100, "m", &FlightParams::CA_ROTOR0_PX, nullptr},
    ParamInfo{"CA_ROTOR0_PY", ParamType::Float, 0.174, -100, 100, "m", &FlightParams::CA_ROTOR0_PY, nullptr},
    ParamInfo{"CA_ROTOR0_KM", ParamType::Float, 0.05, -1, 1, "", &FlightParams::CA_ROTOR0_KM, nullptr},
    ParamInfo{"CA_ROTOR1_PX", ParamType::Float, -0.174, -100, 100, "m", &FlightParams::CA_ROTOR1_PX, nullptr},
    ParamInfo{"CA_ROTOR1_PY", ParamType::Float, -0.174, -100, 100, "m", &FlightParams::CA_ROTOR1_PY, nullptr},
    ParamInfo{"CA_ROTOR1_KM", ParamType::Float, 0.05, -1, 1, "", &FlightParams::CA_ROTOR1_KM, nullptr},
    ParamInfo{"CA_ROTOR2_PX", ParamType::Float, 0.174, -100, 100, "m", &FlightParams::CA_ROTOR2_PX, nullptr},
    ParamInfo{"CA_ROTOR2_PY", ParamType::Float, -0.174, -100, 100, "m", &FlightParams::CA_ROTOR2_PY, nullptr},
    ParamInfo{"CA_ROTOR2_KM", ParamType::Float, -0.05, -1, 1, "", &FlightParams::CA_ROTOR2_KM, nullptr},
    ParamInfo{"CA_ROTOR3_PX", ParamType::Float, -0.174, -100, 100, "m", &FlightParams::CA_ROTOR3_PX, nullptr},
    ParamInfo{"CA_ROTOR3_PY", ParamType::Float, 0.174, -100, 100, "m", &FlightParams::CA_ROTOR3_PY, nullptr},
    ParamInfo{"CA_ROTOR3_KM", ParamType::Float, -0.05, -1, 1, "", &FlightParams::CA_ROTOR3_KM, nullptr},
    ParamInfo{"THR_MDL_FAC", ParamType::Float, 1.0, 0, 1, "", &FlightParams::THR_MDL_FAC, nullptr},
    ParamInfo{"HITL_MOT_IDLE", ParamType::Float, 0.1, 0, 0.5, "", &FlightParams::HITL_MOT_IDLE, nullptr},
    ParamInfo{"COM_DISARM_LAND", ParamType::Float, 2.0, -1, 20, "s", &FlightParams::COM_DISARM_LAND, nullptr},
    ParamInfo{"COM_DISARM_PRFLT", ParamType::Float, 10.0, -1, 20, "s", &FlightParams::COM_DISARM_PRFLT, nullptr},
    ParamInfo{"COM_RC_LOSS_T", ParamType::Float, 0.5, 0, 35, "s", &FlightParams::COM_RC_LOSS_T, nullptr},
    ParamInfo{"COM_RC_OVERRIDE", ParamType::Int32, 1, 0, 3, "", nullptr, &FlightParams::COM_RC_OVERRIDE},
    ParamInfo{"COM_RC_STICK_OV", ParamType::Float, 30.0, 5, 80, "%", &FlightParams::COM_RC_STICK_OV, nullptr},
    ParamInfo{"LNDMC_Z_VEL_MAX", ParamType::Float, 0.5, 0.1, 10, "m/s", &FlightParams::LNDMC_Z_VEL_MAX, nullptr},
    ParamInfo{"LNDMC_XY_VEL_MAX", ParamType::Float, 1.5, 0.1, 10, "m/s", &FlightParams::LNDMC_XY_VEL_MAX, nullptr},
    ParamInfo{"LNDMC_TRIG_TIME", ParamType::Float, 1.0, 0.1, 10, "s", &FlightParams::LNDMC_TRIG_TIME, nullptr},
    ParamInfo{"EKF2_MAG_DECL", ParamType::Float, 3.2737, -180, 180, "deg", &FlightParams::EKF2_MAG_DECL, nullptr},
    ParamInfo{"HITL_MAG_INCL", ParamType::Float, -100.0, -100, 90, "deg", &FlightParams::HITL_MAG_INCL, nullptr},
    ParamInfo{"EKF2_REQ_EPH", ParamType::Float, 3.0, 1, 100, "m", &FlightParams::EKF2_REQ_EPH, nullptr},
    ParamInfo{"EKF2_REQ_NSATS", ParamType::Int32, 6, 4, 12, "", nullptr, &FlightParams::EKF2_REQ_NSATS},
    ParamInfo{"EKF2_REQ_GPS_H", ParamType::Float, 5.0, 0.1, 100, "s", &FlightParams::EKF2_REQ_GPS_H, nullptr},
    ParamInfo{"EKF2_GPS_P_NOISE", ParamType::Float, 0.5, 0.01, 10, "m", &FlightParams::EKF2_GPS_P_NOISE, nullptr},
    ParamInfo{"EKF2_GPS_V_NOISE", ParamType::Float, 0.3, 0.01, 5, "m/s", &FlightParams::EKF2_GPS_V_NOISE, nullptr},
    ParamInfo{"EKF2_BARO_NOISE", ParamType::Float, 0.3, 0.01, 15, "m", &FlightParams::EKF2_BARO_NOISE, nullptr},
    ParamInfo{"EKF2_HEAD_NOISE", ParamType::Float, 0.3, 0.0001, 1, "rad", &FlightParams::EKF2_HEAD_NOISE, nullptr},
    ParamInfo{"EKF2_ACC_NOISE", ParamType::Float, 0.35, 0.01, 2, "m/s^2", &FlightParams::EKF2_ACC_NOISE, nullptr},
    ParamInfo{"EKF2_ACC_B_NOISE", ParamType::Float, 0.003, 0, 0.1, "m/s^3", &FlightParams::EKF2_ACC_B_NOISE, nullptr},
    ParamInfo{"EKF2_GPS_P_GATE", ParamType::Float, 5.0, 1, 10, "SD", &FlightParams::EKF2_GPS_P_GATE, nullptr},
    ParamInfo{"EKF2_GPS_V_GATE", ParamType::Float, 5.0, 1, 10, "SD", &FlightParams::EKF2_GPS_V_GATE, nullptr},
    ParamInfo{"EKF2_BARO_GATE", ParamType::Float, 5.0, 1, 10, "SD", &FlightParams::EKF2_BARO_GATE, nullptr},
    ParamInfo{"EKF2_MAG_GATE", ParamType::Float, 3.0, 1, 10, "SD", &FlightParams::EKF2_MAG_GATE, nullptr},
    ParamInfo{"ATT_W_ACC", ParamType::Float, 0.2, 0, 1, "", &FlightParams::ATT_W_ACC, nullptr},
    ParamInfo{"ATT_W_MAG", ParamType::Float, 0.1, 0, 1, "", &FlightParams::ATT_W_MAG, nullptr},
    ParamInfo{"ATT_W_GYRO_BIAS", ParamType::Float, 0.1, 0, 1, "", &FlightParams::ATT_W_GYRO_BIAS, nullptr},
    ParamInfo{"ATT_BIAS_MAX", ParamType::Float, 0.05, 0, 2, "rad/s", &FlightParams::ATT_BIAS_MAX, nullptr},
    ParamInfo{"ATT_ACC_COMP", ParamType::Int32, 1, 0, 1, "", nullptr, &FlightParams::ATT_ACC_COMP},
    ParamInfo{"HITL_ATT_ALIGN", ParamType::Float, 10.0, 1, 50, "", &FlightParams::HITL_ATT_ALIGN, nullptr},
};

}  // namespace

std::span<const ParamInfo> param_table() { return kTable; }

const ParamInfo* find_param(std::string_view name) {
  for (const ParamInfo& p : kTable) {
    if (name == p.name) return &p;
  }
  return nullptr;
}

std::optional<double> get_param(const FlightParams& params, std::string_view name) {
  const ParamInfo* p = find_param(name);
  if (p == nullptr) return std::nullopt;
  return p->type == ParamType::Float ? static_cast<double>(params.*(p->f)) : static_cast<double>(params.*(p->i));
}

std::string to_string(ParamResult result) {
  switch (result) {
    case ParamResult::Success: return "Success";
    case ParamResult::UnknownName: return "UnknownName";
    case ParamResult::OutOfRange: return "OutOfRange";
    case ParamResult::NotANumber: return "NotANumber";
  }
  return "Unknown";
}

ParamResult set_param(FlightParams& params, std::string_view name, double value) {
  const ParamInfo* p = find_param(name);
  if (p == nullptr) return ParamResult::UnknownName;
  if (!std::isfinite(value)) return ParamResult::NotANumber;
  if (p->type == ParamType::Int32) value = std::round(value);
  if (value < p->min_value || value > p->max_value) return ParamResult::OutOfRange;
  if (p->type == ParamType::Float) {
    params.*(p->f) = static_cast<float>(value);
  } else {
    params.*(p->i) = static_cast<std::int32_t>(value);
  }
  return ParamResult::Success;
}

}  // namespace hitl::flight
