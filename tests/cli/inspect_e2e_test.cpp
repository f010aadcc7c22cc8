// hitl inspect end to end: the real binary, real MAVLink over loopback UDP, its JSON checked.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <csignal>
#include <fstream>

#include "base/mavlink/frame_encoder.h"
#include "base/mavlink/messages.h"
#include "engine/mavlink/tlog.h"
#include "tests/support/json_lines.h"
#include "tests/support/mavlink_peer.h"
#include "tests/support/process.h"

namespace hitl {
namespace {

using namespace std::chrono_literals;
using test::Process;

std::vector<std::string> args(std::initializer_list<std::string> a) {
  std::vector<std::string> v{test::hitl_binary()};
  v.insert(v.end(), a);
  return v;
}

nlohmann::json last_json(Process& p) {
  const auto out = p.out();
  EXPECT_FALSE(out.empty()) << "no output; stderr: " << p.err();
  return test::last_json_line(out);
}

mavlink::msg::Odometry odometry(uint64_t t) {
  mavlink::msg::Odometry o;
  o.time_usec = t;
  o.frame_id = 1;
  o.child_frame_id = 12;
  o.q = {1, 0, 0, 0};
  o.z = -2.5f;
  return o;
}

TEST(InspectE2E, Phase1CheckPassesAtTheExpectedRate) {
  const uint16_t port = test::free_udp_port();
  Process p(args({"inspect", "--port", std::to_string(port), "--duration", "3", "--json", "--expect", "ODOMETRY=250"}));
  ASSERT_TRUE(p.wait_for_stderr("listening", 10s)) << p.err();
  test::MavlinkPeer sender(0, port);
  uint64_t t = 0;
  sender.start_paced(250, 6s, [&](test::MavlinkPeer& peer) { peer.send(odometry(t += 4000)); });
  const int code = p.wait(30s);
  sender.stop();
  const auto j = last_json(p);
  EXPECT_EQ(code, 0) << p.out() << p.err();
  EXPECT_EQ(j["type"], "summary");
  EXPECT_EQ(j["end"], "duration");
  EXPECT_NEAR(j["duration_s"].get<double>(), 3.0, 0.5);
  const auto& odo = j["messages"]["ODOMETRY"];
  EXPECT_EQ(odo["id"], 331);
  EXPECT_NEAR(odo["rate_hz"].get<double>(), 250.0, 12.5);
  EXPECT_GT(odo["count"].get<int>(), 600);
  EXPECT_NEAR(odo["gap_us"]["mean"].get<double>(), 4000.0, 400.0);
  EXPECT_GT(odo["gap_us"]["max"].get<double>(), 0.0);
  EXPECT_EQ(odo["bytes"].get<int>() % odo["count"].get<int>(), 0);
  EXPECT_EQ(j["crc_errors"], 0);
  EXPECT_EQ(j["parse_errors"], 0);
  EXPECT_EQ(j["unknown"], 0);
  ASSERT_EQ(j["sources"].size(), 1u);
  EXPECT_EQ(j["sources"][0]["lost"], 0);
  EXPECT_TRUE(j["expect"][0]["ok"].get<bool>());
  EXPECT_TRUE(j["ok"].get<bool>());
  // Status objects each second, then exactly one summary, last.
  EXPECT_GE(p.out_lines().size(), 3u);
  EXPECT_EQ(nlohmann::json::parse(p.out_lines().front())["type"], "status");
}

TEST(InspectE2E, ExpectationNotMetExitsOneAndSaysWhich) {
  const uint16_t port = test::free_udp_port();
  Process p(args({"inspect", "--port", std::to_string(port), "--duration", "2", "--expect", "ODOMETRY=250,HIL_SENSOR=250"}));
  ASSERT_TRUE(p.wait_for_stderr("listening", 10s));
  test::MavlinkPeer sender(0, port);
  uint64_t t = 0;
  sender.start_paced(100, 4s, [&](test::MavlinkPeer& peer) { peer.send(odometry(t += 10000)); });
  EXPECT_EQ(p.wait(30s), 1);
  EXPECT_NE(p.out().find("FAIL ODOMETRY"), std::string::npos) << p.out();
  EXPECT_NE(p.out().find("too slow"), std::string::npos);
  EXPECT_NE(p.out().find("FAIL HIL_SENSOR: none received"), std::string::npos);
}

TEST(InspectE2E, GarbageCrcBrokenAndTruncatedDatagramsAreCountedNeverFatal) {
  const uint16_t port = test::free_udp_port();
  Process p(args({"inspect", "--port", std::to_string(port), "--duration", "2", "--json"}));
  ASSERT_TRUE(p.wait_for_stderr("listening", 10s));
  test::MavlinkPeer peer(0, port);
  mavlink::FrameEncoder enc(1, 1);
  mavlink::FrameBuffer buf;
  const std::size_t n = enc.encode(odometry(1), buf);
  std::vector<uint8_t> good(buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(n));
  auto bad_crc = good;
  bad_crc[20] ^= 0x55;
  auto truncated = good;
  truncated.resize(n / 2);
  std::vector<uint8_t> garbage(300);
  for (std::size_t i = 0; i < garbage.size(); ++i) garbage[i] = static_cast<uint8_t>(i * 37 + 1);
  std::vector<uint8_t> empty;
  for (int i = 0; i < 5; ++i) {
    peer.send_bytes(garbage);
    peer.send_bytes(bad_crc);
    peer.send_bytes(truncated);
    peer.send_bytes(empty);
    peer.send_bytes(good);
  }
  EXPECT_EQ(p.wait(30s), 0);
  const auto j = last_json(p);
  EXPECT_EQ(j["messages"]["ODOMETRY"]["count"], 5);
  EXPECT_GE(j["crc_errors"].get<int>(), 5);
  EXPECT_GE(j["truncated"].get<int>(), 5);
  EXPECT_GE(j["parse_errors"].get<int>(), 5);
}

TEST(InspectE2E, PortInUseIsOneLineAndExitTwo) {
  test::MavlinkPeer holder(0, 0);
  const uint16_t port = holder.endpoint().local_address().port();
  auto r = test::run_hitl({"inspect", "--bind", "127.0.0.1", "--port", std::to_string(port), "--duration", "1"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("already in use"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

TEST(InspectE2E, BadUsageExitsTwo) {
  EXPECT_EQ(test::run_hitl({"inspect"}).exit_code, 2);
  EXPECT_EQ(test::run_hitl({"inspect", "--port", "1", "--tlog", "/etc/hostname"}).exit_code, 2);
  auto unknown = test::run_hitl({"inspect", "--port", "14999", "--show", "NOT_A_MESSAGE", "--duration", "1"});
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_NE(unknown.err.find("NOT_A_MESSAGE"), std::string::npos);
  EXPECT_EQ(test::run_hitl({"inspect", "--port", "14999", "--expect", "ODOMETRY=abc"}).exit_code, 2);
  EXPECT_EQ(test::run_hitl({"inspect", "--tlog", "/nonexistent.tlog"}).exit_code, 2);
  EXPECT_EQ(test::run_hitl({"nosuchcommand"}).exit_code, 2);
}

TEST(InspectE2E, RecordThenReadTheTlogBack) {
  const auto dir = test::temp_dir();
  const uint16_t port = test::free_udp_port();
  Process p(args({"inspect", "--port", std::to_string(port), "--count", "50", "--record", dir + "/rec.tlog", "--json"}));
  ASSERT_TRUE(p.wait_for_stderr("listening", 10s));
  test::MavlinkPeer peer(0, port);
  uint64_t t = 0;
  peer.start_paced(200, 5s, [&](test::MavlinkPeer& pp) { pp.send(odometry(t += 5000)); });
  EXPECT_EQ(p.wait(30s), 0);
  peer.stop();
  EXPECT_EQ(last_json(p)["end"], "count");
  EXPECT_EQ(last_json(p)["messages"]["ODOMETRY"]["count"], 50);

  auto r = test::run_hitl({"--json", "inspect", "--tlog", dir + "/rec.tlog"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const auto j = test::last_json_line(r.out);
  EXPECT_EQ(j["end"], "end_of_log");
  EXPECT_EQ(j["messages"]["ODOMETRY"]["count"], 50);
  EXPECT_NEAR(j["messages"]["ODOMETRY"]["rate_hz"].get<double>(), 200.0, 20.0);
}

TEST(InspectE2E, TlogRatesComeFromTheLogsTimestamps) {
  const auto path = test::temp_dir() + "/synthetic.tlog";
  {
    auto w = mavlink::TlogWriter::open(path);
    mavlink::FrameEncoder enc(1, 1);
    mavlink::FrameBuffer buf;
    for (int i = 0; i < 1001; ++i) {  // exactly 250 Hz for 4 s of log time
      const std::size_t n = enc.encode(odometry(static_cast<uint64_t>(i)), buf);
      w->write(1'700'000'000'000'000ULL + static_cast<uint64_t>(i) * 4000, {buf.data(), n});
    }
  }
  auto r = test::run_hitl({"inspect", "--tlog", path, "--json", "--expect", "ODOMETRY=250", "--tolerance", "0.1"});
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  const auto j = test::last_json_line(r.out);
  EXPECT_NEAR(j["duration_s"].get<double>(), 4.0, 1e-6);
  EXPECT_NEAR(j["messages"]["ODOMETRY"]["rate_hz"].get<double>(), 250.0, 1e-6);
  EXPECT_NEAR(j["messages"]["ODOMETRY"]["gap_us"]["std"].get<double>(), 0.0, 1e-6);
  // --duration on a log counts log time.
  auto part = test::run_hitl({"inspect", "--tlog", path, "--json", "--duration", "1"});
  EXPECT_EQ(test::last_json_line(part.out)["messages"]["ODOMETRY"]["count"], 251);
}

TEST(InspectE2E, ShowFollowPrintsDecodedFieldsAndNamesHilSensorBits) {
  const uint16_t port = test::free_udp_port();
  Process p(args({"inspect", "--port", std::to_string(port), "--show", "HIL_SENSOR", "--follow", "--count", "2"}));
  ASSERT_TRUE(p.wait_for_stderr("listening", 10s));
  test::MavlinkPeer peer(0, port);
  mavlink::msg::HilSensor s;
  s.zacc = -9.81f;
  s.fields_updated = 0x3F;  // accel + gyro
  peer.send(s);
  s.fields_updated = 0x1FFF;
  peer.send(s);
  EXPECT_EQ(p.wait(20s), 0);
  const auto out = p.out();
  EXPECT_NE(out.find("HIL_SENSOR time_usec=0 us xacc=0 m/s/s"), std::string::npos) << out;
  EXPECT_NE(out.find("zacc=-9.81 m/s/s"), std::string::npos) << out;
  EXPECT_NE(out.find("fields_updated=63 (accel gyro)"), std::string::npos) << out;
  EXPECT_NE(out.find("fields_updated=8191 (accel gyro mag baro diff_pressure)"), std::string::npos) << out;
}

TEST(InspectE2E, ShowFollowNamesEnumsBitmasksAndThePx4ModeOfTheBoard) {
  // Issue 18 point 9: against `hitl target`, one line per message with names, not numbers.
  const std::string hil = std::to_string(test::free_udp_port()), gcs = std::to_string(test::free_udp_port());
  Process board(args({"target", "--bind", "127.0.0.1", "--hil-port", hil, "--gcs-port", gcs, "--vio-port", "0"}));
  ASSERT_TRUE(board.wait_for_stderr("EMULATED", 10s)) << board.err();
  Process p(args({"inspect", "--connect", "127.0.0.1:" + gcs, "--local-port", std::to_string(test::free_udp_port()),
                  "--show", "HEARTBEAT,STATUSTEXT", "--follow", "--count", "3", "--duration", "15"}));
  EXPECT_EQ(p.wait(30s), 0) << p.err();
  board.signal(SIGINT);
  board.wait(10s);
  const auto out = p.out();
  EXPECT_NE(out.find("HEARTBEAT custom_mode=Hold type=QUADROTOR autopilot=PX4 base_mode=CUSTOM_MODE_ENABLED|"), std::string::npos)
      << out;
  EXPECT_NE(out.find("system_status=STANDBY"), std::string::npos) << out;
  EXPECT_NE(out.find("STATUSTEXT severity=NOTICE text=\"hitl target: an emulated VOXL2 board"), std::string::npos) << out;
  int heartbeat_lines = 0;
  for (const auto& line : p.out_lines()) heartbeat_lines += line.rfind("HEARTBEAT ", 0) == 0 ? 1 : 0;
  EXPECT_GE(heartbeat_lines, 2) << out;  // each message on a line of its own
}

TEST(InspectE2E, CtrlCPrintsTheFinalSummary) {
  const uint16_t port = test::free_udp_port();
  Process p(args({"inspect", "--port", std::to_string(port), "--json"}));
  ASSERT_TRUE(p.wait_for_stderr("listening", 10s));
  test::MavlinkPeer peer(0, port);
  peer.send(odometry(1));
  std::this_thread::sleep_for(300ms);
  p.signal(SIGINT);
  EXPECT_EQ(p.wait(10s), 0);
  const auto j = last_json(p);
  EXPECT_EQ(j["type"], "summary");
  EXPECT_EQ(j["end"], "stopped");
  EXPECT_EQ(j["messages"]["ODOMETRY"]["count"], 1);
}

TEST(InspectE2E, ConnectSendsHeartbeatsFromTheFixedPortAndCountsReplies) {
  test::MavlinkPeer board(0, 0, 1, 1);  // plays a PX4 GCS instance
  const uint16_t board_port = board.endpoint().local_address().port();
  const uint16_t local_port = test::free_udp_port();
  Process p(args({"inspect", "--connect", "127.0.0.1:" + std::to_string(board_port), "--local-port",
                  std::to_string(local_port), "--duration", "2.5", "--json"}));
  auto heard = board.receive_for(1500ms);
  ASSERT_FALSE(heard.empty()) << p.err();
  EXPECT_EQ(heard[0].msgid, mavlink::msg::Heartbeat::kId);
  EXPECT_EQ(heard[0].as<mavlink::msg::Heartbeat>().type, 6);  // MAV_TYPE_GCS
  EXPECT_EQ(heard[0].sysid, 255);
  ASSERT_TRUE(board.endpoint().partner());
  EXPECT_EQ(board.endpoint().partner()->port(), local_port);
  for (int i = 0; i < 10; ++i) board.send(mavlink::msg::Attitude{});
  EXPECT_EQ(p.wait(20s), 0) << p.err();
  EXPECT_EQ(last_json(p)["messages"]["ATTITUDE"]["count"], 10);
}

TEST(InspectE2E, DialectFileNamesMessagesHitlDoesNotCompileIn) {
  const auto dir = test::temp_dir();
  std::ofstream(dir + "/extra.xml") << R"(<?xml version="1.0"?>
<mavlink><messages><message id="42000" name="HITL_TEST_THING">
  <field type="float" name="speed" units="m/s">s</field><field type="uint8_t" name="mode">m</field>
</message></messages></mavlink>)";
  const uint16_t port = test::free_udp_port();
  Process p(args({"--dialect", dir + "/extra.xml", "--json", "inspect", "--port", std::to_string(port), "--show",
                  "HITL_TEST_THING", "--follow", "--count", "1"}));
  ASSERT_TRUE(p.wait_for_stderr("listening", 10s)) << p.err();
  test::MavlinkPeer peer(0, port);
  // speed = 2.5f (0x40200000 LE), mode = 3; CRC_EXTRA computed by the same rule as mavgen.
  mavlink::MessageSet set;
  set.add([] {
    mavlink::MessageDesc d;
    d.id = 42000;
    d.name = "HITL_TEST_THING";
    d.fields = {{"speed", mavlink::FieldType::Float, 0, 0, false, "m/s", ""}, {"mode", mavlink::FieldType::Uint8, 0, 0, false, "", ""}};
    mavlink::assign_wire_order(d);
    d.crc_extra = mavlink::compute_crc_extra(d);
    return d;
  }());
  const uint8_t payload[5] = {0x00, 0x00, 0x20, 0x40, 3};
  mavlink::FrameBuffer buf;
  const std::size_t n = peer.encoder().encode_raw(42000, set.find(42000u)->crc_extra, payload, 5, buf);
  peer.send_bytes({buf.data(), n});
  EXPECT_EQ(p.wait(20s), 0) << p.err();
  const auto frame = nlohmann::json::parse(p.out_lines().at(0));
  EXPECT_EQ(frame["name"], "HITL_TEST_THING");
  EXPECT_EQ(frame["fields"]["speed"], 2.5);
  EXPECT_EQ(frame["fields"]["mode"], 3);
}

}  // namespace
}  // namespace hitl

namespace hitl {
namespace {

TEST(CliE2E, HelpAndVersion) {
  auto help = test::run_hitl({"--help"});
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.out.find("inspect"), std::string::npos);
  EXPECT_NE(help.out.find("--json"), std::string::npos);
  EXPECT_NE(help.out.find("--config"), std::string::npos);
  auto version = test::run_hitl({"--version"});
  EXPECT_EQ(version.exit_code, 0);
  EXPECT_EQ(version.out.rfind("hitl ", 0), 0u) << version.out;
  EXPECT_EQ(test::run_hitl({"inspect", "--help"}).exit_code, 0);
}

TEST(CliE2E, ConfigFileSetsSubcommandOptionsAndRejectsUnknownKeys) {
  const auto dir = test::temp_dir();
  const auto log = dir + "/l.tlog";
  {
    auto w = mavlink::TlogWriter::open(log);
    mavlink::FrameEncoder enc(1, 1);
    mavlink::FrameBuffer buf;
    for (int i = 0; i < 101; ++i) w->write(1'000'000 + static_cast<uint64_t>(i) * 10'000, {buf.data(), enc.encode(mavlink::msg::Attitude{}, buf)});
  }
  std::ofstream(dir + "/ok.toml") << "json = true\n[inspect]\ntlog = \"" << log << "\"\nexpect = \"ATTITUDE=100\"\n";
  auto ok = test::run_hitl({"--config", dir + "/ok.toml", "inspect"});
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_NE(ok.out.find("\"ATTITUDE\""), std::string::npos);
  std::ofstream(dir + "/fail.toml") << "[inspect]\ntlog = \"" << log << "\"\nexpect = \"ATTITUDE=50\"\n";
  EXPECT_EQ(test::run_hitl({"--config", dir + "/fail.toml", "inspect"}).exit_code, 1);
  std::ofstream(dir + "/bad.toml") << "bogus_key = 3\n";
  auto bad = test::run_hitl({"--config", dir + "/bad.toml", "inspect", "--tlog", log});
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("bogus_key"), std::string::npos) << bad.err;
  EXPECT_EQ(test::run_hitl({"--config", dir + "/missing.toml", "inspect", "--tlog", log}).exit_code, 2);

  // -v names new senders and message ids on stderr; without it, stderr has only the start line.
  auto verbose = test::run_hitl({"-v", "inspect", "--tlog", log});
  EXPECT_NE(verbose.err.find("new source tlog sysid 1 compid 1"), std::string::npos) << verbose.err;
  EXPECT_NE(verbose.err.find("new message ATTITUDE"), std::string::npos) << verbose.err;
  EXPECT_EQ(test::run_hitl({"inspect", "--tlog", log}).err.find("new message"), std::string::npos);
}

}  // namespace
}  // namespace hitl
