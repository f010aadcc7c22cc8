// The messages a parser knows: compiled-in ones plus any loaded from dialect XML.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "base/mavlink/message_desc.h"

namespace hitl::mavlink {

class MessageSet {
 public:
  /// An empty set.
  MessageSet() = default;
  /// The messages compiled into hitl (messages.h).
  static MessageSet compiled();

  MessageSet(const MessageSet& other);
  MessageSet& operator=(const MessageSet& other);
  MessageSet(MessageSet&&) noexcept = default;
  MessageSet& operator=(MessageSet&&) noexcept = default;

  /// Adds a message, replacing one with the same id (a dialect may redefine a message).
  void add(MessageDesc desc);

  const MessageDesc* find(uint32_t id) const {
    if (id < fast_.size()) return fast_[id];
    auto it = by_id_.find(id);
    return it == by_id_.end() ? nullptr : it->second.get();
  }
  const MessageDesc* find(std::string_view name) const;
  /// Resolves a user's word: a message name (any case) or a numeric id.
  const MessageDesc* lookup(std::string_view name_or_id) const;

  std::size_t size() const { return by_id_.size(); }
  /// All messages, ordered by id.
  std::vector<const MessageDesc*> all() const;

 private:
  std::unordered_map<uint32_t, std::unique_ptr<MessageDesc>> by_id_;
  std::unordered_map<std::string, const MessageDesc*> by_name_;
  std::array<const MessageDesc*, 512> fast_{};
};

}  // namespace hitl::mavlink
