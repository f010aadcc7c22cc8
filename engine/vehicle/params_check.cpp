#include "engine/vehicle/params_check.h"

#include <map>

#include "engine/vehicle/param_notes.h"

namespace hitl::vehicle {

const char* to_string(ParamGroup group) {
  switch (group) {
    case ParamGroup::System: return "system";
    case ParamGroup::Calibration: return "calibration";
    case ParamGroup::Ekf2: return "EKF2";
    case ParamGroup::Arming: return "arming";
    case ParamGroup::ControlAllocation: return "control allocation";
  }
  return "?";
}

ParamGroup param_group(const std::string& name) {
  auto starts = [&](const char* prefix) { return name.rfind(prefix, 0) == 0; };
  if (starts("CAL_")) return ParamGroup::Calibration;
  if (starts("EKF2_")) return ParamGroup::Ekf2;
  if (starts("CBRK_") || starts("COM_")) return ParamGroup::Arming;
  if (starts("CA_")) return ParamGroup::ControlAllocation;
  return ParamGroup::System;
}

std::vector<ParamCheckRow> check_params(const std::vector<Param>& board, const std::vector<Param>& expected) {
  std::map<std::string, ParamValue> on_board;
  for (const auto& p : board) on_board[p.name] = p.value;
  std::vector<ParamCheckRow> rows;
  rows.reserve(expected.size());
  for (const auto& p : expected) {
    ParamCheckRow row;
    row.name = p.name;
    row.group = param_group(p.name);
    row.expected = p.value;
    if (auto it = on_board.find(p.name); it != on_board.end()) row.board = it->second;
    row.ok = row.board && *row.board == p.value;
    row.absent = !row.board;
    if (row.absent) {
      if (const AbsentParamNote* note = find_absent_note(p.name)) row.note = "not in " + note->firmware + ": " + note->replacement;
      row.fix = "this firmware lacks " + p.name + " (a failure only with --strict)";
    } else if (!row.ok) {
      row.fix = "hitl params set " + p.name + " " + p.value.to_string() + "  (or: hitl params reset)";
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

bool row_fails(const ParamCheckRow& row, bool strict) { return !row.ok && (!row.absent || strict); }

}  // namespace hitl::vehicle
