#include "engine/board/restart_params.h"

#include <array>

namespace hitl::board {
namespace {

constexpr std::array<const char*, 5> kExact{"SYS_AUTOSTART", "SYS_HITL", "SYS_MC_EST_GROUP", "IMU_GYRO_RATEMAX", "EKF2_MAG_TYPE"};
constexpr std::array<const char*, 2> kPrefixes{"CBRK_", "SENS_EN_"};

}  // namespace

bool needs_restart(const std::string& name) {
  for (const char* e : kExact)
    if (name == e) return true;
  for (const char* p : kPrefixes)
    if (name.rfind(p, 0) == 0) return true;
  return false;
}

std::vector<std::string> restart_params(const std::vector<std::string>& names) {
  std::vector<std::string> out;
  for (const auto& n : names)
    if (needs_restart(n)) out.push_back(n);
  return out;
}

std::string restart_param_rule_text() {
  std::string text;
  for (const char* e : kExact) text += std::string(text.empty() ? "" : ", ") + e;
  for (const char* p : kPrefixes) text += std::string(", ") + p + "*";
  return text;
}

}  // namespace hitl::board
