// What a board answers to the parameter and shell protocols, collected without I/O so that the
// clients (param_client, shell_client) and the fuzzer (tests/fuzz/board_replies_fuzz.cpp) share it.
// Both are bounded whatever the board sends.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "base/mavlink/messages.h"
#include "engine/vehicle/params_file.h"

namespace hitl::vehicle {

/// A PARAM_VALUE's name (up to 16 characters, NUL-terminated when shorter) and value.
std::string param_name(const std::array<char, 16>& id);
ParamValue param_value_of(const mavlink::msg::ParamValue& v);

/// The answers to PARAM_REQUEST_LIST / PARAM_REQUEST_READ: one entry per index below the count
/// the board announces (at most 65,535 by the wire format), the first value of each index kept.
class ParamCollector {
 public:
  /// Takes one PARAM_VALUE; true when every index of the announced count has arrived.
  bool take(const mavlink::msg::ParamValue& v);
  std::optional<uint16_t> total() const { return total_; }
  std::size_t received() const { return got_.size(); }
  bool has(uint16_t index) const { return got_.count(index) != 0; }
  /// The parameters in index order.
  std::vector<Param> params() const;

 private:
  std::map<uint16_t, Param> got_;
  std::optional<uint16_t> total_;
};

/// The PX4 shell's output (SERIAL_CONTROL device 10) until the prompt comes back. At most
/// kMaxShellOutputBytes are kept (a board that never stops talking cannot grow it); the prompt is
/// still recognised past that.
inline constexpr std::size_t kMaxShellOutputBytes = 1 << 20;
class ShellOutput {
 public:
  /// Appends one reply; true when the output now ends with the prompt ("pxh> " or "nsh> ").
  /// Replies from other devices are ignored.
  bool append(const mavlink::msg::SerialControl& reply);
  void clear();
  const std::string& text() const { return text_; }
  bool cut() const { return cut_; }  ///< more than kMaxShellOutputBytes arrived
  /// The output without the echoed command line and the final prompt.
  std::string body() const;

 private:
  std::string text_;
  std::string tail_;  ///< the last bytes received, for the prompt
  bool cut_ = false;
};

}  // namespace hitl::vehicle
