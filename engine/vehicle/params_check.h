// The board's parameters against the spec's HITL set (hitl_default_params()): what `hitl params
// check` / `diff` print and what `hitl doctor`'s parameter checks judge. One row per parameter of
// the set, in its order, each with the command that fixes it.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "engine/vehicle/params_file.h"

namespace hitl::vehicle {

/// The spec's parameter categories (its "HITL Default Parameters" tables).
enum class ParamGroup { System, Calibration, Ekf2, Arming, ControlAllocation };

/// "system", "calibration", "EKF2", "arming", "control allocation".
const char* to_string(ParamGroup group);
/// The category of a parameter of the HITL set, by PX4's name prefix (SYS_/IMU_, CAL_, EKF2_,
/// CBRK_/COM_, CA_); System for anything else.
ParamGroup param_group(const std::string& name);

struct ParamCheckRow {
  std::string name;
  ParamGroup group = ParamGroup::System;
  ParamValue expected;
  std::optional<ParamValue> board;  ///< none: the board has no such parameter
  bool ok = false;                  ///< the board has it, with the expected value
  bool absent = false;              ///< the board has no such parameter (not a wrong value)
  std::string note;                 ///< absent: which firmware lacks it and what replaces it (param_notes.h), if known
  std::string fix;                  ///< empty when ok
};

/// Every parameter of `expected` against `board` (a full download).
std::vector<ParamCheckRow> check_params(const std::vector<Param>& board, const std::vector<Param>& expected);

/// Whether a row fails the check: a wrong value always; an absent parameter only when `strict`.
bool row_fails(const ParamCheckRow& row, bool strict);

}  // namespace hitl::vehicle
