// PX4's parameter protocol from the ground-station side: full download by index with re-requests
// of missing indices, get with retries, set verified by the PARAM_VALUE echo. INT32 values travel
// bytewise in the float field (PX4's MAV_PROTOCOL_CAPABILITY_PARAM_ENCODE_BYTEWISE).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "base/common/expected.h"
#include "engine/vehicle/params_file.h"
#include "engine/vehicle/vehicle_link.h"

namespace hitl::vehicle {

class ParamClient {
 public:
  explicit ParamClient(VehicleLink& link) : link_(link) {}

  /// Every parameter, in index order; `progress(received, total)` as they arrive.
  Expected<std::vector<Param>> download(const std::function<void(std::size_t, std::size_t)>& progress = {});
  Expected<ParamValue> get(const std::string& name);
  /// Sets and checks the echo; an Error says what the board kept instead.
  Expected<ParamValue> set(const std::string& name, const ParamValue& value);

  static constexpr int kRetries = 3;
  static constexpr double kTimeout_s = 1.0;

 private:
  VehicleLink& link_;
};

}  // namespace hitl::vehicle
