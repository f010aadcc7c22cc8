// A non-blocking UDP endpoint: binds a local address, sends to its partner, and learns
// the partner from what it hears (router style: answer the last sender; PX4 style:
// keep the first sender for good). Later layers add TCP and routing on the same shape.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "base/common/expected.h"
#include "engine/net/socket_address.h"

namespace hitl::net {

enum class PartnerPolicy {
  Fixed,       ///< always send to the configured peer
  LastSender,  ///< answer the source of the last datagram; the configured peer until one arrives
  FirstSender  ///< lock onto the first source heard and keep it (a PX4 MAVLink instance)
};

struct EndpointStats {
  uint64_t datagrams_in = 0;
  uint64_t datagrams_out = 0;
  uint64_t bytes_in = 0;
  uint64_t bytes_out = 0;
  uint64_t send_errors = 0;  ///< datagrams the kernel refused (never counted in datagrams_out)
  int last_send_errno = 0;   ///< the latest refusal's errno, 0 when none
  uint64_t partner_changes = 0;
  uint64_t kernel_rx_drops = 0;  ///< datagrams the kernel dropped for a full receive buffer (SO_RXQ_OVFL)
};

/// What one send did: left, or the send buffer was full (EAGAIN/ENOBUFS: try again when writable,
/// not an error), or the kernel refused it (counted in send_errors).
enum class SendOutcome { Sent, WouldBlock, Refused };

struct Datagram {
  std::span<const uint8_t> bytes;
  SocketAddress from;
  int64_t rx_time_unix_ns = 0;  ///< kernel receive time (CLOCK_REALTIME)
};

class UdpEndpoint {
 public:
  struct Config {
    std::string bind_address = "0.0.0.0";
    uint16_t bind_port = 0;  ///< 0: ephemeral
    std::optional<SocketAddress> peer;
    PartnerPolicy policy = PartnerPolicy::LastSender;
    std::string name = "UDP";  ///< names the endpoint in errors ("--port", "HIL link")
    int receive_buffer_bytes = 1 << 20;  ///< SO_RCVBUF asked for (the kernel caps it at net.core.rmem_max)
    int send_buffer_bytes = 0;           ///< SO_SNDBUF asked for; 0: the kernel's default (net.core.wmem_default)
  };
  /// The socket buffers the kernel granted (it doubles what it was asked, capped at *mem_max).
  struct BufferSizes {
    int receive_bytes = 0, send_bytes = 0;
  };

  /// Opens and binds; a port in use or a bad address is an Error naming both.
  static Expected<UdpEndpoint> open(const Config& config);

  UdpEndpoint(UdpEndpoint&& other) noexcept;
  UdpEndpoint& operator=(UdpEndpoint&& other) noexcept;
  UdpEndpoint(const UdpEndpoint&) = delete;
  UdpEndpoint& operator=(const UdpEndpoint&) = delete;
  ~UdpEndpoint();

  /// The next waiting datagram, or nullopt when none is waiting (never blocks).
  /// The bytes stay valid until the next call.
  std::optional<Datagram> receive();
  /// Waits up to timeout_ms for a datagram to arrive; false on timeout or signal.
  bool wait_readable(int timeout_ms) const;

  /// Sends one datagram to the partner; an Error when no partner is known yet or the send fails.
  Status send(std::span<const uint8_t> bytes);
  Status send_to(const SocketAddress& to, std::span<const uint8_t> bytes);
  /// send_to() that tells a full send buffer apart: WouldBlock is not counted as a send error.
  SendOutcome try_send_to(const SocketAddress& to, std::span<const uint8_t> bytes);

  /// Appends a frame to the datagram being built; sends first when it would exceed `max_datagram`.
  Status queue(std::span<const uint8_t> frame);
  /// Sends what queue() collected as one datagram.
  Status flush();
  /// Bytes queue() holds for the next datagram.
  std::size_t queued_bytes() const { return tx_batch_.size(); }

  /// The first failed send to each destination, once each, in words (errno and the likely fix,
  /// net::describe_send_error): for the caller to say at once. Later failures are only counted.
  std::vector<std::string> take_send_errors();

  const std::optional<SocketAddress>& partner() const { return partner_; }
  void set_partner(const SocketAddress& address) { partner_ = address; }
  const SocketAddress& local_address() const { return local_; }
  const EndpointStats& stats() const { return stats_; }
  BufferSizes buffer_sizes() const;
  /// Reads the socket's drop count now (SO_MEMINFO), not only when a datagram arrives: the
  /// datagrams the kernel dropped at the end of a flood, after which nothing more comes, are
  /// counted too (kernel_rx_drops). The same running count SO_RXQ_OVFL reports, so neither counts twice.
  void poll_kernel_drops();
  /// The bytes (with the kernel's per-datagram overhead) waiting in the receive buffer (SO_MEMINFO).
  std::size_t receive_queue_bytes() const;
  /// Asks for a receive buffer of `bytes` (SO_RCVBUF: the kernel doubles it, capped at net.core.rmem_max).
  void set_receive_buffer(int bytes);
  const std::string& name() const { return config_.name; }
  int fd() const { return fd_; }

  static constexpr std::size_t kMaxDatagram = 1472;  ///< one Ethernet MTU of UDP payload

 private:
  UdpEndpoint(int fd, Config config, SocketAddress local);
  void learn(const SocketAddress& from);
  /// Counts a refused send and keeps its words for take_send_errors() (once per destination).
  Error refused(const SocketAddress& to, int error);
  /// Adds what the kernel's running drop count (SO_RXQ_OVFL, SO_MEMINFO) shows beyond the last one.
  void add_kernel_drops(uint32_t running_count);

  int fd_ = -1;
  Config config_;
  SocketAddress local_;
  std::optional<SocketAddress> partner_;
  bool locked_ = false;
  EndpointStats stats_;
  uint32_t last_rxq_ovfl_ = 0;  ///< the kernel's running SO_RXQ_OVFL count (it wraps at 2^32)
  std::vector<uint8_t> rx_buffer_;
  std::vector<uint8_t> tx_batch_;
  std::vector<SocketAddress> failed_destinations_;
  std::vector<std::string> unreported_send_errors_;
};

}  // namespace hitl::net
