#include "engine/net/client_port.h"

#include <algorithm>
#include <cstring>

namespace hitl::net {

Expected<ClientPort> ClientPort::open(const std::string& bind_address, uint16_t port,
                                      const std::vector<SocketAddress>& fixed_peers, const ClientPortLimits& limits) {
  ClientPort cp;
  cp.limits_ = limits;
  UdpEndpoint::Config c;
  c.bind_address = bind_address;
  c.bind_port = port;
  c.policy = PartnerPolicy::Fixed;
  c.name = port != 0 ? "--clients" : "--gcs";
  c.send_buffer_bytes = limits.send_buffer_bytes;
  c.receive_buffer_bytes = limits.receive_buffer_bytes;
  if (port != 0 || !fixed_peers.empty()) {
    auto ep = UdpEndpoint::open(c);
    if (!ep) return ep.error();
    cp.endpoint_.emplace(std::move(ep.value()));
  }
  const auto now = std::chrono::steady_clock::now();
  for (const auto& p : fixed_peers) cp.clients_.push_back(Client{p, now, true});
  return cp;
}

std::optional<SocketAddress> ClientPort::local_address() const {
  if (!endpoint_) return std::nullopt;
  return endpoint_->local_address();
}

std::size_t ClientPort::receive_some(std::size_t max_datagrams, const std::function<void(const Datagram&)>& on_datagram) {
  if (!endpoint_) return 0;
  std::size_t read = 0;
  const auto now = std::chrono::steady_clock::now();
  while (read < max_datagrams) {
    auto d = endpoint_->receive();
    if (!d) break;
    ++read;
    ++stats_.datagrams_in;
    auto it = std::find_if(clients_.begin(), clients_.end(), [&](const Client& c) { return c.address == d->from; });
    if (it != clients_.end()) {
      it->last_heard = now;
    } else if (clients_.size() < limits_.max_clients) {
      clients_.push_back(Client{d->from, now, false});
    } else {
      ++stats_.refused_datagrams;
      continue;
    }
    on_datagram(*d);
  }
  return read;
}

namespace {

/// The MAVLink message id of a frame (v2 or v1), or ClientPort::kOtherIds when it has none.
uint32_t message_id(std::span<const uint8_t> f) {
  if (f.size() >= 10 && f[0] == 0xFD) return uint32_t{f[7]} | uint32_t{f[8]} << 8 | uint32_t{f[9]} << 16;
  if (f.size() >= 6 && f[0] == 0xFE) return f[5];
  return ClientPort::kOtherIds;
}

}  // namespace

std::size_t ClientPort::queue_limit() const {
  if (limits_.max_queue_s <= 0) return limits_.max_queued_frames;
  const double per_datagram_s = send_s_per_datagram_ > 0 ? send_s_per_datagram_ : kAssumedSendTime_s;
  const double per_frame_s = per_datagram_s * static_cast<double>(std::max<std::size_t>(1, clients_.size()));
  const auto frames = static_cast<std::size_t>(limits_.max_queue_s / per_frame_s);
  // Never fewer than one pump() sends to every client: what one loop turn takes in is sent, not dropped.
  const std::size_t floor = std::max(limits_.min_queued_frames, limits_.max_datagrams_out / std::max<std::size_t>(1, clients_.size()));
  return std::clamp(frames, std::min(floor, limits_.max_queued_frames), limits_.max_queued_frames);
}

void ClientPort::drop_oldest(Queue& queue) {
  const Frame& f = queue.frames.front();
  uint64_t not_reached = 0;
  for (std::size_t i = queue.next_client; i < clients_.size(); ++i) {
    const Client& c = clients_[i];
    if ((f.except && c.address == *f.except) ||
        (!f.only.empty() && std::find(f.only.begin(), f.only.end(), c.address) == f.only.end()))
      continue;
    ++not_reached;
  }
  ++stats_.dropped_frames;
  stats_.dropped_deliveries += not_reached;
  uint32_t id = message_id({f.bytes.data(), f.size});
  if (!stats_.dropped_by_msgid.contains(id) && stats_.dropped_by_msgid.size() >= kMaxDropIds) id = kOtherIds;
  stats_.dropped_by_msgid[id] += not_reached;
  queue.frames.pop_front();
  queue.next_client = 0;
}

void ClientPort::broadcast(std::span<const uint8_t> bytes, const std::optional<SocketAddress>& except,
                           const std::vector<SocketAddress>& only) {
  if (!endpoint_ || clients_.empty()) return;
  Queue& queue = except ? forwarded_ : own_;
  if (bytes.size() > kMaxFrameBytes) {
    ++stats_.dropped_frames;
    return;
  }
  if (limits_.max_queue_s > 0) {  // fresh: the newest goes in, the oldest make room
    const std::size_t limit = std::max<std::size_t>(1, queue_limit());
    while (queue.frames.size() >= limit) drop_oldest(queue);
  } else if (queue.frames.size() >= limits_.max_queued_frames) {
    ++stats_.dropped_frames;
    return;
  }
  Frame& f = queue.frames.emplace_back();
  std::memcpy(f.bytes.data(), bytes.data(), bytes.size());
  f.size = bytes.size();
  f.except = except;
  f.only = only;
}

void ClientPort::forget_silent_clients() {
  const auto now = std::chrono::steady_clock::now();
  for (std::size_t i = clients_.size(); i-- > 0;) {
    const Client& c = clients_[i];
    if (c.fixed || now - c.last_heard <= kClientTimeout) continue;
    for (Queue* q : {&own_, &forwarded_})
      if (q->next_client > i) --q->next_client;  // the front frame's progress keeps pointing at the same client
    clients_.erase(clients_.begin() + static_cast<std::ptrdiff_t>(i));
  }
}

void ClientPort::send_from(Queue& queue, std::size_t& budget) {
  while (!queue.frames.empty() && budget > 0 && !blocked_) {
    const Frame& f = queue.frames.front();
    while (queue.next_client < clients_.size() && budget > 0) {
      const Client& c = clients_[queue.next_client];
      if ((f.except && c.address == *f.except) ||
          (!f.only.empty() && std::find(f.only.begin(), f.only.end(), c.address) == f.only.end())) {
        ++queue.next_client;
        continue;
      }
      const SendOutcome sent = endpoint_->try_send_to(c.address, {f.bytes.data(), f.size});
      if (sent == SendOutcome::WouldBlock) {  // kept: the same client again once the socket is writable
        ++stats_.send_buffer_full;
        blocked_ = true;
        return;
      }
      --budget;
      ++queue.next_client;
      if (sent == SendOutcome::Sent) ++stats_.datagrams_out;
      else ++stats_.send_errors;
    }
    if (queue.next_client < clients_.size()) return;  // budget spent mid-frame: carry on next time
    queue.frames.pop_front();
    queue.next_client = 0;
  }
}

void ClientPort::pump() {
  if (!endpoint_) return;
  forget_silent_clients();
  blocked_ = false;
  std::size_t budget = limits_.max_datagrams_out;
  const auto start = std::chrono::steady_clock::now();
  send_from(own_, budget);
  send_from(forwarded_, budget);
  // The time a datagram takes to send, measured over enough of them to mean something: it sizes
  // the fresh queue in sending time (queue_limit()).
  if (const std::size_t sent = limits_.max_datagrams_out - budget; sent >= 64) {
    const double per = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / static_cast<double>(sent);
    send_s_per_datagram_ = send_s_per_datagram_ <= 0 ? per : 0.8 * send_s_per_datagram_ + 0.2 * per;
  }
}

std::vector<SocketAddress> ClientPort::clients() const {
  std::vector<SocketAddress> out;
  for (const auto& c : clients_) out.push_back(c.address);
  return out;
}

}  // namespace hitl::net
