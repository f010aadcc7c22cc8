// ESTIMATOR_STATUS.flags in words, PX4/QGroundControl's names, in bit order: what the estimator
// says is valid, and the three bits that report trouble (constant position mode, GPS glitch,
// accelerometer error).
#pragma once

#include <cstdint>
#include <vector>

namespace hitl::telemetry {

struct EstimatorFlag {
  uint16_t bit = 0;
  const char* word = "";  ///< "attitude", "vel horiz", ..., "GPS glitch"
  bool set = false;
  bool fault = false;     ///< a bit that is bad news when set
};

/// Every known bit of ESTIMATOR_STATUS_FLAGS, set or not, in bit order.
std::vector<EstimatorFlag> estimator_flags(uint16_t flags);

}  // namespace hitl::telemetry
