#include "base/mavlink/hil_sensor_fields.h"

#include <array>
#include <utility>

namespace hitl::mavlink::hil_sensor {

std::string describe_fields_updated(uint32_t fields_updated) {
  static constexpr std::array<std::pair<uint32_t, const char*>, 5> kGroups = {
      {{kAccel, "accel"}, {kGyro, "gyro"}, {kMag, "mag"}, {kBaro, "baro"}, {kDiffPressure, "diff_pressure"}}};
  static constexpr std::array<const char*, 13> kBits = {"xacc", "yacc", "zacc", "xgyro", "ygyro",
                                                        "zgyro", "xmag", "ymag", "zmag", "abs_pressure",
                                                        "diff_pressure", "pressure_alt", "temperature"};
  std::string out;
  auto add = [&out](const std::string& word) {
    if (!out.empty()) out += ' ';
    out += word;
  };
  uint32_t named = 0;
  for (const auto& [mask, name] : kGroups) {
    if ((fields_updated & mask) == mask) {
      add(name);
      named |= mask;
    }
  }
  for (std::size_t bit = 0; bit < kBits.size(); ++bit) {
    const uint32_t m = 1U << bit;
    if ((fields_updated & m) && !(named & m)) add(std::string(kBits[bit]) + "(partial)");
  }
  if (fields_updated & kReset) add("reset");
  if (out.empty()) out = "none";
  return out;
}

}  // namespace hitl::mavlink::hil_sensor
