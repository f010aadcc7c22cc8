#include "tests/support/sim_load.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <thread>

#include "base/common/clock.h"
#include "base/mavlink/frame_encoder.h"
#include "base/mavlink/frame_parser.h"
#include "base/mavlink/messages.h"
#include "engine/net/udp_endpoint.h"
#include "tests/support/json_lines.h"
#include "tests/support/loopback.h"
#include "tests/support/process.h"

namespace hitl::test {
namespace {

using namespace std::chrono_literals;

int open_udp() {
  const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK, 0);
  if (fd < 0) return -1;
  sockaddr_in a = loopback_address(0);
  int small = 4096;  // nobody reads the clients' sockets: keep what the kernel holds for them small
  ::setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &small, sizeof small);
  if (::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
    ::close(fd);
    return -1;
  }
  return fd;
}

void send_to(int fd, const sockaddr_in& to, const uint8_t* bytes, std::size_t n) {
  (void)::sendto(fd, bytes, n, MSG_DONTWAIT, reinterpret_cast<const sockaddr*>(&to), sizeof to);
}

}  // namespace

SimLoadResult run_sim_load(const SimLoadConfig& config) {
  SimLoadResult r;
  rlimit nofile{};
  if (::getrlimit(RLIMIT_NOFILE, &nofile) == 0 && nofile.rlim_cur < nofile.rlim_max) {
    nofile.rlim_cur = nofile.rlim_max;
    ::setrlimit(RLIMIT_NOFILE, &nofile);
  }
  const uint16_t board_port = free_udp_port(), sim_port = free_udp_port(), clients_port = free_udp_port();
  net::UdpEndpoint::Config bc;
  bc.bind_address = "127.0.0.1";
  bc.bind_port = board_port;
  bc.name = "load board";
  auto board = net::UdpEndpoint::open(bc);
  if (!board) {
    r.err = board.error().message;
    return r;
  }
  int rcv = 4 << 20;
  ::setsockopt(board->fd(), SOL_SOCKET, SO_RCVBUF, &rcv, sizeof rcv);

  const double warmup_s = 1.0;
  const double load_start_s = 1.0;  // after the first HIL_SENSOR: clients, then the flood
  std::vector<std::string> args{hitl_binary(), "--json", "sim", "-i", "127.0.0.1", "--hil-port", std::to_string(board_port),
                                "--local-port", std::to_string(sim_port), "--no-vio", "--clients", std::to_string(clients_port),
                                "--duration", std::to_string(warmup_s + load_start_s + config.measure_s + 3.0)};
  args.insert(args.end(), config.extra_args.begin(), config.extra_args.end());
  Process sim(args);

  // The board: kernel receive time of every HIL_SENSOR.
  std::vector<double> sensor_s;
  std::atomic<bool> board_stop{false};
  std::thread board_thread([&]() {
    auto set = mavlink::MessageSet::compiled();
    mavlink::FrameParser parser(set);
    while (!board_stop.load()) {
      if (!board->wait_readable(50)) continue;
      while (auto d = board->receive()) {
        const double t = static_cast<double>(d->rx_time_unix_ns) * 1e-9;
        parser.parse_datagram(d->bytes, [&](const mavlink::Frame& f) {
          if (f.is<mavlink::msg::HilSensor>()) sensor_s.push_back(t);
        });
      }
    }
  });
  const auto stop_board = [&]() {
    board_stop = true;
    if (board_thread.joinable()) board_thread.join();
  };

  // Wait for the session to run, then open the clients.
  for (int i = 0; i < 300 && sim.running(); ++i) {
    std::this_thread::sleep_for(20ms);
    if (!sim.err().empty() && sim.err().find("HIL_SENSOR") != std::string::npos) break;
  }
  std::this_thread::sleep_for(std::chrono::duration<double>(warmup_s));
  std::vector<int> clients;
  clients.reserve(static_cast<std::size_t>(config.clients));
  for (int i = 0; i < config.clients; ++i) {
    const int fd = open_udp();
    if (fd < 0) break;
    clients.push_back(fd);
  }
  r.clients_opened = static_cast<int>(clients.size());
  const int stranger = open_udp();

  mavlink::FrameEncoder client_encoder(255, 190);
  mavlink::msg::Heartbeat hb;
  hb.type = 6;  // MAV_TYPE_GCS
  hb.autopilot = 8;
  mavlink::FrameBuffer hb_buf;
  const std::size_t hb_n = client_encoder.encode(hb, hb_buf);
  const sockaddr_in to_clients = loopback_address(clients_port), to_hil = loopback_address(sim_port);

  const double load_t0 = unix_time_ns() * 1e-9;
  std::atomic<bool> load_stop{false};
  std::thread heartbeats([&]() {
    double next = 0;
    while (!load_stop.load()) {
      const double now = unix_time_ns() * 1e-9 - load_t0;
      if (now >= next) {
        next += config.heartbeat_period_s;
        for (const int fd : clients) send_to(fd, to_clients, hb_buf.data(), hb_n);
      }
      std::this_thread::sleep_for(20ms);
    }
  });
  std::thread flood([&]() {
    std::this_thread::sleep_for(std::chrono::duration<double>(load_start_s));
    uint8_t junk[600];
    uint32_t x = 12345;
    const double t0 = unix_time_ns() * 1e-9;
    for (uint64_t i = 0; i < config.flood_datagrams && !load_stop.load(); ++i) {
      const bool to_client_port = i % 2 == 0;
      const int fd = to_client_port && !clients.empty() ? clients.front() : stranger;
      if (i % 4 < 2) {  // a valid frame
        send_to(fd, to_client_port ? to_clients : to_hil, hb_buf.data(), hb_n);
      } else {
        const std::size_t n = 8 + x % 500;
        for (std::size_t k = 0; k < n; ++k) {
          x = x * 1664525u + 1013904223u;
          junk[k] = static_cast<uint8_t>(x >> 24);
        }
        junk[0] = 0xFD;
        send_to(fd, to_client_port ? to_clients : to_hil, junk, n);
      }
      ++r.flood_sent;
      if (i % 2000 == 1999) std::this_thread::yield();
    }
    r.flood_s = unix_time_ns() * 1e-9 - t0;
  });

  std::this_thread::sleep_for(std::chrono::duration<double>(load_start_s + config.measure_s));
  const double t_end = unix_time_ns() * 1e-9;
  load_stop = true;
  heartbeats.join();
  flood.join();
  r.exit_code = sim.wait(60s);
  stop_board();
  r.err = sim.err();
  r.summary = last_json_line(sim.out());
  for (const int fd : clients) ::close(fd);
  if (stranger >= 0) ::close(stranger);

  // One-second windows from when the load began, up to when it stopped.
  const double t0 = load_t0;
  const int windows = static_cast<int>(std::floor(t_end - t0));
  r.per_second_hz.assign(static_cast<std::size_t>(std::max(0, windows)), 0.0);
  double last = t0;  // a silence at either end of the window counts as a gap too
  for (const double t : sensor_s) {
    if (t < t0 || t >= t0 + windows) continue;
    ++r.per_second_hz[static_cast<std::size_t>(t - t0)];
    ++r.sensors;
    r.max_gap_s = std::max(r.max_gap_s, t - last);
    last = t;
  }
  r.max_gap_s = std::max(r.max_gap_s, t0 + windows - last);
  r.worst_1s_rate_hz = r.per_second_hz.empty() ? 0 : *std::min_element(r.per_second_hz.begin(), r.per_second_hz.end());
  return r;
}

}  // namespace hitl::test
