#include "engine/net/tcp_links.h"

#include <cstdio>

#include "base/common/clock.h"

namespace hitl::net {
namespace {

std::string period_text(double period_s) {
  char text[32];
  std::snprintf(text, sizeof text, "%g s", period_s);
  return text;
}

}  // namespace

// --- TcpClientLink ---------------------------------------------------------------------------

Expected<std::unique_ptr<TcpClientLink>> TcpClientLink::open(const Config& config) {
  auto link = std::unique_ptr<TcpClientLink>(new TcpClientLink(config));
  if (config.reconnect_period_s > 0) return link;  // maintain() connects, and reconnects
  auto client = TcpClient::connect(config.server, config.connect_timeout_ms, config.name);
  if (!client) return client.error();
  link->client_.emplace(std::move(client.value()));
  ++link->stats_.connects;
  return link;
}

void TcpClientLink::maintain(double now_s) {
  if (client_ || config_.reconnect_period_s <= 0 || now_s < next_connect_s_) return;
  next_connect_s_ = now_s + config_.reconnect_period_s;
  auto client = TcpClient::connect(config_.server, config_.connect_timeout_ms, config_.name);
  if (client) {
    client_.emplace(std::move(client.value()));
    ++stats_.connects;
    say(name_ + ": connected", Severity::Info);
  } else if (!warned_) {
    warned_ = true;
    say(client.error().message + "; retrying every " + period_text(config_.reconnect_period_s), Severity::Warning);
  }
}

void TcpClientLink::lose(double now_s) {
  client_.reset();
  lost_ = true;
  tx_.clear();
  if (config_.reconnect_period_s > 0) {
    next_connect_s_ = now_s + config_.reconnect_period_s;
    say(name_ + ": connection closed; reconnecting every " + period_text(config_.reconnect_period_s), Severity::Warning);
  }
}

std::size_t TcpClientLink::read_some(std::size_t max_reads, const ChunkHandler& on_chunk) {
  std::size_t reads = 0;
  for (; client_ && reads < max_reads; ++reads) {
    auto bytes = client_->receive();
    if (!bytes) {
      lose(monotonic_s());
      break;
    }
    if (bytes->empty()) break;
    ++stats_.datagrams_in;
    stats_.bytes_in += bytes->size();
    on_chunk(LinkChunk{*bytes, config_.server, /*whole_datagram=*/false});
  }
  return reads;
}

Status TcpClientLink::send(std::span<const uint8_t> bytes) {
  if (!client_) return Error::failed(name_ + ": not connected to " + config_.server.to_string());
  auto st = client_->send(bytes);
  if (st) {
    ++stats_.datagrams_out;
    stats_.bytes_out += bytes.size();
  } else if (config_.reconnect_period_s <= 0) {
    lose(monotonic_s());  // a stream does not come back: the link is closed
  }  // reconnecting: the next read sees the loss and says it
  return st;
}

Status TcpClientLink::flush() {
  if (tx_.empty()) return Ok{};
  std::vector<uint8_t> bytes;
  bytes.swap(tx_);
  return send(bytes);
}

// --- TcpServerLink ---------------------------------------------------------------------------

Expected<std::unique_ptr<TcpServerLink>> TcpServerLink::listen(const std::string& bind_address, uint16_t port,
                                                               const std::string& name) {
  auto server = TcpServer::listen(bind_address, port, name);
  if (!server) return server.error();
  return std::unique_ptr<TcpServerLink>(new TcpServerLink(std::move(server.value()), name));
}

bool TcpServerLink::wait_connected(int timeout_ms) {
  if (server_.connected()) return true;
  if (closed_ || !server_.accept_client(timeout_ms)) return false;
  ++stats_.connects;
  return true;
}

std::size_t TcpServerLink::read_some(std::size_t max_reads, const ChunkHandler& on_chunk) {
  std::size_t reads = 0;
  for (; server_.connected() && reads < max_reads; ++reads) {
    auto bytes = server_.receive();
    if (!bytes) {
      closed_ = true;
      break;
    }
    if (bytes->empty()) break;
    ++stats_.datagrams_in;
    stats_.bytes_in += bytes->size();
    on_chunk(LinkChunk{*bytes, *server_.client(), /*whole_datagram=*/false});
  }
  return reads;
}

Status TcpServerLink::send(std::span<const uint8_t> bytes) {
  if (!server_.connected()) return Error::failed(name_ + ": no client connected");
  auto st = server_.send(bytes);
  if (st) {
    ++stats_.datagrams_out;
    stats_.bytes_out += bytes.size();
  } else {
    closed_ = true;  // PX4 never reconnects
  }
  return st;
}

Status TcpServerLink::flush() {
  if (tx_.empty()) return Ok{};
  std::vector<uint8_t> bytes;
  bytes.swap(tx_);
  if (!server_.connected()) return Ok{};  // nobody yet: what was queued is dropped, as before
  return send(bytes);
}

}  // namespace hitl::net
