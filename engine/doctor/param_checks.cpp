#include "engine/doctor/param_checks.h"

#include <algorithm>

#include "base/contract/device_ids.h"
#include "engine/doctor/check_catalog.h"

namespace hitl::doctor {
namespace {

struct GroupCheck {
  vehicle::ParamGroup group;
  const char* id;
};
constexpr GroupCheck kGroups[] = {{vehicle::ParamGroup::System, check::kParamsSystem},
                                  {vehicle::ParamGroup::Calibration, check::kParamsCalibration},
                                  {vehicle::ParamGroup::Ekf2, check::kParamsEkf2},
                                  {vehicle::ParamGroup::Arming, check::kParamsArming},
                                  {vehicle::ParamGroup::ControlAllocation, check::kParamsAllocation}};

/// What a wrong CAL_*_ID is against: the dsp_hitl device it must name.
std::string device_note(const std::string& name) {
  if (name == "CAL_ACC0_ID" || name == "CAL_GYRO0_ID") return " (dsp_hitl's IMU is " + std::to_string(target::kDeviceIdImu) + ")";
  if (name == "CAL_MAG0_ID") return " (dsp_hitl's mag is " + std::to_string(target::kDeviceIdMag) + ")";
  if (name == "CAL_BARO0_ID") return " (dsp_hitl's baro is " + std::to_string(target::kDeviceIdBaro) + ")";
  return "";
}

}  // namespace

std::vector<CheckResult> param_checks(const Expected<std::vector<vehicle::Param>>& board) {
  std::vector<CheckResult> out;
  if (!board) {
    for (const auto& g : kGroups)
      out.push_back(g.group == vehicle::ParamGroup::System
                        ? make_result(g.id, Verdict::Fail, "could not read the parameters: " + board.error().message,
                                      "hitl params show (it says what stops the download)")
                        : make_result(g.id, Verdict::Skip, "no parameters (see params-system)"));
    return out;
  }
  const auto rows = vehicle::check_params(*board, vehicle::hitl_default_params());
  for (const auto& g : kGroups) {
    std::size_t total = 0;
    std::vector<const vehicle::ParamCheckRow*> wrong;
    std::string absent;  // parameters this firmware does not have: not wrong (hitl params check --strict)
    for (const auto& r : rows) {
      if (r.group != g.group) continue;
      ++total;
      if (vehicle::row_fails(r, false)) wrong.push_back(&r);
      else if (r.absent) absent += (absent.empty() ? "" : ", ") + r.name;
    }
    if (wrong.empty()) {
      const std::size_t present = total - (absent.empty() ? 0 : static_cast<std::size_t>(std::count(absent.begin(), absent.end(), ',') + 1));
      out.push_back(make_result(g.id, Verdict::Pass, std::to_string(present) + " of " + std::to_string(total) + " " +
                                                         vehicle::to_string(g.group) + " parameters as the spec's HITL set" +
                                                         (absent.empty() ? "" : "; not on this firmware: " + absent)));
      continue;
    }
    std::string saw;
    for (const auto* r : wrong)
      saw += (saw.empty() ? "" : ", ") + r->name + " " + (r->board ? r->board->to_string() : std::string("missing")) +
             " (spec " + r->expected.to_string() + ")" + device_note(r->name);
    std::string fix = wrong.size() == 1 ? wrong.front()->fix : "hitl params reset  (sets and verifies the spec's HITL set)";
    if (g.group == vehicle::ParamGroup::System || g.group == vehicle::ParamGroup::Calibration)
      fix += "; then restart PX4, which reads these at start: adb shell voxl-px4-hitl start";
    out.push_back(make_result(g.id, Verdict::Fail, saw, fix));
  }
  return out;
}

}  // namespace hitl::doctor
