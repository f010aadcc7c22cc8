#include "target/vio-server/odometry_receiver.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>

namespace hitl::vio {

OdometryReceiver::OdometryReceiver(int fd, uint16_t port)
    : fd_(fd), port_(port), messages_(mavlink::MessageSet::compiled()), parser_(messages_) {}

OdometryReceiver::~OdometryReceiver() {
  if (fd_ >= 0) ::close(fd_);
}

Expected<std::unique_ptr<OdometryReceiver>> OdometryReceiver::open(const std::string& ip, uint16_t port) {
  const std::string where = "UDP " + ip + ":" + std::to_string(port);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(port);
  if (::inet_pton(AF_INET, ip.c_str(), &addr.sin_addr) != 1) return Error{"\"" + ip + "\" is not an IPv4 address"};
  const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd < 0) return Error{"cannot open a UDP socket: " + std::string(std::strerror(errno))};
  if (::bind(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0) {
    const int err = errno;
    ::close(fd);
    if (err == EADDRINUSE) return Error{where + " is already in use (is another voxl-hitl-vio-server running?)"};
    if (err == EADDRNOTAVAIL) return Error{where + ": " + ip + " is not an address of this machine"};
    return Error{"cannot bind " + where + ": " + std::strerror(err)};
  }
  socklen_t len = sizeof addr;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len);
  return std::unique_ptr<OdometryReceiver>(new OdometryReceiver(fd, ntohs(addr.sin_port)));
}

void OdometryReceiver::drain(const OdometryHandler& on_odometry, const MalformedHandler& on_malformed) {
  std::array<uint8_t, 65536> buf;
  for (;;) {
    sockaddr_in from{};
    socklen_t from_len = sizeof from;
    const ssize_t n = ::recvfrom(fd_, buf.data(), buf.size(), 0, reinterpret_cast<sockaddr*>(&from), &from_len);
    if (n < 0) return;  // EAGAIN: drained (other errors are transient on UDP)
    char host[INET_ADDRSTRLEN] = "?";
    ::inet_ntop(AF_INET, &from.sin_addr, host, sizeof host);
    handle(buf.data(), static_cast<std::size_t>(n), std::string(host) + ":" + std::to_string(ntohs(from.sin_port)),
           on_odometry, on_malformed);
  }
}

void OdometryReceiver::handle(const uint8_t* data, std::size_t len, const std::string& sender,
                              const OdometryHandler& on_odometry, const MalformedHandler& on_malformed) {
  ++counters_.datagrams;
  counters_.bytes += len;
  const mavlink::ParserStats before = parser_.stats();
  parser_.parse_datagram({data, len}, [&](const mavlink::Frame& frame) {
    // Frames of ids hitl does not compile in (desc == nullptr) are counted with the other messages.
    if (frame.desc != nullptr && frame.is<mavlink::msg::Odometry>()) {
      ++counters_.odometry;
      on_odometry(frame.as<mavlink::msg::Odometry>());
    } else {
      ++counters_.other_messages;
    }
  });
  const mavlink::ParserStats& after = parser_.stats();
  const uint64_t crc = after.crc_errors - before.crc_errors;
  const uint64_t garbage = after.parse_errors - before.parse_errors;
  const uint64_t truncated = after.truncated - before.truncated;
  const uint64_t flags = after.bad_incompat_flags - before.bad_incompat_flags;
  if (crc + garbage + truncated + flags == 0) return;
  ++counters_.malformed_datagrams;
  counters_.crc_errors += crc;
  counters_.garbage_runs += garbage;
  counters_.truncated += truncated;
  counters_.bad_incompat_flags += flags;
  std::string why = "from ";
  why.append(sender).append(", ").append(std::to_string(len)).append(" bytes:");
  auto add = [&why](uint64_t n, const char* what) {
    if (n == 0) return;
    why.append(" ").append(std::to_string(n)).append(what);
  };
  add(crc, " checksum error(s)");
  add(garbage, " run(s) of non-MAVLink bytes");
  add(truncated, " frame(s) cut off");
  add(flags, " frame(s) with unknown incompat flags");
  on_malformed(why);
}

}  // namespace hitl::vio
