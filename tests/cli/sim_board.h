// What the hitl sim end-to-end tests share: a loopback peer that plays the board's HIL instance
// (records every frame, answers each HIL_SENSOR with HIL_ACTUATOR_CONTROLS), the controls it
// answers with, the x500's hover command, and the summary line the session prints last.
#pragma once

#include <nlohmann/json.hpp>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "base/mavlink/enums.h"
#include "base/mavlink/frame_parser.h"
#include "base/mavlink/messages.h"
#include "engine/model/x500_defaults.h"
#include "tests/support/json_lines.h"
#include "tests/support/mavlink_peer.h"
#include "tests/support/process.h"

namespace hitl::sim_e2e {

using namespace std::chrono_literals;
namespace msg = mavlink::msg;
using test::Process;

inline const double kHover = model::hover_command(model::x500_vehicle_config(), model::default_world_config());

inline nlohmann::json last_json(const std::string& out) { return test::last_json_line(out); }

inline msg::HilActuatorControls actuators(double u, bool armed) {
  msg::HilActuatorControls a;
  a.controls = {};
  for (int i = 0; i < 4; ++i) a.controls[static_cast<std::size_t>(i)] = static_cast<float>(u);
  a.mode = mavlink::mode_flag::kCustomModeEnabled | mavlink::mode_flag::kHilEnabled | (armed ? mavlink::mode_flag::kSafetyArmed : 0);
  a.flags = 0x0F;
  return a;
}

/// Plays the board's HIL instance: records every frame, answers each HIL_SENSOR via `answer`.
class Board {
 public:
  Board() : port_(test::free_udp_port()), sim_port_(test::free_udp_port()), vio_port_(test::free_udp_port()), peer_(port_, sim_port_) {}
  ~Board() { stop(); }

  std::vector<std::string> sim_args(std::initializer_list<std::string> extra) const {
    std::vector<std::string> a{test::hitl_binary(), "--json", "sim", "-i", "127.0.0.1", "--hil-port", std::to_string(port_),
                               "--local-port", std::to_string(sim_port_), "--vio-port", std::to_string(vio_port_),
                               "--clients", "0"};
    a.insert(a.end(), extra);
    return a;
  }

  /// Starts answering: `answer(sensor, index)` returns the controls to send back, or nothing.
  void serve(std::function<std::optional<msg::HilActuatorControls>(const msg::HilSensor&, uint64_t)> answer) {
    running_ = true;
    thread_ = std::thread([this, answer]() {
      auto set = mavlink::MessageSet::compiled();
      mavlink::FrameParser parser(set);
      uint64_t n = 0;
      while (running_) {
        if (!peer_.endpoint().wait_readable(20)) continue;
        while (auto d = peer_.endpoint().receive()) {
          parser.parse_datagram(d->bytes, [&](const mavlink::Frame& f) {
            {
              std::lock_guard<std::mutex> lock(mutex_);
              frames_.push_back(f);
            }
            if (!f.is<msg::HilSensor>()) return;
            if (auto a = answer(f.as<msg::HilSensor>(), n++)) peer_.send(*a);
          });
        }
      }
    });
  }
  void stop() {
    running_ = false;
    if (thread_.joinable()) thread_.join();
  }
  std::vector<mavlink::Frame> frames() {
    std::lock_guard<std::mutex> lock(mutex_);
    return frames_;
  }
  test::MavlinkPeer& peer() { return peer_; }
  uint16_t port() const { return port_; }
  uint16_t sim_port() const { return sim_port_; }
  uint16_t vio_port() const { return vio_port_; }

 private:
  uint16_t port_, sim_port_, vio_port_;
  test::MavlinkPeer peer_;
  std::thread thread_;
  std::atomic<bool> running_{false};
  std::mutex mutex_;
  std::vector<mavlink::Frame> frames_;
};

}  // namespace hitl::sim_e2e
