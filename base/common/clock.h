// The two clocks hitl reads: wall time (timestamps on the wire and in .tlog) and monotonic time
// (durations, deadlines, timeouts), in the units their callers use.
#pragma once

#include <chrono>
#include <cstdint>

namespace hitl {

/// Nanoseconds since the Unix epoch (CLOCK_REALTIME).
inline int64_t unix_time_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch()).count();
}

/// Seconds on the monotonic clock (CLOCK_MONOTONIC): for durations and deadlines only.
inline double monotonic_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// Microseconds on the monotonic clock.
inline uint64_t monotonic_us() {
  return static_cast<uint64_t>(
      std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now().time_since_epoch()).count());
}

}  // namespace hitl
