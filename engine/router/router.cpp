#include "engine/router/router.h"

#include <algorithm>

#include "base/mavlink/message_desc.h"

namespace hitl::router {

std::pair<uint8_t, uint8_t> target_of(const mavlink::Frame& frame) {
  if (frame.desc == nullptr && frame.check != nullptr) {  // a standard id hitl has no type for: the XML's offsets
    const auto& c = *frame.check;  // zero-extended past a truncated payload, as below
    return {(c.flags & mavlink::MessageCheck::kHasTargetSystem) ? frame.payload[c.target_system_offset] : uint8_t{0},
            (c.flags & mavlink::MessageCheck::kHasTargetComponent) ? frame.payload[c.target_component_offset] : uint8_t{0}};
  }
  if (frame.desc == nullptr) return {0, 0};
  const auto read = [&](const char* name) -> uint8_t {
    const auto* field = frame.desc->field(name);
    if (field == nullptr || field->offset >= frame.payload.size()) return 0;
    return frame.payload[field->offset];  // zero-extended past a truncated payload
  };
  const uint8_t system = read("target_system");
  // MANUAL_CONTROL names its system in `target`.
  return {system != 0 ? system : read("target"), read("target_component")};
}

LinkId Router::add_link(std::string name, Sender send, bool hub) {
  links_.push_back(Link{std::move(name), std::move(send), hub, {}, {}, {}});
  return links_.size() - 1;
}

bool Router::wants(const Link& link, uint8_t target_system, uint8_t target_component, bool anyone_knows) const {
  // Broadcast, or nobody has shown this system yet: everywhere, so that a first command reaches a silent vehicle.
  if (target_system == 0 || !anyone_knows) return true;
  return std::any_of(link.systems.begin(), link.systems.end(),
                     [&](const auto& s) { return shows(s.first, s.second, target_system, target_component); });
}

void Router::learn_peer(Link& hub, const net::SocketAddress& peer, uint8_t sysid, uint8_t compid) {
  for (auto& p : hub.peers) {
    if (p.sysid == sysid && p.compid == compid && p.address == peer) {
      p.heard = routed_;
      return;
    }
  }
  if (hub.peers.size() >= kMaxSystemsPerLink) {  // a sender inventing ids: the stalest goes
    auto stalest = std::min_element(hub.peers.begin(), hub.peers.end(), [](const auto& a, const auto& b) { return a.heard < b.heard; });
    hub.peers.erase(stalest);
    ++hub.counters.peers_forgotten;
  }
  hub.peers.push_back(PeerSystem{peer, sysid, compid, routed_});
}

std::size_t Router::route(const mavlink::Frame& frame, LinkId from, double now_s,
                          const std::optional<net::SocketAddress>& peer) {
  Link& source = links_.at(from);
  ++routed_;
  source.counters.frames_in += 1;
  source.counters.bytes_in += frame.raw_len;
  if (source.systems.size() < kMaxSystemsPerLink) source.systems.insert({frame.sysid, frame.compid});
  else if (!source.systems.count({frame.sysid, frame.compid})) ++source.counters.systems_not_learned;
  if (source.hub && peer) learn_peer(source, *peer, frame.sysid, frame.compid);
  if (dedup_.seen_recently(frame.bytes(), now_s)) {
    ++source.counters.duplicates_in;
    ++duplicates_;
    return 0;
  }
  const auto [system, component] = target_of(frame);
  const bool anyone_knows = system != 0 && std::any_of(links_.begin(), links_.end(), [&](const Link& l) {
    return std::any_of(l.systems.begin(), l.systems.end(), [&](const auto& s) { return s.first == system; });
  });
  std::size_t sent = 0;
  for (LinkId id = 0; id < links_.size(); ++id) {
    Link& link = links_[id];
    if (id == from && !link.hub) continue;
    if (!wants(link, system, component, anyone_knows)) continue;
    Delivery to;
    if (id == from) to.except = peer;
    if (link.hub && system != 0 && anyone_knows) {  // only the peers that showed the target
      for (const auto& p : link.peers)
        if (shows(p.sysid, p.compid, system, component) && !(to.except && p.address == *to.except)) to.only.push_back(p.address);
      if (to.only.empty()) continue;
    }
    link.send(frame.bytes(), to);
    link.counters.frames_out += 1;
    link.counters.bytes_out += frame.raw_len;
    ++sent;
  }
  return sent;
}

void Router::send(LinkId to, std::span<const uint8_t> bytes) {
  Link& link = links_.at(to);
  link.send(bytes, Delivery{});
  link.counters.frames_out += 1;
  link.counters.bytes_out += bytes.size();
}

}  // namespace hitl::router
