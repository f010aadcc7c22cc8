// The floor under sim_timing_bench's real-time figures: a loop with no simulator in it that makes
// the same system calls and sends the same traffic as a real-time `hitl sim` session with VIO and a
// truth client (docs/sim.md "Measured"). Each tick, on an absolute deadline with a 1 ns timer
// slack: drain the board's answers, send one HIL_SENSOR (73 bytes) to the board, one ODOMETRY
// (245 bytes) to the VIO port, and every fifth tick one ODOMETRY to the truth client the client
// port has heard from (with `sendmmsg_both`, the first two go in one sendmmsg). What it costs and how its sends are spaced is what this machine charges any
// simulator at 250 Hz; `hitl sim`'s own share is the difference. It prints the same
// {"type":"status"} lines (steps, sim_time_s) as `hitl --json sim` so the bench watches both alike.
#include "bench/sim/timing_floor.h"

#include <netinet/in.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>

#include "base/mavlink/frame_encoder.h"
#include "base/mavlink/messages.h"
#include "tests/support/loopback.h"

namespace hitl::bench {
namespace {

int bound_socket(uint16_t port) {
  const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK, 0);
  sockaddr_in a = test::loopback_address(port);
  if (fd < 0 || ::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
    std::perror("timing floor: bind");
    std::exit(1);
  }
  return fd;
}

void add_ns(timespec& t, long ns) {
  t.tv_nsec += ns;
  while (t.tv_nsec >= 1000000000L) {
    t.tv_nsec -= 1000000000L;
    ++t.tv_sec;
  }
}

}  // namespace

int run_timing_floor(const FloorPorts& ports, double seconds, bool sendmmsg_both) {
  const int board = bound_socket(ports.sim), vio = bound_socket(0), clients = bound_socket(ports.clients);
  const sockaddr_in board_to = test::loopback_address(ports.board), vio_to = test::loopback_address(ports.vio);
  sockaddr_in client_to{};
  bool client_known = false;

  mavlink::FrameEncoder encoder(1, 250);
  mavlink::FrameBuffer sensor_buf, odometry_buf;
  mavlink::msg::HilSensor sensor;
  sensor.fields_updated = 0x1FFF;
  mavlink::msg::Odometry odometry;
  odometry.frame_id = 20;  // MAV_FRAME_LOCAL_FRD
  uint8_t rx[65536];

  prctl(PR_SET_TIMERSLACK, 1UL, 0UL, 0UL, 0UL);
  constexpr long kPeriod_ns = 4000000;  // 250 Hz
  timespec due{};
  ::clock_gettime(CLOCK_MONOTONIC, &due);
  const uint64_t ticks = static_cast<uint64_t>(seconds * 250.0);
  for (uint64_t k = 1; k <= ticks; ++k) {
    add_ns(due, kPeriod_ns);
    while (::clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &due, nullptr) == EINTR) {}
    while (::recv(board, rx, sizeof rx, MSG_DONTWAIT) > 0) {}  // the board's answers
    sockaddr_in from{};
    socklen_t from_len = sizeof from;
    while (::recvfrom(clients, rx, sizeof rx, MSG_DONTWAIT, reinterpret_cast<sockaddr*>(&from), &from_len) > 0) {
      client_to = from;
      client_known = true;
    }
    sensor.time_usec = k * 4000;
    odometry.time_usec = k * 4000;
    const std::size_t sensor_n = encoder.encode(sensor, sensor_buf);
    const std::size_t odometry_n = encoder.encode(odometry, odometry_buf);
    if (sendmmsg_both) {  // one system call for both datagrams (from one socket)
      iovec iov[2] = {{sensor_buf.data(), sensor_n}, {odometry_buf.data(), odometry_n}};
      mmsghdr m[2]{};
      m[0].msg_hdr.msg_name = const_cast<sockaddr_in*>(&board_to);
      m[0].msg_hdr.msg_namelen = sizeof board_to;
      m[0].msg_hdr.msg_iov = &iov[0];
      m[0].msg_hdr.msg_iovlen = 1;
      m[1].msg_hdr.msg_name = const_cast<sockaddr_in*>(&vio_to);
      m[1].msg_hdr.msg_namelen = sizeof vio_to;
      m[1].msg_hdr.msg_iov = &iov[1];
      m[1].msg_hdr.msg_iovlen = 1;
      ::sendmmsg(board, m, 2, MSG_DONTWAIT | MSG_NOSIGNAL);
    } else {  // as hitl sim does: one sendto each, from the HIL and the VIO link's own sockets
      ::sendto(board, sensor_buf.data(), sensor_n, MSG_DONTWAIT | MSG_NOSIGNAL, reinterpret_cast<const sockaddr*>(&board_to),
               sizeof board_to);
      ::sendto(vio, odometry_buf.data(), odometry_n, MSG_DONTWAIT | MSG_NOSIGNAL, reinterpret_cast<const sockaddr*>(&vio_to),
               sizeof vio_to);
    }
    if (client_known && k % 5 == 0)
      ::sendto(clients, odometry_buf.data(), odometry_n, MSG_DONTWAIT | MSG_NOSIGNAL,
               reinterpret_cast<const sockaddr*>(&client_to), sizeof client_to);
    if (k % 250 == 0) {
      std::printf("{\"type\":\"status\",\"steps\":%llu,\"sim_time_s\":%.3f}\n", static_cast<unsigned long long>(k),
                  static_cast<double>(k) * 0.004);
      std::fflush(stdout);
    }
  }
  std::printf("{\"type\":\"summary\",\"end\":\"duration\",\"wall_time_s\":%.3f}\n", seconds);
  ::close(board);
  ::close(vio);
  ::close(clients);
  return 0;
}

}  // namespace hitl::bench
