// Routes MAVLink frames between links the way mavlink-router does: a frame goes to every link
// except the one it came from, unless it names a target (target_system / target_component fields,
// read from the message's description), in which case only links that have shown that system (and
// component, when one is named) get it; a target nobody has shown yet goes everywhere, so a first
// command still reaches a vehicle that has not spoken. Duplicates within the dedup window are
// dropped. A "hub" link stands for many peers on one socket (the client port): frames from one of
// its peers go to its other peers too, never back to the sender; the hub remembers which peer
// address showed which (sysid, compid), so a targeted frame reaches only the peers that showed its
// target, as separate links do.
// Used by `hitl sim` (board <-> clients) and `hitl bridge` (board <-> clients <-> endpoints): one
// code path for both.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "base/mavlink/frame.h"
#include "engine/net/socket_address.h"
#include "engine/router/dedup.h"

namespace hitl::router {

using LinkId = std::size_t;

/// Which peers of a hub link get a frame: every one but `except` (the sender, never echoed), or,
/// for a targeted frame, only the peers in `only` that showed its target. Other links ignore it.
struct Delivery {
  std::optional<net::SocketAddress> except;
  std::vector<net::SocketAddress> only;  ///< empty: every peer
};

/// Sends bytes out of a link.
using Sender = std::function<void(std::span<const uint8_t> bytes, const Delivery& to)>;

struct LinkCounters {
  uint64_t frames_in = 0;
  uint64_t bytes_in = 0;
  uint64_t frames_out = 0;
  uint64_t bytes_out = 0;
  uint64_t duplicates_in = 0;  ///< frames that arrived here and had already come another way
  uint64_t systems_not_learned = 0;  ///< frames from a new (sysid, compid) after kMaxSystemsPerLink
  uint64_t peers_forgotten = 0;      ///< hub: (peer, sysid, compid) dropped for newer ones past kMaxSystemsPerLink
};

/// (target_system, target_component) of a frame; {0, 0} = broadcast (also for messages without
/// target fields and for ids neither the message set nor the official XML knows).
std::pair<uint8_t, uint8_t> target_of(const mavlink::Frame& frame);

class Router {
 public:
  /// A link learns at most this many (sysid, compid): a sender inventing ids cannot make every
  /// targeted frame's lookup grow (a real link shows a handful).
  static constexpr std::size_t kMaxSystemsPerLink = 256;

  explicit Router(double dedup_window_s = 0.0) : dedup_(dedup_window_s) {}

  LinkId add_link(std::string name, Sender send, bool hub = false);
  /// A frame arrived on `from` (from peer `peer` of a hub link): learn, dedup, forward.
  /// Returns how many links it was sent to (0 for a duplicate).
  std::size_t route(const mavlink::Frame& frame, LinkId from, double now_s,
                    const std::optional<net::SocketAddress>& peer = std::nullopt);
  /// Sends our own frame (e.g. the bridge's HEARTBEAT) out of one link, counted.
  void send(LinkId to, std::span<const uint8_t> bytes);

  const std::string& name(LinkId id) const { return links_.at(id).name; }
  const LinkCounters& counters(LinkId id) const { return links_.at(id).counters; }
  /// Systems (sysid, compid) seen arriving on a link.
  const std::set<std::pair<uint8_t, uint8_t>>& systems(LinkId id) const { return links_.at(id).systems; }
  /// Hub links: how many (peer, sysid, compid) are remembered.
  std::size_t peer_systems(LinkId id) const { return links_.at(id).peers.size(); }
  std::size_t link_count() const { return links_.size(); }
  uint64_t duplicates() const { return duplicates_; }

 private:
  /// On a hub: this peer address showed this (sysid, compid), last when `heard` (the route count).
  struct PeerSystem {
    net::SocketAddress address;
    uint8_t sysid = 0, compid = 0;
    uint64_t heard = 0;
  };
  struct Link {
    std::string name;
    Sender send;
    bool hub = false;
    LinkCounters counters;
    std::set<std::pair<uint8_t, uint8_t>> systems;
    std::vector<PeerSystem> peers;  ///< hub only; at most kMaxSystemsPerLink, the least recently heard go first
  };
  static bool shows(uint8_t sysid, uint8_t compid, uint8_t target_system, uint8_t target_component) {
    return sysid == target_system && (target_component == 0 || compid == target_component);
  }
  bool wants(const Link& link, uint8_t target_system, uint8_t target_component, bool anyone_knows) const;
  void learn_peer(Link& hub, const net::SocketAddress& peer, uint8_t sysid, uint8_t compid);

  std::vector<Link> links_;
  uint64_t routed_ = 0;
  DedupWindow dedup_;
  uint64_t duplicates_ = 0;
};

}  // namespace hitl::router
