#include "engine/report/parameters.h"

#include <cstring>

#include "engine/vehicle/params_file.h"

namespace hitl::report {
namespace {

constexpr uint8_t kMavParamTypeUint8 = 1, kMavParamTypeInt8 = 2, kMavParamTypeUint16 = 3, kMavParamTypeInt16 = 4,
                  kMavParamTypeUint32 = 5, kMavParamTypeInt32 = 6, kMavParamTypeReal32 = 9;

/// Equal as PX4 keeps them: float32 (or an int32 in a double, exactly).
bool same(double a, double b) { return static_cast<float>(a) == static_cast<float>(b); }

}  // namespace

double param_value_number(float wire, uint8_t param_type) {
  uint32_t bits = 0;
  std::memcpy(&bits, &wire, sizeof bits);
  switch (param_type) {
    case kMavParamTypeUint8: return static_cast<uint8_t>(bits);
    case kMavParamTypeInt8: return static_cast<int8_t>(static_cast<uint8_t>(bits));
    case kMavParamTypeUint16: return static_cast<uint16_t>(bits);
    case kMavParamTypeInt16: return static_cast<int16_t>(static_cast<uint16_t>(bits));
    case kMavParamTypeUint32: return bits;
    case kMavParamTypeInt32: return vehicle::decode_param_float(wire, vehicle::ParamType::Int32).as_double();
    case kMavParamTypeReal32: return wire;
    default: return wire;  // 64-bit types do not fit PARAM_VALUE's float; PX4 sends none
  }
}

ParameterTable non_default_parameters(const FlightLog& log) {
  ParameterTable t;
  const std::map<std::string, double>* values = &log.parameters;
  if (!log.parameters.empty()) {
    t.values_from = "PARAM_VALUE in this log (" + std::to_string(log.parameters.size()) + " parameters, the last value of each)";
  } else if (log.px4 && !log.px4->parameters.empty()) {
    values = &log.px4->parameters;
    t.values_from = "no PARAM_VALUE in this log: PX4's ULog's parameters (" + std::to_string(values->size()) +
                    ", the last value of each)";
  } else {
    return t;
  }
  std::map<std::string, double> defaults;
  if (log.px4 && !log.px4->parameters.empty()) {
    // PX4 logs a default ('Q') only for a parameter whose value differs from it; one without is at
    // its default in the ULog's parameters.
    defaults = log.px4->parameters;
    for (const auto& [name, d] : log.px4->parameter_defaults) defaults[name] = d;
    t.defaults_from = "PX4's ULog " + log.px4->path + " (its logged defaults: the airframe's where it has one, else the "
                      "firmware's; a parameter without a logged default is at the value the ULog starts with)";
  } else {
    for (const auto& p : vehicle::hitl_default_params()) defaults[p.name] = p.value.as_double();
    t.defaults_from = "the spec's HITL set that hitl target boots with and hitl params reset pushes "
                      "(base/contract/hitl-defaults.params, " + std::to_string(defaults.size()) +
                      " parameters); a parameter outside it has no default known to hitl";
  }
  if (values == &log.parameters)
    for (const auto& [name, value] : log.parameters)
      if (const auto first = log.parameters_first.find(name); first != log.parameters_first.end() && !same(value, first->second))
        t.changed.push_back({name, value, first->second});
  for (const auto& [name, value] : *values) {
    const auto it = defaults.find(name);
    if (it == defaults.end()) {
      ++t.without_default;
      continue;
    }
    ++t.compared;
    if (!same(value, it->second)) t.differ.push_back({name, value, it->second});
  }
  return t;
}

}  // namespace hitl::report
