// A TCP listener many clients connect to, as mavlink-router's TCP server port (5760): ground
// station tools (QGroundControl, MAVProxy --master=tcp:..., pymavlink) come and go. A hub link
// (link.h): each client's stream is parsed apart, frames say which client sent them, and sends go
// to every client or to the ones the router names. Bounded: at most max_clients clients (a further
// one is closed at once, said once), and at most kMaxPending_bytes waiting for a slow client (what
// does not fit is dropped whole and counted as a send error, said once per client): one slow
// client never holds the others or the caller's loop.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "engine/net/link.h"

namespace hitl::net {

class TcpHubLink final : public Link {
 public:
  static Expected<std::unique_ptr<TcpHubLink>> listen(const std::string& bind_address, uint16_t port, std::size_t max_clients,
                                                      const std::string& name);
  ~TcpHubLink() override;

  std::size_t read_some(std::size_t max_reads, const ChunkHandler& on_chunk) override;
  std::size_t drain_from(mavlink::FrameParser& parser, const SourcedFrameHandler& on_frame, std::size_t max_reads = kAll) override;
  bool wait_readable(int timeout_ms) const override;
  Status send(std::span<const uint8_t> bytes) override;
  Status send_to_peers(std::span<const uint8_t> bytes, const std::optional<SocketAddress>& except,
                       std::span<const SocketAddress> only) override;
  void queue(std::span<const uint8_t> frame) override { tx_.insert(tx_.end(), frame.begin(), frame.end()); }
  bool has_room_for(std::size_t bytes) const override { return tx_.size() + bytes <= kMaxPending_bytes; }
  Status flush() override;
  void maintain(double now_s) override;
  bool connected() const override { return !clients_.empty(); }
  bool hub() const override { return true; }
  /// The latest client to connect (the health line's partner); nullopt with none.
  std::optional<SocketAddress> peer() const override;
  std::optional<SocketAddress> local_address() const override { return local_; }
  /// An epoll descriptor: readable when a client sent something or a new one is waiting.
  int fd() const override { return epoll_fd_; }
  std::size_t client_count() const { return clients_.size(); }

  static constexpr std::size_t kMaxPending_bytes = 256 * 1024;

 private:
  struct Client;
  TcpHubLink(int listen_fd, int epoll_fd, SocketAddress local, std::size_t max_clients, const std::string& name);
  void accept_waiting();
  void drop(std::size_t index, const std::string& why);
  /// Writes what waits for `c`, then `bytes`; false when the client went away.
  bool write(Client& c, std::span<const uint8_t> bytes);

  int listen_fd_ = -1;
  int epoll_fd_ = -1;
  SocketAddress local_;
  std::size_t max_clients_;
  std::vector<std::unique_ptr<Client>> clients_;
  std::vector<uint8_t> rx_buffer_;
  bool said_full_ = false;
};

}  // namespace hitl::net
