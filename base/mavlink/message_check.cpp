#include "base/mavlink/message_check.h"

#include <algorithm>

#include "base/mavlink/messages.h"

namespace hitl::mavlink {

const MessageCheck* find_standard_check(uint32_t id) {
  const auto& table = msg::kStandardChecks;  // sorted by id (the generator's order)
  const auto* it = std::lower_bound(table.begin(), table.end(), id, [](const MessageCheck& c, uint32_t v) { return c.id < v; });
  return it != table.end() && it->id == id ? &*it : nullptr;
}

}  // namespace hitl::mavlink
