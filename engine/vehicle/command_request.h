// One COMMAND_LONG as a request, before it is addressed and sent: what the action API's requests
// (action.h) return, what CommandClient sends and what the trajectory pilot puts in its output.
#pragma once

#include <array>
#include <cstdint>

namespace hitl::vehicle {

/// A command id and its seven parameters (NaN: reserved, or the board's default).
struct CommandRequest {
  uint16_t command = 0;
  std::array<float, 7> params{};
};

}  // namespace hitl::vehicle
