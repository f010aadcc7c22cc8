// The parameters that differ from the flight stack's defaults (docs/report.md "Parameters"), the last
// section of the report as of Flight Review: the values from the log's PARAM_VALUE (hitl params, a
// ground station, the session's own reads), or PX4's ULog when the log has none; the defaults from
// PX4's ULog when one is merged (its logged defaults), else the emulated board's: the spec's HITL set
// that `hitl target` boots with (base/contract/hitl-defaults.params).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "engine/report/flight_log.h"

namespace hitl::report {

struct ParameterRow {
  std::string name;
  double value = 0;
  double default_value = 0;
};

struct ParameterTable {
  std::string values_from;    ///< where the values came from, in words ("" : no values at all)
  std::string defaults_from;  ///< where the defaults came from, in words
  std::vector<ParameterRow> differ;  ///< by name
  /// Set during the log (PARAM_VALUE only): its last value differs from its first; default_value is
  /// the first. Whatever the defaults know: a parameter the emulated board's set does not have shows here.
  std::vector<ParameterRow> changed;
  std::size_t compared = 0;          ///< values with a known default
  std::size_t without_default = 0;   ///< values whose default the source does not know
};

/// The parameters of `log` (and its merged ULog) that differ from their defaults.
ParameterTable non_default_parameters(const FlightLog& log);

/// PARAM_VALUE's param_value as the number it carries: PX4 sends integer types byte-wise in the
/// float (MAV_PROTOCOL_CAPABILITY_PARAM_ENCODE_BYTEWISE); MAV_PARAM_TYPE 9 (REAL32) is the float.
double param_value_number(float wire, uint8_t param_type);

}  // namespace hitl::report
