// The latency the adb tunnel adds, on loopback: a UDP echo stands in for the board's port; the round
// trip client -> echo -> client is timed directly, and through the host side (DatagramTunnel) and
// hitl-adb-relay's loop (Relay), each on its own thread as in use: client -> tunnel's local UDP ->
// pump -> TCP -> relay -> UDP -> echo and back. adb itself (its server, USB, adbd) is not in the
// path here; on a real board it adds its own share (docs/adb.md). Prints figures; asserts nothing.
//   Usage: adb_tunnel_latency_bench [ROUND_TRIPS]   (default 20000 per case)
#include <poll.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

#include "engine/net/datagram_tunnel.h"
#include "engine/net/udp_endpoint.h"
#include "target/adb-relay/relay.h"

using namespace hitl;
using Clock = std::chrono::steady_clock;

namespace {

net::UdpEndpoint open_udp() {
  net::UdpEndpoint::Config c;
  c.bind_address = "127.0.0.1";
  c.policy = net::PartnerPolicy::LastSender;
  auto ep = net::UdpEndpoint::open(c);
  if (!ep) {
    std::fprintf(stderr, "%s\n", ep.error().message.c_str());
    std::exit(1);
  }
  return std::move(ep.value());
}

/// The board's port: every datagram goes back to its sender.
class Echo {
 public:
  Echo() : ep_(open_udp()), thread_([this] {
    while (!stop_.load()) {
      if (!ep_.wait_readable(50)) continue;
      while (auto d = ep_.receive()) (void)ep_.send_to(d->from, d->bytes);
    }
  }) {}
  ~Echo() {
    stop_.store(true);
    thread_.join();
  }
  uint16_t port() const { return ep_.local_address().port(); }

 private:
  net::UdpEndpoint ep_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

struct Figures {
  double p50_us, p90_us, p99_us, max_us, mean_us;
  int lost;
};

Figures measure(const net::SocketAddress& to, int round_trips, std::size_t payload_bytes) {
  net::UdpEndpoint client = open_udp();
  std::vector<uint8_t> payload(payload_bytes, 0xA5);
  std::vector<double> us;
  us.reserve(static_cast<std::size_t>(round_trips));
  int lost = 0;
  for (int i = 0; i < round_trips + 200; ++i) {  // the first 200 warm up
    payload[0] = static_cast<uint8_t>(i);
    const auto t0 = Clock::now();
    (void)client.send_to(to, payload);
    bool back = false;
    while (!back && client.wait_readable(1000)) {
      while (auto d = client.receive())
        if (!d->bytes.empty() && d->bytes[0] == payload[0]) back = true;
    }
    const auto t1 = Clock::now();
    if (!back) {
      ++lost;
      continue;
    }
    if (i >= 200) us.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count());
  }
  std::sort(us.begin(), us.end());
  auto pct = [&](double p) { return us.empty() ? 0.0 : us[std::min(us.size() - 1, static_cast<std::size_t>(p * static_cast<double>(us.size())))]; };
  double sum = 0;
  for (double v : us) sum += v;
  return {pct(0.50), pct(0.90), pct(0.99), us.empty() ? 0.0 : us.back(), us.empty() ? 0.0 : sum / static_cast<double>(us.size()), lost};
}

void print(const char* name, std::size_t bytes, const Figures& f) {
  std::printf("%-22s %6zu B   p50 %7.1f us   p90 %7.1f us   p99 %7.1f us   max %8.1f us   mean %7.1f us   lost %d\n", name, bytes,
              f.p50_us, f.p90_us, f.p99_us, f.max_us, f.mean_us, f.lost);
}

}  // namespace

int main(int argc, char** argv) {
  const int round_trips = argc > 1 ? std::atoi(argv[1]) : 20000;
  Echo echo;
  adb::RelayConfig rc;
  rc.tcp_port = 0;
  rc.hil_port = echo.port();
  rc.vio_port = echo.port();
  rc.gcs_port = echo.port();
  rc.hil_source_port = 0;
  rc.gcs_source_port = 0;
  std::string error;
  auto relay = adb::Relay::open(rc, [](const std::string&) {}, &error);
  if (!relay) {
    std::fprintf(stderr, "relay: %s\n", error.c_str());
    return 1;
  }
  std::atomic<bool> stop{false};
  std::thread relay_thread([&] { relay->run(stop); });
  const uint16_t relay_port = relay->tcp_port();
  auto tunnel = net::DatagramTunnel::open({}, [relay_port]() -> Expected<std::unique_ptr<adb::FramedStream>> {
    auto r = net::connect_to_relay(net::SocketAddress::resolve("127.0.0.1", relay_port).value(), 2000);
    if (!r.stream) return Error{r.error};
    return std::move(r.stream);
  });
  if (!tunnel) {
    std::fprintf(stderr, "tunnel: %s\n", tunnel.error().message.c_str());
    return 1;
  }
  const auto direct = net::SocketAddress::resolve("127.0.0.1", echo.port()).value();
  const auto through = (*tunnel)->local_endpoint(adb::Channel::Hil);
  std::printf("UDP round trips on loopback, %d per case (hitl-adb-relay and the host side in-process, own threads)\n", round_trips);
  for (std::size_t bytes : {std::size_t{80}, std::size_t{1400}}) {  // a HIL_SENSOR frame; a batch near the MTU
    const auto d = measure(direct, round_trips, bytes);
    const auto t = measure(through, round_trips, bytes);
    print("direct UDP", bytes, d);
    print("through the tunnel", bytes, t);
    std::printf("%-22s %6zu B   p50 %+7.1f us   p99 %+7.1f us (round trip; one way is about half)\n", "added by the tunnel", bytes,
                t.p50_us - d.p50_us, t.p99_us - d.p99_us);
  }
  const auto s = (*tunnel)->stats();
  std::printf("tunnel ping round trip (1 Hz, pump + relay): %.1f us, max %.1f us\n", s.rtt_ms.value_or(0) * 1000, s.rtt_max_ms * 1000);
  tunnel->reset();
  stop.store(true);
  relay_thread.join();
  return 0;
}
