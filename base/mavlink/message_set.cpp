#include "base/mavlink/message_set.h"

#include <algorithm>
#include <cctype>
#include <charconv>

#include "base/mavlink/messages.h"
#include "base/mavlink/typed_codec.h"

namespace hitl::mavlink {
namespace {

template <class... Ms>
void add_all(MessageSet& set, TypeList<Ms...>) {
  (set.add(describe<Ms>()), ...);
}

std::string upper(std::string_view text) {
  std::string out(text);
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

}  // namespace

MessageSet MessageSet::compiled() {
  MessageSet set;
  add_all(set, msg::All{});
  return set;
}

MessageSet::MessageSet(const MessageSet& other) {
  for (const auto& [id, desc] : other.by_id_) add(*desc);
}

MessageSet& MessageSet::operator=(const MessageSet& other) {
  if (this != &other) {
    MessageSet copy(other);
    *this = std::move(copy);
  }
  return *this;
}

void MessageSet::add(MessageDesc desc) {
  const uint32_t id = desc.id;
  if (auto old = by_id_.find(id); old != by_id_.end()) by_name_.erase(old->second->name);
  auto owned = std::make_unique<MessageDesc>(std::move(desc));
  const MessageDesc* ptr = owned.get();
  by_id_[id] = std::move(owned);
  by_name_[ptr->name] = ptr;
  if (id < fast_.size()) fast_[id] = ptr;
}

const MessageDesc* MessageSet::find(std::string_view name) const {
  auto it = by_name_.find(std::string(name));
  return it == by_name_.end() ? nullptr : it->second;
}

const MessageDesc* MessageSet::lookup(std::string_view name_or_id) const {
  uint32_t id = 0;
  auto [end, ec] = std::from_chars(name_or_id.data(), name_or_id.data() + name_or_id.size(), id);
  if (ec == std::errc() && end == name_or_id.data() + name_or_id.size()) return find(id);
  return find(std::string_view(upper(name_or_id)));
}

std::vector<const MessageDesc*> MessageSet::all() const {
  std::vector<const MessageDesc*> out;
  out.reserve(by_id_.size());
  for (const auto& [id, desc] : by_id_) out.push_back(desc.get());
  std::sort(out.begin(), out.end(), [](auto* a, auto* b) { return a->id < b->id; });
  return out;
}

}  // namespace hitl::mavlink
