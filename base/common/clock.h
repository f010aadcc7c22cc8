// The two clocks hitl reads: wall time (timestamps on the wire and in .tlog) and monotonic time
// (durations, deadlines, timeouts), in the units their callers use. Standard library only (C++17):
// the board programs (target/adb-relay, target/vio-server) read it too. std::chrono::steady_clock
// is CLOCK_MONOTONIC on Linux.
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

/// Milliseconds on the monotonic clock, signed: for deadline arithmetic (`deadline_ms - now`).
inline int64_t monotonic_ms() {
  return std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// Nanoseconds on the monotonic clock (CLOCK_MONOTONIC: what the board's MPA pipes stamp poses with).
inline uint64_t monotonic_ns() {
  return static_cast<uint64_t>(
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch()).count());
}

}  // namespace hitl
