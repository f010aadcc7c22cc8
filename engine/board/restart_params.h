// Which PX4 parameters take effect only when PX4 starts again. PX4's parameter metadata marks them
// `@reboot_required true`; of the spec's HITL set (base/contract/hitl-defaults.params) these are
// SYS_AUTOSTART, SYS_HITL (system_params.c), IMU_GYRO_RATEMAX (imu_gyro_parameters.c),
// EKF2_MAG_TYPE (ekf2_params.c), the circuit breakers CBRK_* (circuit_breaker_params.c) and,
// beyond the set, the sensor enables SENS_EN_* and SYS_MC_EST_GROUP. On a VOXL2 "restart" is PX4's
// process (voxl-px4-hitl), not the board: the parameters live in PX4's memory and its file.
#pragma once

#include <string>
#include <vector>

namespace hitl::board {

bool needs_restart(const std::string& param_name);
/// The names of `names` that need one, in order.
std::vector<std::string> restart_params(const std::vector<std::string>& names);
/// "SYS_AUTOSTART, SYS_HITL, ..., CBRK_*, SENS_EN_*": the rule, for messages and docs.
std::string restart_param_rule_text();

}  // namespace hitl::board
