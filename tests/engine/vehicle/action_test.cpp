// The action API against a scripted board on loopback: each action's request, its outcome word
// with the board's reason, pending refusals retried, what the board must show before success.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstring>
#include <vector>

#include "base/mavlink/enums.h"
#include "engine/vehicle/action.h"
#include "engine/vehicle/command_worker.h"
#include "tests/support/board_link.h"
#include "tests/support/scripted_board.h"

namespace hitl::vehicle {
namespace {

namespace msg = mavlink::msg;
using test::ScriptedBoard;
using test::connect_to;

void answer(test::MavlinkPeer& peer, uint16_t command, mavlink::MavResult result, const char* statustext = nullptr) {
  msg::CommandAck ack;
  ack.command = command;
  ack.result = static_cast<uint8_t>(result);
  peer.send(ack);
  if (!statustext) return;
  msg::Statustext t;
  std::strncpy(t.text.data(), statustext, t.text.size() - 1);
  peer.send(t);
}

TEST(ActionRequests, EachActionsCommandAndParameters) {
  EXPECT_EQ(arm_request().command, mavlink::cmd::kComponentArmDisarm);
  EXPECT_EQ(arm_request().params[0], 1.0f);
  EXPECT_EQ(arm_request().params[1], 0.0f);
  EXPECT_EQ(arm_request(true).params[1], mavlink::cmd::kArmDisarmForceMagic);
  EXPECT_EQ(disarm_request().params[0], 0.0f);
  EXPECT_EQ(disarm_request(true).params[1], mavlink::cmd::kArmDisarmForceMagic);
  EXPECT_EQ(takeoff_request().command, mavlink::cmd::kNavTakeoff);
  EXPECT_TRUE(std::isnan(takeoff_request().params[6]));  // the board's MIS_TAKEOFF_ALT
  EXPECT_FLOAT_EQ(takeoff_request(491.5).params[6], 491.5f);
  EXPECT_EQ(land_request().command, mavlink::cmd::kNavLand);
  const auto hold = set_mode_request(kPx4Hold);
  EXPECT_EQ(hold.command, mavlink::cmd::kDoSetMode);
  EXPECT_EQ(hold.params[0], 1.0f);  // custom mode
  EXPECT_EQ(hold.params[1], 4.0f);  // AUTO
  EXPECT_EQ(hold.params[2], 3.0f);  // LOITER
  EXPECT_EQ(kPx4Hold.custom_mode(), (4u << 16) | (3u << 24));
  EXPECT_EQ(set_mode_request(kPx4Position).params[1], 3.0f);
  EXPECT_EQ(set_mode_request(kPx4Stabilized).params[1], 7.0f);
}

TEST(Action, ArmSucceedsOnceTheHeartbeatShowsIt) {
  ScriptedBoard* self = nullptr;
  ScriptedBoard board([&](const mavlink::Frame& f, test::MavlinkPeer& peer) {
    if (!f.is<msg::CommandLong>()) return;
    const auto c = f.as<msg::CommandLong>();
    answer(peer, c.command, mavlink::MavResult::Accepted);
    self->base_mode = c.param1 == 1.0f ? mavlink::mode_flag::kSafetyArmed : 0;
  });
  self = &board;
  auto link = connect_to(board.port());
  Action action(*link);
  const auto armed = action.arm();
  EXPECT_EQ(armed.result, ActionResult::Success) << to_string(armed.result);
  ASSERT_TRUE(armed.command);
  EXPECT_EQ(armed.command->text(), "accepted");
  EXPECT_EQ(action.disarm().result, ActionResult::Success);
  EXPECT_EQ(board.base_mode.load(), 0);
}

TEST(Action, APendingRefusalIsRetriedSayingWhyThenArms) {
  std::atomic<int> tries{0};
  ScriptedBoard* self = nullptr;
  ScriptedBoard board([&](const mavlink::Frame& f, test::MavlinkPeer& peer) {
    if (!f.is<msg::CommandLong>()) return;
    if (tries++ < 2) return answer(peer, mavlink::cmd::kComponentArmDisarm, mavlink::MavResult::TemporarilyRejected,
                                   "Preflight Fail: ekf2 not aligned");
    answer(peer, mavlink::cmd::kComponentArmDisarm, mavlink::MavResult::Accepted);
    self->base_mode = mavlink::mode_flag::kSafetyArmed;
  });
  self = &board;
  auto link = connect_to(board.port());
  std::vector<std::string> said;
  std::vector<double> left;
  const auto outcome = Action(*link).arm(false, 10.0, [&](const CommandOutcome& refusal, double left_s) {
    said.push_back(refusal.text());
    left.push_back(left_s);
  });
  EXPECT_EQ(outcome.result, ActionResult::Success);
  ASSERT_EQ(said.size(), 2u);
  EXPECT_EQ(said[0], "temporarily rejected: Preflight Fail: ekf2 not aligned");
  EXPECT_GT(left[0], left[1]);
  EXPECT_LE(left[0], 10.0);
}

TEST(Action, ARefusalThatNeedsTheOperatorIsNotRetriedAndCarriesTheReason) {
  std::atomic<int> tries{0};
  ScriptedBoard board([&](const mavlink::Frame& f, test::MavlinkPeer& peer) {
    if (!f.is<msg::CommandLong>()) return;
    ++tries;
    answer(peer, mavlink::cmd::kComponentArmDisarm, mavlink::MavResult::Denied, "Arming denied: kill switch engaged");
  });
  auto link = connect_to(board.port());
  const auto outcome = Action(*link).arm(false, 10.0, [](const CommandOutcome&, double) { ADD_FAILURE() << "retried"; });
  EXPECT_EQ(outcome.result, ActionResult::Refused);
  ASSERT_TRUE(outcome.command);
  EXPECT_EQ(outcome.command->text(), "denied: Arming denied: kill switch engaged");
  EXPECT_EQ(tries.load(), 1);
  EXPECT_EQ(outcome_text(OperatorCommand::Arm, outcome), "arm denied: Arming denied: kill switch engaged");
}

TEST(Action, AcceptedButNeverShownAndNoAnswerAreTheirOwnWords) {
  ScriptedBoard board([&](const mavlink::Frame& f, test::MavlinkPeer& peer) {
    if (f.is<msg::CommandLong>() && f.as<msg::CommandLong>().command == mavlink::cmd::kComponentArmDisarm)
      answer(peer, mavlink::cmd::kComponentArmDisarm, mavlink::MavResult::Accepted);  // but stays disarmed
  });
  auto link = connect_to(board.port());
  Action action(*link);
  const auto unseen = action.arm();
  EXPECT_EQ(unseen.result, ActionResult::NotShown);
  EXPECT_EQ(outcome_text(OperatorCommand::Arm, unseen), "arm accepted, but HEARTBEAT did not show it within 3 s");
  const auto silent = action.land();  // the board ignores NAV_LAND
  EXPECT_EQ(silent.result, ActionResult::NoAnswer);
  EXPECT_FALSE(silent.command);
  EXPECT_NE(silent.error.find("no COMMAND_ACK"), std::string::npos) << silent.error;
  EXPECT_EQ(outcome_text(OperatorCommand::Land, silent), "land: " + silent.error);
}

TEST(Action, TakeoffToAnAltitudeAboveHomeThenWaitsForIt) {
  std::atomic<float> asked_amsl_m{0};
  std::atomic<bool> climbing{false};
  std::atomic<int> relative_mm{0};
  ScriptedBoard board(
      [&](const mavlink::Frame& f, test::MavlinkPeer& peer) {
        if (!f.is<msg::CommandLong>()) return;
        const auto c = f.as<msg::CommandLong>();
        asked_amsl_m = c.param7;
        answer(peer, c.command, mavlink::MavResult::Accepted);
        climbing = true;
      },
      [&](test::MavlinkPeer& peer) {
        if (climbing) relative_mm += 200;
        msg::GlobalPositionInt p;
        p.relative_alt = relative_mm.load();
        p.alt = 488000 + p.relative_alt;  // home 488 m AMSL
        peer.send(p);
      });
  auto link = connect_to(board.port());
  Action action(*link);
  const auto accepted = action.takeoff(3.5);
  ASSERT_EQ(accepted.result, ActionResult::Success) << accepted.error;
  EXPECT_FLOAT_EQ(asked_amsl_m.load(), 491.5f);
  std::vector<double> seen;
  const auto climbed = action.wait_altitude(3.5, 10.0, [&](double alt_m) { seen.push_back(alt_m); });
  EXPECT_EQ(climbed.result, ActionResult::Success);
  ASSERT_TRUE(climbed.altitude_m);
  EXPECT_GE(*climbed.altitude_m, 3.2);
  EXPECT_FALSE(seen.empty());
}

TEST(Action, TakeoffToAnAltitudeWithoutAPositionSaysSo) {
  ScriptedBoard board([](const mavlink::Frame& f, test::MavlinkPeer& peer) {
    if (f.is<msg::CommandLong>()) answer(peer, f.as<msg::CommandLong>().command, mavlink::MavResult::Accepted);
  });
  auto link = connect_to(board.port());
  const auto outcome = Action(*link).takeoff(2.0);
  EXPECT_EQ(outcome.result, ActionResult::NoPosition);
  EXPECT_EQ(outcome.error, "no GLOBAL_POSITION_INT from the board: is its position estimate valid?");
}

TEST(Action, HoldSucceedsOnceTheHeartbeatShowsTheMode) {
  ScriptedBoard* self = nullptr;
  ScriptedBoard board([&](const mavlink::Frame& f, test::MavlinkPeer& peer) {
    if (!f.is<msg::CommandLong>()) return;
    const auto c = f.as<msg::CommandLong>();
    answer(peer, c.command, mavlink::MavResult::Accepted);
    if (c.command == mavlink::cmd::kDoSetMode)
      self->custom_mode = static_cast<uint32_t>(c.param2) << 16 | static_cast<uint32_t>(c.param3) << 24;
  });
  self = &board;
  auto link = connect_to(board.port());
  EXPECT_EQ(Action(*link).hold().result, ActionResult::Success);
  EXPECT_EQ(board.custom_mode.load(), kPx4Hold.custom_mode());
}

TEST(Action, LandThenWaitsForTheDisarm) {
  ScriptedBoard* self = nullptr;
  std::atomic<int> relative_mm{2000};
  std::atomic<bool> landing{false};
  ScriptedBoard board(
      [&](const mavlink::Frame& f, test::MavlinkPeer& peer) {
        if (!f.is<msg::CommandLong>()) return;
        answer(peer, f.as<msg::CommandLong>().command, mavlink::MavResult::Accepted);
        landing = true;
      },
      [&](test::MavlinkPeer& peer) {
        if (landing && relative_mm > 0) relative_mm -= 250;
        if (relative_mm <= 0) self->base_mode = 0;  // touched down: PX4 disarms
        msg::GlobalPositionInt p;
        p.relative_alt = std::max(0, relative_mm.load());
        peer.send(p);
      });
  self = &board;
  board.base_mode = mavlink::mode_flag::kSafetyArmed;
  auto link = connect_to(board.port());
  Action action(*link);
  ASSERT_EQ(action.land().result, ActionResult::Success);
  const auto landed = action.wait_landed(10.0);
  EXPECT_EQ(landed.result, ActionResult::Success);
  ASSERT_TRUE(landed.altitude_m);
  EXPECT_LT(*landed.altitude_m, 0.5);
}

}  // namespace
}  // namespace hitl::vehicle
