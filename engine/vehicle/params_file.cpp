#include "base/common/bounded_read.h"
#include "engine/vehicle/params_file.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

namespace hitl::vehicle {

// Generated at build time from base/contract/hitl-defaults.params (see CMakeLists.txt).
extern const char* const kHitlDefaultParamsText;

std::string ParamValue::to_string() const {
  if (type == ParamType::Int32) return std::to_string(i);
  // The shortest text that reads back as the same float ("0.95", not "0.949999988").
  char buf[32];
  for (int digits = 6; digits <= 9; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, static_cast<double>(f));
    if (std::strtof(buf, nullptr) == f) break;
  }
  return buf;
}

Expected<ParamValue> parse_param_value(std::string_view text, ParamType type) {
  const std::string value(text);
  try {
    std::size_t used = 0;
    ParamValue out;
    if (type == ParamType::Int32) {
      const long long v = std::stoll(value, &used);
      if (v < INT32_MIN || v > INT32_MAX) throw std::out_of_range("int32");
      out = ParamValue::int32(static_cast<int32_t>(v));
    } else {
      const float v = std::stof(value, &used);
      if (!std::isfinite(v)) throw std::out_of_range("finite");
      out = ParamValue::real32(v);
    }
    if (used != value.size()) throw std::invalid_argument("trailing");
    return out;
  } catch (const std::exception&) {
    return Error::input("value '" + value + "' is not a valid " +
                 (type == ParamType::Int32 ? "INT32 (an integer from -2147483648 to 2147483647)"
                                           : "REAL32 (a finite number within +-3.4e38)"));
  }
}

Expected<std::vector<Param>> parse_params(std::string_view text, std::string_view source) {
  std::vector<Param> out;
  std::istringstream in{std::string(text)};
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    std::istringstream fields(line);
    std::string sys, comp, name, value, type;
    const std::string where = std::string(source) + ":" + std::to_string(line_no) + ": ";
    if (!(fields >> sys >> comp >> name >> value >> type))
      return Error::input(where + "expected 'Vehicle-Id Component-Id Name Value Type', got '" + line + "'");
    if (name.size() > 16) return Error::input(where + "parameter name '" + name + "' is longer than 16 characters");
    Param p{name, {}};
    if (type != "6" && type != "9") return Error::input(where + name + ": type '" + type + "' is not 6 (INT32) or 9 (REAL32)");
    auto v = parse_param_value(value, type == "6" ? ParamType::Int32 : ParamType::Real32);
    if (!v) return Error::input(where + name + ": " + v.error().message);
    p.value = *v;
    out.push_back(std::move(p));
  }
  return out;
}

Expected<std::vector<Param>> load_params_file(const std::string& path) {
  auto text = read_bounded_file(path, "parameter file", kMaxConfigFileBytes);
  if (!text) return text.error();
  return parse_params(*text, path);
}

std::string format_params(const std::vector<Param>& params, uint8_t sysid, uint8_t compid) {
  std::string out = "# Onboard parameters for Vehicle " + std::to_string(sysid) +
                    "\n#\n# Stack: PX4 Pro\n# Vehicle: Multi-Rotor\n#\n# Vehicle-Id Component-Id Name Value Type\n";
  for (const auto& p : params)
    out += std::to_string(sysid) + "\t" + std::to_string(compid) + "\t" + p.name + "\t" + p.value.to_string() + "\t" +
           std::to_string(static_cast<int>(p.value.type)) + "\n";
  return out;
}

const std::vector<Param>& hitl_default_params() {
  static const std::vector<Param> params = [] {
    auto parsed = parse_params(kHitlDefaultParamsText, "base/contract/hitl-defaults.params");
    return parsed ? parsed.value() : std::vector<Param>{};  // a parse error fails the build's test, not here
  }();
  return params;
}

float encode_param_float(const ParamValue& value) {
  if (value.type == ParamType::Real32) return value.f;
  float wire;
  std::memcpy(&wire, &value.i, sizeof wire);
  return wire;
}

ParamValue decode_param_float(float wire, ParamType type) {
  if (type == ParamType::Real32) return ParamValue::real32(wire);
  int32_t v;
  std::memcpy(&v, &wire, sizeof v);
  return ParamValue::int32(v);
}

}  // namespace hitl::vehicle
