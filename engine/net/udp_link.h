// A Link over one UDP socket (link.h): a fixed peer (the board, udp:HOST:PORT, the adb tunnel's
// local end) or one learnt from who spoke (udpin:PORT: the last sender), as UdpEndpoint's
// PartnerPolicy says. With hear_peer_only, datagrams from any other address are dropped unparsed and
// counted (ignored_other_address): a PX4 MAVLink instance answers from its own port, so anything
// else is not the board.
#pragma once

#include <memory>

#include "engine/net/link.h"
#include "engine/net/udp_endpoint.h"

namespace hitl::net {

class UdpLink final : public Link {
 public:
  struct Config {
    UdpEndpoint::Config endpoint;
    bool hear_peer_only = false;  ///< drop datagrams not from endpoint.peer (needs a peer)
  };
  /// Opens and binds; a port in use or a bad address is an Error naming both.
  static Expected<std::unique_ptr<UdpLink>> open(const Config& config);

  std::size_t read_some(std::size_t max_reads, const ChunkHandler& on_chunk) override;
  bool wait_readable(int timeout_ms) const override { return endpoint_.wait_readable(timeout_ms); }
  Status send(std::span<const uint8_t> bytes) override;
  void queue(std::span<const uint8_t> frame) override { tx_.insert(tx_.end(), frame.begin(), frame.end()); }
  bool has_room_for(std::size_t bytes) const override {
    return tx_.empty() || tx_.size() + bytes <= UdpEndpoint::kMaxDatagram;
  }
  Status flush() override;
  bool connected() const override { return true; }
  std::optional<SocketAddress> peer() const override { return endpoint_.partner(); }
  std::optional<SocketAddress> local_address() const override { return endpoint_.local_address(); }
  int fd() const override { return endpoint_.fd(); }
  std::vector<std::string> take_send_errors() override { return endpoint_.take_send_errors(); }
  UdpEndpoint::BufferSizes buffer_sizes() const { return endpoint_.buffer_sizes(); }
  /// UdpEndpoint::poll_kernel_drops(), into stats().kernel_rx_drops.
  void poll_kernel_drops();
  std::size_t receive_queue_bytes() const { return endpoint_.receive_queue_bytes(); }
  void set_receive_buffer(int bytes) { endpoint_.set_receive_buffer(bytes); }
  /// send() that tells a full send buffer apart (WouldBlock: keep it and wait for POLLOUT).
  SendOutcome try_send(std::span<const uint8_t> bytes);

 private:
  UdpLink(UdpEndpoint endpoint, const Config& config);
  void sync_stats();

  UdpEndpoint endpoint_;
  std::optional<SocketAddress> only_from_;
};

}  // namespace hitl::net
