// hitl target's operator surface through MAVLink: PX4's parameter protocol (bytewise INT32),
// commands and their ACKs, stream intervals, the shell, the partner lock, malformed input.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <csignal>
#include <cstring>
#include <map>

#include "base/mavlink/enums.h"
#include "base/mavlink/messages.h"
#include "engine/vehicle/params_file.h"
#include "tests/support/mavlink_peer.h"
#include "tests/support/process.h"
#include "tests/support/tmux.h"

namespace hitl {
namespace {

using namespace std::chrono_literals;
namespace msg = mavlink::msg;

std::string param_name(const std::array<char, 16>& id) { return std::string(id.data(), strnlen(id.data(), id.size())); }

class TargetE2E : public ::testing::Test {
 protected:
  void SetUp() override {
    hil_ = test::free_udp_port();
    gcs_ = test::free_udp_port();
    board_ = std::make_unique<test::Process>(std::vector<std::string>{
        test::hitl_binary(), "--json", "target", "--bind", "127.0.0.1", "--hil-port", std::to_string(hil_), "--gcs-port",
        std::to_string(gcs_), "--vio-port", "0"});
    ASSERT_TRUE(board_->wait_for_stderr("EMULATED", 10s)) << board_->err();
    gs_ = std::make_unique<test::MavlinkPeer>(0, gcs_, 255, 190);
    gs_->send(msg::Heartbeat{});  // become the GCS instance's partner
  }

  /// Frames of type M received within `wait`.
  template <class M>
  std::vector<M> collect(std::chrono::milliseconds wait) {
    std::vector<M> out;
    for (const auto& f : gs_->receive_for(wait))
      if (f.is<M>()) out.push_back(f.as<M>());
    return out;
  }

  msg::CommandLong command(uint16_t id, float p1 = 0, float p2 = 0) {
    msg::CommandLong c;
    c.target_system = 1;
    c.target_component = 1;
    c.command = id;
    c.param1 = p1;
    c.param2 = p2;
    return c;
  }

  uint16_t hil_ = 0, gcs_ = 0;
  std::unique_ptr<test::Process> board_;
  std::unique_ptr<test::MavlinkPeer> gs_;
};

TEST_F(TargetE2E, ParameterProtocolWithBytewiseInt32) {
  gs_->send(msg::ParamRequestList{});
  std::map<std::string, msg::ParamValue> all;
  for (const auto& p : collect<msg::ParamValue>(1500ms)) all[param_name(p.param_id)] = p;
  ASSERT_GT(all.size(), 100u);
  const auto& cal = all.at("CAL_ACC0_ID");
  EXPECT_EQ(cal.param_type, mavlink::kMavParamTypeInt32);
  EXPECT_EQ(vehicle::decode_param_float(cal.param_value, vehicle::ParamType::Int32), vehicle::ParamValue::int32(1310988));
  EXPECT_EQ(all.at("SYS_HITL").param_count, all.size());
  EXPECT_EQ(all.at("CA_ROTOR2_KM").param_value, -0.05f);

  msg::ParamSet set;
  std::memcpy(set.param_id.data(), "MPC_XY_P", 8);
  set.param_value = 1.1f;
  set.param_type = mavlink::kMavParamTypeReal32;
  gs_->send(set);
  auto echo = collect<msg::ParamValue>(500ms);
  ASSERT_FALSE(echo.empty());
  EXPECT_EQ(param_name(echo.back().param_id), "MPC_XY_P");
  EXPECT_FLOAT_EQ(echo.back().param_value, 1.1f);

  msg::ParamRequestRead read;
  std::memcpy(read.param_id.data(), "MPC_XY_P", 8);
  read.param_index = -1;
  gs_->send(read);
  auto back = collect<msg::ParamValue>(500ms);
  ASSERT_FALSE(back.empty());
  EXPECT_FLOAT_EQ(back.back().param_value, 1.1f);

  // Out of range: refused, the echo carries the unchanged value.
  set.param_value = 1000.0f;
  gs_->send(set);
  auto refused = collect<msg::ParamValue>(500ms);
  ASSERT_FALSE(refused.empty());
  EXPECT_FLOAT_EQ(refused.back().param_value, 1.1f);
}

TEST_F(TargetE2E, CommandsAreAcknowledgedWithTheRightResult) {
  gs_->send(command(mavlink::cmd::kSetMessageInterval, msg::Attitude::kId, 20000));  // ATTITUDE at 50 Hz
  auto acks = collect<msg::CommandAck>(300ms);
  ASSERT_FALSE(acks.empty());
  EXPECT_EQ(acks.back().result, static_cast<uint8_t>(mavlink::MavResult::Accepted));
  int attitudes = 0;
  for (const auto& f : gs_->receive_for(1000ms)) attitudes += f.is<msg::Attitude>();
  EXPECT_NEAR(attitudes, 50, 12);

  gs_->send(command(mavlink::cmd::kRequestMessage, msg::AutopilotVersion::kId));
  bool got_version = false;
  for (const auto& f : gs_->receive_for(500ms))
    if (f.is<msg::AutopilotVersion>())
      got_version = (f.as<msg::AutopilotVersion>().capabilities & mavlink::capability::kParamEncodeBytewise) != 0;
  EXPECT_TRUE(got_version);

  gs_->send(command(31000));  // nothing hitl target knows
  acks = collect<msg::CommandAck>(300ms);
  ASSERT_FALSE(acks.empty());
  EXPECT_EQ(acks.back().result, static_cast<uint8_t>(mavlink::MavResult::Unsupported));

  // Arming without sensor data: refused, and the reason comes as STATUSTEXT.
  gs_->send(command(mavlink::cmd::kComponentArmDisarm, 1));
  bool refused = false, reason = false;
  for (const auto& f : gs_->receive_for(500ms)) {
    if (f.is<msg::CommandAck>()) refused = f.as<msg::CommandAck>().result != 0;
    if (f.is<msg::Statustext>()) reason = std::string(f.as<msg::Statustext>().text.data()).find("Preflight Fail") != std::string::npos;
  }
  EXPECT_TRUE(refused);
  EXPECT_TRUE(reason);
}

TEST_F(TargetE2E, ShellAnswersDspHitlStatusInTheSpecsFormat) {
  msg::SerialControl sc;
  sc.device = 10;
  sc.flags = 2 | 4;  // RESPOND | EXCLUSIVE, as mavlink_shell.py sends
  const std::string line = "qshell dsp_hitl status\n";
  sc.count = static_cast<uint8_t>(line.size());
  std::memcpy(sc.data.data(), line.data(), line.size());
  gs_->send(sc);
  std::string out;
  for (const auto& f : gs_->receive_for(800ms))
    if (f.is<msg::SerialControl>()) {
      const auto r = f.as<msg::SerialControl>();
      out.append(reinterpret_cast<const char*>(r.data.data()), r.count);
    }
  EXPECT_NE(out.find("Running: yes\n=== IMU Section ===\n  HIL sensor_imu received: 0"), std::string::npos) << out;
  EXPECT_NE(out.find("=== MAG/BARO Section ==="), std::string::npos);
  EXPECT_NE(out.find("pxh> "), std::string::npos);
}

TEST_F(TargetE2E, HeartbeatSaysPx4QuadInHilAndAnotherSenderIsNotAnswered) {
  auto hbs = collect<msg::Heartbeat>(1500ms);
  ASSERT_FALSE(hbs.empty());
  EXPECT_EQ(hbs.back().autopilot, 12);  // MAV_AUTOPILOT_PX4 dialect (the banner and STATUSTEXT say emulator)
  EXPECT_EQ(hbs.back().type, 2);
  EXPECT_TRUE(hbs.back().base_mode & mavlink::mode_flag::kHilEnabled);
  test::MavlinkPeer second(0, gcs_, 255, 191);
  second.send(msg::Heartbeat{});
  EXPECT_TRUE(second.receive_for(1500ms).empty());  // PX4 keeps its first partner for good
}

TEST_F(TargetE2E, MalformedInputIsCountedNeverFatal) {
  test::MavlinkPeer junk(0, hil_);
  std::vector<uint8_t> garbage(500);
  for (std::size_t i = 0; i < garbage.size(); ++i) garbage[i] = static_cast<uint8_t>(i * 97 + 0xFD);
  for (int i = 0; i < 20; ++i) junk.send_bytes(garbage);
  msg::HilSensor nan_sensor;
  nan_sensor.xacc = std::nanf("");
  nan_sensor.fields_updated = 0x1FFF;
  junk.send(nan_sensor);
  std::this_thread::sleep_for(1500ms);
  ASSERT_TRUE(board_->running()) << board_->err();
  board_->signal(SIGINT);
  EXPECT_EQ(board_->wait(10s), 0);
  const auto lines = board_->out_lines();
  ASSERT_FALSE(lines.empty());
  const auto j = nlohmann::json::parse(lines.back());
  EXPECT_EQ(j["type"], "summary");
  EXPECT_GT(j["malformed"].get<int>(), 10);
}

// `hitl target &` then another hitl command in one terminal (the README's way): the background
// board keeps its once-a-second status lines to itself, so the next command's output is readable;
// in the foreground it shows them.
TEST(TargetInATerminal, ABackgroundJobKeepsItsStatusLinesToItself) {
  const std::string tmux = test::tmux_path();
  if (tmux.empty()) GTEST_SKIP() << "tmux is not installed (scripts/install-deps.sh --test installs it)";
  auto board = [](const std::string& how) {
    return test::shell_quoted(test::hitl_binary()) + " target --bind 127.0.0.1 --hil-port " + std::to_string(test::free_udp_port()) +
           " --gcs-port " + std::to_string(test::free_udp_port()) + " --vio-port 0 --lockstep" + how;
  };
  test::Tmux t(tmux, "target-bg");
  t.start("bash --norc --noprofile -i");
  std::string screen;
  t.keys({board(" & sleep 3.5; kill %1; echo back\"\"-done"), "Enter"});
  ASSERT_TRUE(t.until([](const std::string& s) { return s.find("back-done\n") != std::string::npos; }, 20s, &screen)) << screen;
  EXPECT_NE(screen.find("EMULATED"), std::string::npos) << screen;
  EXPECT_EQ(screen.find("HIL_SENSOR 0"), std::string::npos) << screen;  // no status line
  t.keys({"clear; timeout -s INT 3.5 " + board("") + "; echo front\"\"-done", "Enter"});
  ASSERT_TRUE(t.until([](const std::string& s) { return s.find("front-done\n") != std::string::npos; }, 20s, &screen)) << screen;
  EXPECT_NE(screen.find("HIL_SENSOR 0"), std::string::npos) << screen;
}

}  // namespace
}  // namespace hitl
