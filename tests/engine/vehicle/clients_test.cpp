// The protocol clients against scripted peers on loopback: lost requests, duplicates, IN_PROGRESS.
#include <gtest/gtest.h>

#include <atomic>
#include <cstring>
#include <thread>

#include "base/contract/dsp_hitl_status.h"
#include "base/mavlink/enums.h"
#include "base/mavlink/frame_parser.h"
#include "base/mavlink/text_field.h"
#include "engine/net/tcp_server.h"
#include "engine/vehicle/command_client.h"
#include "engine/vehicle/param_client.h"
#include "engine/vehicle/shell_client.h"
#include "engine/vehicle/shell_poller.h"
#include "tests/support/mavlink_peer.h"
#include "tests/support/board_link.h"
#include "tests/support/scripted_board.h"

namespace hitl::vehicle {
namespace {

namespace msg = mavlink::msg;
using namespace std::chrono_literals;

using test::ScriptedBoard;
using test::connect_to;

TEST(CommandClient, RetransmitsAfterALossAndWaitsThroughInProgress) {
  std::atomic<int> seen{0};
  ScriptedBoard board([&](const mavlink::Frame& f, test::MavlinkPeer& peer) {
    if (!f.is<msg::CommandLong>()) return;
    const auto c = f.as<msg::CommandLong>();
    if (seen++ == 0) return;  // the first one is lost
    EXPECT_EQ(c.confirmation, 1);
    msg::CommandAck ack;
    ack.command = c.command;
    ack.result = static_cast<uint8_t>(mavlink::MavResult::InProgress);
    peer.send(ack);
    std::this_thread::sleep_for(1500ms);  // longer than one try: the client must not resend
    ack.result = 0;
    peer.send(ack);
    peer.send(ack);  // a duplicate ACK is harmless
  });
  auto link = connect_to(board.port());
  CommandClient client(*link);
  auto r = client.send(mavlink::cmd::kNavTakeoff, {0, 0, 0, 0, 0, 0, 10});
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_TRUE(r->accepted());
  EXPECT_EQ(seen.load(), 2);
}

TEST(CommandClient, DenialCarriesTheStatustextAndSilenceIsAnError) {
  ScriptedBoard board([&](const mavlink::Frame& f, test::MavlinkPeer& peer) {
    if (!f.is<msg::CommandLong>()) return;
    msg::CommandAck ack;
    ack.command = f.as<msg::CommandLong>().command;
    ack.result = static_cast<uint8_t>(mavlink::MavResult::TemporarilyRejected);
    peer.send(ack);
    msg::Statustext t;
    std::strcpy(t.text.data(), "Preflight Fail: ekf2 not aligned");
    peer.send(t);  // after the ACK, as PX4 often does
  });
  auto link = connect_to(board.port());
  CommandClient client(*link);
  auto r = client.send(mavlink::cmd::kComponentArmDisarm, {1, 0, 0, 0, 0, 0, 0});
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->text(), "temporarily rejected: Preflight Fail: ekf2 not aligned");

  ScriptedBoard mute([](const mavlink::Frame&, test::MavlinkPeer&) {});
  auto quiet_link = connect_to(mute.port());
  CommandClient quiet(*quiet_link);
  EXPECT_FALSE(quiet.send(400, {1, 0, 0, 0, 0, 0, 0}, 0.2, 2).ok());
}

TEST(CommandClient, APx4RefusalInChunksIsReadWhole) {
  // PX4 v1.16 sends a text over 50 characters as chunks of one id (issue 38: "hitl arm" printed
  // "Arming temporarily rejected: t" and a tab, the last chunk only).
  const std::string refusal = "Arming denied: Resolve system health failures first\tsensors: accel 0 uncalibrated";
  ScriptedBoard board([&](const mavlink::Frame& f, test::MavlinkPeer& peer) {
    if (!f.is<msg::CommandLong>()) return;
    msg::CommandAck ack;
    ack.command = f.as<msg::CommandLong>().command;
    ack.result = static_cast<uint8_t>(mavlink::MavResult::TemporarilyRejected);
    peer.send(ack);
    for (uint8_t seq = 0; seq * 50U < refusal.size(); ++seq) {
      msg::Statustext t;
      t.severity = 2;
      t.id = 17;
      t.chunk_seq = seq;
      mavlink::set_text(t.text, std::string_view(refusal).substr(seq * 50U, 50));
      peer.send(t);
    }
  });
  auto link = connect_to(board.port());
  CommandClient client(*link);
  auto r = client.send(mavlink::cmd::kComponentArmDisarm, {1, 0, 0, 0, 0, 0, 0});
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->text(), "temporarily rejected: Arming denied: Resolve system health failures first sensors: accel 0 uncalibrated");
  EXPECT_EQ(r->statustexts.size(), 1U);
}

TEST(ParamClient, DownloadReRequestsMissingIndicesAndIgnoresDuplicates) {
  ScriptedBoard board([&](const mavlink::Frame& f, test::MavlinkPeer& peer) {
    auto value = [&](uint16_t i) {
      msg::ParamValue v;
      const std::string name = "P" + std::to_string(i);
      std::memcpy(v.param_id.data(), name.data(), name.size());
      v.param_value = static_cast<float>(i);
      v.param_type = 9;
      v.param_count = 10;
      v.param_index = i;
      peer.send(v);
    };
    if (f.is<msg::ParamRequestList>()) {
      for (uint16_t i = 0; i < 10; ++i)
        if (i != 3 && i != 7) value(i);  // two lost on the way
      value(2);                          // and a duplicate
    } else if (f.is<msg::ParamRequestRead>()) {
      value(static_cast<uint16_t>(f.as<msg::ParamRequestRead>().param_index));
    }
  });
  auto link = connect_to(board.port());
  ParamClient client(*link);
  auto all = client.download();
  ASSERT_TRUE(all.ok()) << all.error().message;
  ASSERT_EQ(all->size(), 10u);
  EXPECT_EQ((*all)[7].name, "P7");
  EXPECT_EQ((*all)[7].value, ParamValue::real32(7));
}

/// `reply` as a board's shell sends it: SERIAL_CONTROL replies of up to 70 bytes each.
void send_shell_reply(test::MavlinkPeer& peer, const std::string& reply) {
  for (std::size_t pos = 0; pos < reply.size(); pos += 70) {
    msg::SerialControl out;
    out.device = 10;
    out.flags = 1;
    const auto n = std::min<std::size_t>(70, reply.size() - pos);
    out.count = static_cast<uint8_t>(n);
    std::memcpy(out.data.data(), reply.data() + pos, n);
    peer.send(out);
  }
}

TEST(ShellClient, CollectsOutputUntilThePromptAndDropsTheEcho) {
  ScriptedBoard board([&](const mavlink::Frame& f, test::MavlinkPeer& peer) {
    if (!f.is<msg::SerialControl>()) return;
    const auto in = f.as<msg::SerialControl>();
    const std::string text(reinterpret_cast<const char*>(in.data.data()), in.count);
    std::string reply = text == "\n" ? "\npxh> " : text + "line one\nline two that is long enough to need a second chunk of output\npxh> ";
    send_shell_reply(peer, reply);
  });
  auto link = connect_to(board.port());
  ShellClient shell(*link);
  auto out = shell.run("ver all");
  ASSERT_TRUE(out.ok()) << out.error().message;
  EXPECT_EQ(*out, "line one\nline two that is long enough to need a second chunk of output\n");
}

// Issue 18: a poll the shell answers with nothing (the prompt alone) is a shell that did not
// answer, not a board without dsp_hitl; the poller keeps asking and shows the counters once the
// board answers.
TEST(ShellPoller, AnEmptyReplyIsAShellThatDidNotAnswerAndItKeepsAsking) {
  std::atomic<int> polls{0};
  ScriptedBoard board([&](const mavlink::Frame& f, test::MavlinkPeer& peer) {
    if (!f.is<msg::SerialControl>()) return;
    const auto in = f.as<msg::SerialControl>();
    const std::string text(reinterpret_cast<const char*>(in.data.data()), in.count);
    std::string reply = "\npxh> ";
    if (text != "\n" && polls.fetch_add(1) >= 2)  // the first two polls: an empty reply
      reply = text + target::dsp_hitl_status_text(true, {}, {}) + "pxh> ";
    send_shell_reply(peer, reply);
  });
  LinkOptions o;
  o.connect = "udp:127.0.0.1:" + std::to_string(board.port());
  o.local_port = 0;
  o.timeout_s = 3;
  ShellPoller poller(o, telemetry::DspHitlExpectedRates{}, 0.1, nullptr);
  std::string reason;
  for (int i = 0; i < 100 && reason.empty(); ++i) {
    const auto v = poller.dsp_hitl();
    if (v.state == telemetry::DspHitlView::State::Unavailable) reason = v.reason;
    std::this_thread::sleep_for(20ms);
  }
  EXPECT_NE(reason.find("shell did not answer"), std::string::npos) << reason;
  EXPECT_NE(reason.find("retrying"), std::string::npos) << reason;
  EXPECT_EQ(reason.find("no dsp_hitl"), std::string::npos) << reason;
  bool available = false;
  for (int i = 0; i < 150 && !available; ++i) {
    available = poller.dsp_hitl().state == telemetry::DspHitlView::State::Available;
    std::this_thread::sleep_for(20ms);
  }
  EXPECT_TRUE(available) << poller.dsp_hitl().reason;
}

TEST(VehicleLink, TcpServerBoardAnswersCommands) {
  auto server = net::TcpServer::listen("127.0.0.1", 0, "test board");
  ASSERT_TRUE(server.ok()) << server.error().message;
  const uint16_t port = server->local_address().port();
  std::atomic<bool> running{true};
  std::thread board([&] {
    auto set = mavlink::MessageSet::compiled();
    mavlink::FrameParser parser(set);
    mavlink::FrameEncoder enc(1, 1);
    mavlink::FrameBuffer buf;
    while (running && !server->accept_client(20)) {
    }
    auto next_hb = std::chrono::steady_clock::now();
    while (running && server->connected()) {
      if (std::chrono::steady_clock::now() >= next_hb) {
        msg::Heartbeat hb;
        hb.type = 2;
        hb.autopilot = 12;
        (void)server->send({buf.data(), enc.encode(hb, buf)});
        next_hb += 100ms;
      }
      if (!server->wait_readable(10)) continue;
      auto bytes = server->receive();
      if (!bytes) break;
      parser.feed(*bytes, [&](const mavlink::Frame& f) {
        if (!f.is<msg::CommandLong>()) return;
        msg::CommandAck ack;
        ack.command = f.as<msg::CommandLong>().command;
        (void)server->send({buf.data(), enc.encode(ack, buf)});
      });
    }
  });
  LinkOptions o;
  o.connect = "tcp:127.0.0.1:" + std::to_string(port);
  auto link = VehicleLink::connect(o);
  ASSERT_TRUE(link.ok()) << link.error().message;
  EXPECT_EQ((*link)->target_sysid(), 1);
  EXPECT_NE((*link)->description().find("over TCP"), std::string::npos);
  CommandClient client(**link);
  auto r = client.send(mavlink::cmd::kNavLand, {0, 0, 0, 0, 0, 0, 0});
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_TRUE(r->accepted());
  running = false;
  board.join();
  o.connect = "tcp:127.0.0.1:" + std::to_string(port);  // the socket still listens, but no board answers any more
  o.timeout_s = 1;
  EXPECT_FALSE(VehicleLink::connect(o).ok());
}

}  // namespace
}  // namespace hitl::vehicle
