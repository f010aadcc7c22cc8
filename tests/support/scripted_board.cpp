#include "tests/support/scripted_board.h"

#include "base/mavlink/frame_parser.h"
#include "base/mavlink/messages.h"

namespace hitl::test {

using namespace std::chrono_literals;

ScriptedBoard::ScriptedBoard(Script script, Tick tick) : peer_(0, 0, 1, 1), script_(std::move(script)), tick_(std::move(tick)) {
  thread_ = std::thread([this] {
    auto set = mavlink::MessageSet::compiled();
    mavlink::FrameParser parser(set);
    auto next_hb = std::chrono::steady_clock::now();
    auto next_tick = next_hb;
    while (running_) {
      const auto now = std::chrono::steady_clock::now();
      if (now >= next_hb && peer_.endpoint().partner()) {
        mavlink::msg::Heartbeat hb;
        hb.type = 2;
        hb.autopilot = 12;
        hb.base_mode = base_mode.load();
        hb.custom_mode = custom_mode.load();
        peer_.send(hb);
        next_hb += 100ms;
      }
      if (tick_ && now >= next_tick && peer_.endpoint().partner()) {
        tick_(peer_);
        next_tick += 20ms;
      }
      if (!peer_.endpoint().wait_readable(5)) continue;
      while (auto d = peer_.endpoint().receive())
        parser.parse_datagram(d->bytes, [&](const mavlink::Frame& f) { script_(f, peer_); });
    }
  });
}

ScriptedBoard::~ScriptedBoard() {
  running_ = false;
  thread_.join();
}

}  // namespace hitl::test
