// Links over TCP (link.h): byte streams, so drain() feeds the parser.
//
// TcpClientLink connects to a MAVLink server (mavlink-router's TCP port, MAVProxy, PX4 with -t).
// With reconnect_period_s 0 it connects once in open() (an Error when it cannot) and a lost
// connection stays closed (a vehicle command's --connect tcp:). With a period it connects from
// maintain() and again that long after a loss, saying so as events: "connected", a failed attempt
// once, "connection closed; reconnecting every 2 s" (hitl bridge --endpoint tcp:).
//
// TcpServerLink listens; one client connects (PX4 SITL's simulator link: PX4 connects once and never
// reconnects, so a loss is closed() for good).
#pragma once

#include <memory>

#include "engine/net/link.h"
#include "engine/net/tcp_client.h"
#include "engine/net/tcp_server.h"

namespace hitl::net {

class TcpClientLink final : public Link {
 public:
  struct Config {
    SocketAddress server;
    std::string name = "TCP";
    int connect_timeout_ms = 500;
    double reconnect_period_s = 0;  ///< 0: connect in open(), never again
  };
  static Expected<std::unique_ptr<TcpClientLink>> open(const Config& config);

  std::size_t read_some(std::size_t max_reads, const ChunkHandler& on_chunk) override;
  bool wait_readable(int timeout_ms) const override { return client_ && client_->wait_readable(timeout_ms); }
  Status send(std::span<const uint8_t> bytes) override;
  void queue(std::span<const uint8_t> frame) override { tx_.insert(tx_.end(), frame.begin(), frame.end()); }
  bool has_room_for(std::size_t bytes) const override { return tx_.size() + bytes <= kMaxWrite; }
  Status flush() override;
  void maintain(double now_s) override;
  bool connected() const override { return client_.has_value(); }
  bool closed() const override { return lost_ && config_.reconnect_period_s <= 0; }
  std::optional<SocketAddress> peer() const override { return config_.server; }
  std::optional<SocketAddress> local_address() const override { return std::nullopt; }
  int fd() const override { return client_ ? client_->fd() : -1; }

  static constexpr std::size_t kMaxWrite = 65536;

 private:
  explicit TcpClientLink(const Config& config) : Link(config.name), config_(config) {}
  void lose(double now_s);

  Config config_;
  std::optional<TcpClient> client_;
  double next_connect_s_ = 0;
  bool lost_ = false;
  bool warned_ = false;  ///< a failed connect is said once, not every period
};

class TcpServerLink final : public Link {
 public:
  static Expected<std::unique_ptr<TcpServerLink>> listen(const std::string& bind_address, uint16_t port,
                                                         const std::string& name);

  std::size_t read_some(std::size_t max_reads, const ChunkHandler& on_chunk) override;
  bool wait_readable(int timeout_ms) const override { return server_.wait_readable(timeout_ms); }
  Status send(std::span<const uint8_t> bytes) override;
  void queue(std::span<const uint8_t> frame) override { tx_.insert(tx_.end(), frame.begin(), frame.end()); }
  bool has_room_for(std::size_t bytes) const override { return tx_.size() + bytes <= TcpClientLink::kMaxWrite; }
  Status flush() override;
  bool wait_connected(int timeout_ms) override;
  bool connected() const override { return server_.connected(); }
  bool closed() const override { return closed_; }
  std::optional<SocketAddress> peer() const override { return server_.client(); }
  std::optional<SocketAddress> local_address() const override { return server_.local_address(); }
  int fd() const override { return server_.client_fd(); }

 private:
  explicit TcpServerLink(TcpServer server, const std::string& name) : Link(name), server_(std::move(server)) {}

  TcpServer server_;
  bool closed_ = false;
};

}  // namespace hitl::net
