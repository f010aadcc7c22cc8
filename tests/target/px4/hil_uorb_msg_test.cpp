// One fact in three places: the spec's uORB message definitions, target/px4/msg/*.msg (what PX4
// generates hil_sensor_imu_s / hil_sensor_mag_baro_s from) and target/core/hil_uorb_messages.h
// (what the portable code fills). The .msg files must equal the spec's text line for line (checked
// when ../shared/spec is present, skipped otherwise), and core's structs must have the .msg fields
// with the same names, types and order, and the same constants.
#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "target/core/hil_uorb_messages.h"

namespace hitl::target {
namespace {

struct MsgLine {
  std::string type;   // "uint64", "float32[3]"
  std::string name;
  std::string value;  // constants only
};

std::string trim(const std::string& s) {
  const auto begin = s.find_first_not_of(" \t\r");
  if (begin == std::string::npos) return "";
  return s.substr(begin, s.find_last_not_of(" \t\r") - begin + 1);
}

std::vector<std::string> read_lines(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

/// Fields and constants of a .msg file, comments dropped.
void parse_msg(const std::filesystem::path& path, std::vector<MsgLine>* fields, std::vector<MsgLine>* constants) {
  for (const std::string& raw : read_lines(path)) {
    const std::string line = trim(raw.substr(0, raw.find('#')));
    if (line.empty()) continue;
    std::istringstream words(line);
    MsgLine m;
    words >> m.type >> m.name;
    const auto eq = line.find('=');
    if (eq != std::string::npos) {
      m.name = trim(line.substr(m.type.size(), eq - m.type.size()));
      m.value = trim(line.substr(eq + 1));
      constants->push_back(m);
    } else {
      fields->push_back(m);
    }
  }
}

std::filesystem::path msg_dir() { return std::filesystem::path(HITL_SOURCE_DIR) / "target" / "px4" / "msg"; }

/// A field of a core struct as the .msg would declare it.
struct CoreField {
  std::string type;
  std::string name;
  std::size_t offset;
};

template <typename T>
std::string msg_type() {
  using E = std::remove_all_extents_t<T>;
  std::string base = std::is_same_v<E, uint64_t> ? "uint64"
                     : std::is_same_v<E, float>  ? "float32"
                     : std::is_same_v<E, uint8_t> ? "uint8"
                                                  : "?";
  if constexpr (std::is_array_v<T>) base += "[" + std::to_string(std::extent_v<T>) + "]";
  return base;
}

#define HITL_CORE_FIELD(S, f) CoreField{msg_type<decltype(S::f)>(), #f, offsetof(S, f)}

void expect_same_fields(const std::vector<MsgLine>& msg, const std::vector<CoreField>& core, const char* what) {
  ASSERT_EQ(msg.size(), core.size()) << what << ": the .msg and target/core have different field counts";
  for (std::size_t i = 0; i < msg.size(); ++i) {
    EXPECT_EQ(msg[i].name, core[i].name) << what << " field " << i;
    EXPECT_EQ(msg[i].type, core[i].type) << what << " field " << msg[i].name;
    if (i > 0) {
      EXPECT_GT(core[i].offset, core[i - 1].offset) << what << ": target/core order differs at " << core[i].name;
    }
  }
}

TEST(HilUorbMessages, HilSensorImuMsgMatchesCore) {
  std::vector<MsgLine> fields, constants;
  parse_msg(msg_dir() / "HilSensorImu.msg", &fields, &constants);
  expect_same_fields(fields,
                     {HITL_CORE_FIELD(HilSensorImu, timestamp), HITL_CORE_FIELD(HilSensorImu, accelerometer_m_s2),
                      HITL_CORE_FIELD(HilSensorImu, gyroscope_rad_s), HITL_CORE_FIELD(HilSensorImu, temperature)},
                     "HilSensorImu");
  EXPECT_TRUE(constants.empty());
}

TEST(HilUorbMessages, HilSensorMagBaroMsgMatchesCore) {
  std::vector<MsgLine> fields, constants;
  parse_msg(msg_dir() / "HilSensorMagBaro.msg", &fields, &constants);
  expect_same_fields(fields,
                     {HITL_CORE_FIELD(HilSensorMagBaro, timestamp), HITL_CORE_FIELD(HilSensorMagBaro, magnetometer_ga),
                      HITL_CORE_FIELD(HilSensorMagBaro, pressure_pa), HITL_CORE_FIELD(HilSensorMagBaro, temperature),
                      HITL_CORE_FIELD(HilSensorMagBaro, fields_updated)},
                     "HilSensorMagBaro");
  ASSERT_EQ(constants.size(), 2U);
  EXPECT_EQ(constants[0].type, "uint8");
  EXPECT_EQ(constants[0].name, "FIELD_MAG");
  EXPECT_EQ(constants[0].value, std::to_string(HilSensorMagBaro::FIELD_MAG));
  EXPECT_EQ(constants[1].type, "uint8");
  EXPECT_EQ(constants[1].name, "FIELD_BARO");
  EXPECT_EQ(constants[1].value, std::to_string(HilSensorMagBaro::FIELD_BARO));
}

/// The spec's definition of `name`: the lines after the heading line `name` up to the next blank
/// line (the .msg text as the spec prints it), or nothing when the spec is not there.
std::vector<std::string> spec_definition(const std::string& name) {
  const std::filesystem::path spec_dir = std::filesystem::path(HITL_SOURCE_DIR) / ".." / "shared" / "spec";
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(spec_dir, ec)) {
    const std::vector<std::string> lines = read_lines(entry.path());
    for (std::size_t i = 0; i + 2 < lines.size(); ++i) {
      if (trim(lines[i]) != name || !trim(lines[i + 1]).empty() || trim(lines[i + 2]).rfind("uint64 timestamp", 0) != 0) {
        continue;
      }
      std::vector<std::string> definition;
      for (std::size_t j = i + 2; j < lines.size() && !trim(lines[j]).empty(); ++j) definition.push_back(trim(lines[j]));
      return definition;
    }
  }
  return {};
}

void expect_msg_is_spec_text(const std::string& name) {
  const std::vector<std::string> spec = spec_definition(name);
  if (spec.empty()) GTEST_SKIP() << "the spec (../shared/spec) is not here to compare " << name << ".msg with";
  std::vector<std::string> msg;
  for (const std::string& line : read_lines(msg_dir() / (name + ".msg"))) msg.push_back(trim(line));
  EXPECT_EQ(msg, spec) << name << ".msg differs from the spec's definition";
}

TEST(HilUorbMessages, HilSensorImuMsgIsTheSpecsText) { expect_msg_is_spec_text("HilSensorImu"); }
TEST(HilUorbMessages, HilSensorMagBaroMsgIsTheSpecsText) { expect_msg_is_spec_text("HilSensorMagBaro"); }

}  // namespace
}  // namespace hitl::target
