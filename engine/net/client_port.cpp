#include "engine/net/client_port.h"

#include <algorithm>

namespace hitl::net {

Expected<ClientPort> ClientPort::open(const std::string& bind_address, uint16_t port,
                                      const std::vector<SocketAddress>& fixed_peers) {
  ClientPort cp;
  UdpEndpoint::Config c;
  c.bind_address = bind_address;
  c.bind_port = port;
  c.policy = PartnerPolicy::Fixed;
  c.name = port != 0 ? "--clients" : "--gcs";
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

std::optional<Datagram> ClientPort::receive() {
  if (!endpoint_) return std::nullopt;
  auto d = endpoint_->receive();
  if (!d) return d;
  ++stats_.datagrams_in;
  const auto now = std::chrono::steady_clock::now();
  auto it = std::find_if(clients_.begin(), clients_.end(), [&](const Client& c) { return c.address == d->from; });
  if (it == clients_.end()) clients_.push_back(Client{d->from, now, false});
  else it->last_heard = now;
  return d;
}

void ClientPort::broadcast(std::span<const uint8_t> bytes, const std::optional<SocketAddress>& except) {
  if (!endpoint_) return;
  const auto now = std::chrono::steady_clock::now();
  clients_.erase(std::remove_if(clients_.begin(), clients_.end(),
                                [&](const Client& c) { return !c.fixed && now - c.last_heard > kClientTimeout; }),
                 clients_.end());
  for (const auto& c : clients_) {
    if (except && c.address == *except) continue;
    if (endpoint_->send_to(c.address, bytes)) ++stats_.datagrams_out;
    else ++stats_.send_errors;
  }
}

std::vector<SocketAddress> ClientPort::clients() const {
  std::vector<SocketAddress> out;
  for (const auto& c : clients_) out.push_back(c.address);
  return out;
}

}  // namespace hitl::net
