#include "tests/support/mavlink_peer.h"

#include <time.h>

#include <stdexcept>

namespace hitl::test {
namespace {

net::UdpEndpoint open_endpoint(uint16_t local_port, uint16_t peer_port) {
  net::UdpEndpoint::Config c;
  c.bind_address = "127.0.0.1";
  c.bind_port = local_port;
  c.name = "test peer";
  if (peer_port != 0) c.peer = net::SocketAddress::resolve("127.0.0.1", peer_port).value();
  c.policy = peer_port != 0 ? net::PartnerPolicy::Fixed : net::PartnerPolicy::LastSender;
  auto ep = net::UdpEndpoint::open(c);
  if (!ep) throw std::runtime_error(ep.error().message);
  return std::move(ep.value());
}

}  // namespace

MavlinkPeer::MavlinkPeer(uint16_t local_port, uint16_t peer_port, uint8_t sysid, uint8_t compid)
    : endpoint_(open_endpoint(local_port, peer_port)), messages_(mavlink::MessageSet::compiled()), encoder_(sysid, compid) {}

MavlinkPeer::~MavlinkPeer() { stop(); }

void MavlinkPeer::send_bytes(std::span<const uint8_t> bytes) {
  std::lock_guard<std::mutex> lock(send_mutex_);
  (void)endpoint_.send(bytes);
}

void MavlinkPeer::start_paced(double rate_hz, std::chrono::milliseconds duration,
                              std::function<void(MavlinkPeer&)> make_and_send) {
  stop_ = false;
  pacer_ = std::thread([this, rate_hz, duration, make_and_send]() {
    const int64_t period_ns = static_cast<int64_t>(1e9 / rate_hz);
    timespec next{};
    clock_gettime(CLOCK_MONOTONIC, &next);
    const auto end = std::chrono::steady_clock::now() + duration;
    while (!stop_ && std::chrono::steady_clock::now() < end) {
      make_and_send(*this);
      ++paced_sent_;
      next.tv_nsec += period_ns;
      while (next.tv_nsec >= 1000000000) {
        next.tv_nsec -= 1000000000;
        ++next.tv_sec;
      }
      clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &next, nullptr);
    }
  });
}

void MavlinkPeer::stop() {
  stop_ = true;
  if (pacer_.joinable()) pacer_.join();
}

std::vector<mavlink::Frame> MavlinkPeer::receive_for(std::chrono::milliseconds timeout) {
  std::vector<mavlink::Frame> frames;
  mavlink::FrameParser parser(messages_);
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < deadline) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (!endpoint_.wait_readable(static_cast<int>(std::max<int64_t>(1, left.count())))) continue;
    while (auto d = endpoint_.receive())
      parser.parse_datagram(d->bytes, [&](const mavlink::Frame& f) { frames.push_back(f); });
  }
  return frames;
}

}  // namespace hitl::test
