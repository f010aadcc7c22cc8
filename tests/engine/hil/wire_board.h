// A stand-in board on loopback for the faults' wire tests: a UDP socket that stamps each datagram
// as it arrives and reads HIL_SENSOR, HIL_GPS and ODOMETRY off it; and a session with faults run
// to it on its own thread while the test receives.
#pragma once

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <functional>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "base/common/clock.h"
#include "base/mavlink/frame_parser.h"
#include "base/mavlink/message_set.h"
#include "base/mavlink/messages.h"
#include "engine/hil/session.h"
#include "engine/model/x500_defaults.h"
#include "tests/engine/hil/stand_in_session_config.h"
#include "tests/support/process.h"
#include "tests/support/loopback.h"

namespace hitl::hil::test_wire {

struct Arrival {
  double wall_s = 0;  ///< monotonic, when the datagram arrived
  double sim_s = -1;  ///< its HIL_SENSOR's (or ODOMETRY's) time_usec (-1: none in it)
  std::optional<mavlink::msg::HilSensor> sensor;
  std::optional<mavlink::msg::HilGps> gps;
  std::optional<mavlink::msg::Odometry> odometry;
  double gps_sim_s() const { return gps ? static_cast<double>(gps->time_usec) * 1e-6 : -1; }
};

/// A UDP socket on 127.0.0.1 that stamps every datagram as it arrives.
class Board {
 public:
  Board() {
    fd_ = ::socket(AF_INET, SOCK_DGRAM, 0);
    sockaddr_in a = test::loopback_address(0);
    ::bind(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a);
    socklen_t n = sizeof a;
    ::getsockname(fd_, reinterpret_cast<sockaddr*>(&a), &n);
    port_ = ntohs(a.sin_port);
    timeval tv{0, 100000};
    ::setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
    int size = 4 << 20;  // the VIO board is read after the HIL one: hold a few seconds of it
    ::setsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &size, sizeof size);
  }
  ~Board() { ::close(fd_); }
  Board(const Board&) = delete;
  Board& operator=(const Board&) = delete;
  uint16_t port() const { return port_; }
  /// Every datagram until one of `until_sim_s` of simulated time arrived (or `timeout_s` of wall time).
  std::vector<Arrival> receive_until(double until_sim_s, double timeout_s) {
    namespace msg = mavlink::msg;
    std::vector<Arrival> out;
    mavlink::FrameParser parser(messages_);  // the parser keeps a reference to its set
    uint8_t buf[65536];
    const double end_s = monotonic_s() + timeout_s;
    while (monotonic_s() < end_s) {
      const ssize_t n = ::recv(fd_, buf, sizeof buf, 0);
      if (n <= 0) continue;
      Arrival a;
      a.wall_s = monotonic_s();
      parser.parse_datagram({buf, static_cast<std::size_t>(n)}, [&](const mavlink::Frame& f) {
        if (f.is<msg::HilSensor>()) {
          a.sensor = f.as<msg::HilSensor>();
          a.sim_s = static_cast<double>(a.sensor->time_usec) * 1e-6;
        }
        if (f.is<msg::HilGps>()) a.gps = f.as<msg::HilGps>();
        if (f.is<msg::Odometry>()) {
          a.odometry = f.as<msg::Odometry>();
          a.sim_s = static_cast<double>(a.odometry->time_usec) * 1e-6;
        }
      });
      out.push_back(a);
      if (a.sim_s >= until_sim_s) break;
    }
    return out;
  }

 private:
  mavlink::MessageSet messages_ = mavlink::MessageSet::compiled();
  int fd_ = -1;
  uint16_t port_ = 0;
};

/// A session to `board` with these faults, run on its own thread while the test receives.
class Running {
 public:
  using Tweak = std::function<void(SessionConfig&)>;
  Running(Board& board, const std::vector<std::string>& specs, bool noise = true, const std::string& record_path = "",
          const Tweak& tweak = {}) {
    SessionConfig c = test_session::stand_in_session_config(board.port(), specs);
    c.noise = noise;
    c.record_path = record_path;
    if (tweak) tweak(c);
    auto session = Session::create(c);
    EXPECT_TRUE(session) << session.error().message;
    session_ = std::move(session.value());
    thread_ = std::thread([this] { (void)session_->run(stop_, observer_); });
  }
  ~Running() {
    stop_.store(true);
    thread_.join();
  }
  SessionSnapshot snapshot() const { return session_->snapshot(); }
  Session& session() { return *session_; }

 private:
  std::unique_ptr<Session> session_;
  Session::Observer observer_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

/// `Running`'s tweak for ODOMETRY to `vio` (the VIO link on).
inline Running::Tweak vio_to(const Board& vio) {
  const uint16_t port = vio.port();
  return [port](SessionConfig& c) {
    c.vio = true;
    c.vio_ip = "127.0.0.1";
    c.vio_port = port;
  };
}

}  // namespace hitl::hil::test_wire
