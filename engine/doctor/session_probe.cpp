#include "engine/doctor/session_probe.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <array>
#include <cerrno>

#include "base/common/clock.h"
#include "base/mavlink/frame_encoder.h"
#include "base/mavlink/frame_parser.h"
#include "base/mavlink/heartbeat.h"
#include "base/mavlink/message_set.h"

namespace hitl::doctor {

void probe_session(uint16_t port, double listen_s, const std::function<void(const mavlink::Frame&, double)>& on_frame) {
  const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return;
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(port);
  to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::connect(fd, reinterpret_cast<const sockaddr*>(&to), sizeof to) != 0) {
    ::close(fd);
    return;
  }
  const auto messages = mavlink::MessageSet::compiled();
  mavlink::FrameParser parser(messages);
  mavlink::FrameEncoder encoder(mavlink::kGcsSystemId, mavlink::kCompIdMissionPlanner);
  const double end_s = monotonic_s() + listen_s;
  double next_heartbeat_s = 0;
  std::array<uint8_t, 65536> buf{};
  for (;;) {
    const double now_s = monotonic_s();
    if (now_s >= end_s) break;
    if (now_s >= next_heartbeat_s) {
      next_heartbeat_s = now_s + 1.0;
      mavlink::FrameBuffer frame;
      const std::size_t n = encoder.encode(mavlink::gcs_heartbeat(), frame);
      (void)::send(fd, frame.data(), n, 0);
    }
    pollfd p{fd, POLLIN, 0};
    const double wait_s = std::min(end_s, next_heartbeat_s) - now_s;
    if (::poll(&p, 1, static_cast<int>(wait_s * 1000) + 1) <= 0) continue;
    const ssize_t n = ::recv(fd, buf.data(), buf.size(), MSG_DONTWAIT);
    if (n < 0 && errno == ECONNREFUSED) break;  // nothing listens there: no session
    if (n <= 0) continue;
    parser.parse_datagram({buf.data(), static_cast<std::size_t>(n)},
                          [&](const mavlink::Frame& f) { on_frame(f, monotonic_s()); });
  }
  ::close(fd);
}

}  // namespace hitl::doctor
