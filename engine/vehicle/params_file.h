// PX4 parameters as QGroundControl saves them (.params): one per line,
// "Vehicle-Id <TAB> Component-Id <TAB> Name <TAB> Value <TAB> Type", '#' comments;
// Type is MAV_PARAM_TYPE: 6 = INT32, 9 = REAL32 (PX4 uses only these two).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "base/common/expected.h"

namespace hitl::vehicle {

enum class ParamType : uint8_t { Int32 = 6, Real32 = 9 };

/// A typed PX4 parameter value.
struct ParamValue {
  ParamType type = ParamType::Real32;
  int32_t i = 0;
  float f = 0;

  static ParamValue int32(int32_t v) { return {ParamType::Int32, v, 0}; }
  static ParamValue real32(float v) { return {ParamType::Real32, 0, v}; }
  double as_double() const { return type == ParamType::Int32 ? i : f; }
  bool operator==(const ParamValue& o) const {
    return type == o.type && (type == ParamType::Int32 ? i == o.i : f == o.f);
  }
  /// "1310988" / "0.174"
  std::string to_string() const;
};

struct Param {
  std::string name;  ///< at most 16 characters (PARAM_VALUE.param_id)
  ParamValue value;
};

/// One value as text ("1", "0.5") for a parameter of `type`: an INT32 within its range (never
/// wrapped), a REAL32 finite. `params load` and `params set` both check with it.
Expected<ParamValue> parse_param_value(std::string_view text, ParamType type);

/// Parses .params text; `source` names the input in errors ("hitl-defaults.params:12: ...").
Expected<std::vector<Param>> parse_params(std::string_view text, std::string_view source);
Expected<std::vector<Param>> load_params_file(const std::string& path);
/// Writes QGroundControl's format with its header comment.
std::string format_params(const std::vector<Param>& params, uint8_t sysid = 1, uint8_t compid = 1);

/// The spec's HITL default set, compiled in from base/contract/hitl-defaults.params.
const std::vector<Param>& hitl_default_params();

/// PX4 sends and receives INT32 parameters byte-wise inside PARAM_VALUE/PARAM_SET's float field
/// (MAV_PROTOCOL_CAPABILITY_PARAM_ENCODE_BYTEWISE).
float encode_param_float(const ParamValue& value);
ParamValue decode_param_float(float wire, ParamType type);

}  // namespace hitl::vehicle
