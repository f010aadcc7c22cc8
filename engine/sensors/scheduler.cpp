#include "engine/sensors/scheduler.h"

#include <cmath>

namespace hitl::sensors {

namespace {
// Step times are sums of floating-point steps: allow them to fall a hair short of a due time.
constexpr double kTimeTolerance_s = 1e-9;
}  // namespace

bool PeriodicSchedule::due(double t_s) {
  if (t_s + kTimeTolerance_s < next_due_s()) return false;
  next_index_ = static_cast<std::uint64_t>(std::floor((t_s + kTimeTolerance_s) * rate_hz_)) + 1;
  return true;
}

}  // namespace hitl::sensors
