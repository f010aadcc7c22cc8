// hitl sim --scenario against hitl target (docs/faults.md): a GPS loss and a weak motor in a flown
// square, the summary's faults, and what the emulated board reported; bad --fault input, exit 2.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <csignal>
#include <fstream>

#include "tests/support/process.h"

namespace hitl {
namespace {

using namespace std::chrono_literals;

TEST(FaultsE2E, ScenarioWithGpsLossAndWeakMotorFliesTheSquareAndIsReported) {
  const uint16_t hil = test::free_udp_port(), gcs = test::free_udp_port(), sim_local = test::free_udp_port();
  test::Process board({test::hitl_binary(), "--json", "target", "--bind", "127.0.0.1", "--hil-port", std::to_string(hil),
                       "--gcs-port", std::to_string(gcs), "--vio-port", "0", "--lockstep"});
  ASSERT_TRUE(board.wait_for_stderr("EMULATED", 10s)) << board.err();
  test::Process sim({test::hitl_binary(), "--json", "sim", "-i", "127.0.0.1", "--hil-port", std::to_string(hil),
                     "--local-port", std::to_string(sim_local), "--no-vio", "--clients", "0", "--lockstep", "--speed", "5",
                     "-t", std::string(HITL_SOURCE_DIR) + "/docs/examples/square.json", "--scenario",
                     std::string(HITL_SOURCE_DIR) + "/docs/examples/scenarios/gps-motor.json"});
  EXPECT_EQ(sim.wait(150s), 0) << sim.err();
  board.signal(SIGINT);
  EXPECT_EQ(board.wait(20s), 0) << board.err();
  const auto lines = sim.out_lines();
  ASSERT_FALSE(lines.empty()) << sim.err();
  const auto j = nlohmann::json::parse(lines.back());
  EXPECT_EQ(j["end"], "trajectory_done") << sim.err();
  ASSERT_EQ(j["faults"].size(), 2u) << j["faults"].dump();
  EXPECT_EQ(j["faults_not_started"], nlohmann::json::array()) << j.dump();
  EXPECT_EQ(j["faults"][0]["name"], "gps-loss");
  EXPECT_NEAR(j["faults"][0]["start_s"].get<double>(), 15.0, 1e-6);
  EXPECT_NEAR(j["faults"][0]["end_s"].get<double>(), 23.0, 1e-6);
  EXPECT_EQ(j["faults"][1]["name"], "motor");
  EXPECT_EQ(j["faults"][1]["args"], nlohmann::json::array({2, 0.8}));
  EXPECT_NEAR(j["faults"][1]["end_s"].get<double>(), 33.0, 1e-6);
  for (const char* said : {"t=15.000 s fault gps-loss started (8 s)", "t=23.000 s fault gps-loss ended",
                           "t=25.000 s fault motor:2,0.8 started (8 s)", "t=33.000 s fault motor:2,0.8 ended"})
    EXPECT_NE(sim.err().find(said), std::string::npos) << said;
  // JSON status objects for each start and end; during the motor fault the board asks more of motor 2.
  int fault_events = 0;
  double motor2_excess = 0;
  for (const auto& line : lines) {
    const auto s = nlohmann::json::parse(line, nullptr, false);
    if (s.contains("fault")) ++fault_events;
    if (s.value("type", "") == "status" && s.contains("active_faults") && s["active_faults"] == nlohmann::json::array({"motor:2,0.8"})) {
      const auto& u = s["motor_commands"];
      motor2_excess = std::max(motor2_excess, u[2].get<double>() - (u[0].get<double>() + u[1].get<double>() + u[3].get<double>()) / 3);
    }
  }
  EXPECT_EQ(fault_events, 4);
  EXPECT_GT(motor2_excess, 0.05) << "the board should command the weak motor harder (1/sqrt(0.8): ~+12 %)";
  // What the board reported: it received HIL_GPS only outside the 8 s loss (30 Hz), as many as were sent.
  const auto board_lines = board.out_lines();
  ASSERT_FALSE(board_lines.empty()) << board.err();
  const auto b = nlohmann::json::parse(board_lines.back());
  EXPECT_EQ(b["hil_gps_received"].get<uint64_t>(), j["sent"]["HIL_GPS"]["count"].get<uint64_t>());
  const double flown_s = j["sim_time_s"].get<double>();
  EXPECT_NEAR(b["hil_gps_received"].get<double>(), 30.0 * (flown_s - 8.0), 30.0);
}

// The done-when flight: a scenario on conditions with a GPS loss, a motor degradation and a link
// delay, flown through hitl target in lockstep while a ground station on the board's GCS port
// (hitl inspect --connect) watches what the board says: STATUSTEXT, its mode, ESTIMATOR_STATUS flags.
TEST(FaultsE2E, ConditionalScenarioWithGpsLossMotorAndDelayAndWhatTheBoardDid) {
  const uint16_t hil = test::free_udp_port(), gcs = test::free_udp_port(), sim_local = test::free_udp_port(),
                 gcs_local = test::free_udp_port();
  test::Process board({test::hitl_binary(), "--json", "target", "--bind", "127.0.0.1", "--hil-port", std::to_string(hil),
                       "--gcs-port", std::to_string(gcs), "--vio-port", "0", "--lockstep"});
  ASSERT_TRUE(board.wait_for_stderr("EMULATED", 10s)) << board.err();
  test::Process ground({test::hitl_binary(), "--json", "inspect", "--connect", "127.0.0.1:" + std::to_string(gcs), "--local-port",
                        std::to_string(gcs_local), "--show", "STATUSTEXT,HEARTBEAT,ESTIMATOR_STATUS", "--duration", "300"});
  test::Process sim({test::hitl_binary(), "--json", "sim", "-i", "127.0.0.1", "--hil-port", std::to_string(hil),
                     "--local-port", std::to_string(sim_local), "--no-vio", "--clients", "0", "--lockstep", "--speed", "5",
                     "-t", std::string(HITL_SOURCE_DIR) + "/docs/examples/square.json", "--scenario",
                     std::string(HITL_SOURCE_DIR) + "/docs/examples/scenarios/gps-motor-delay.json"});
  EXPECT_EQ(sim.wait(150s), 0) << sim.err();
  ground.signal(SIGINT);
  board.signal(SIGINT);
  EXPECT_EQ(board.wait(20s), 0) << board.err();
  ground.wait(20s);
  const auto lines = sim.out_lines();
  ASSERT_FALSE(lines.empty()) << sim.err();
  const auto j = nlohmann::json::parse(lines.back());
  EXPECT_EQ(j["end"], "trajectory_done") << sim.err();
  ASSERT_EQ(j["faults"].size(), 3u) << j["faults"].dump();
  EXPECT_EQ(j["faults"][0]["name"], "gps-loss");
  EXPECT_EQ(j["faults"][1]["name"], "motor");
  EXPECT_EQ(j["faults"][2]["name"], "hil-delay");
  const double gps_start_s = j["faults"][0]["start_s"].get<double>();
  EXPECT_GT(gps_start_s, 3.0) << "started on the climb through 2 m, not at 0";
  EXPECT_NEAR(j["faults"][1]["start_s"].get<double>() - gps_start_s, 8.0, 1e-6);
  EXPECT_NEAR(j["faults"][2]["start_s"].get<double>() - gps_start_s, 18.0, 1e-6);
  EXPECT_GT(j["hil_link_faults"]["delayed_datagrams"].get<uint64_t>(), 1000u);  // 6 s of 250 Hz
  // What the board did, second by second (its time: ESTIMATOR_STATUS time_usec), as a ground station saw it.
  constexpr unsigned kPosHorizAbs = 16;  // ESTIMATOR_STATUS_FLAGS ESTIMATOR_POS_HORIZ_ABS
  int without_gps_position = 0;
  bool with_gps_position_at_the_end = false;
  std::string said;
  std::printf("board_time_s  flags  custom_mode  base_mode  latest STATUSTEXT\n");
  for (const auto& line : ground.out_lines()) {
    const auto g = nlohmann::json::parse(line, nullptr, false);
    if (!g.contains("latest") || !g["latest"].contains("ESTIMATOR_STATUS")) continue;
    const auto& latest = g["latest"];
    const auto& es = latest["ESTIMATOR_STATUS"]["fields"];
    const unsigned flags = es["flags"].get<unsigned>();
    const std::string text = latest.contains("STATUSTEXT") ? latest["STATUSTEXT"]["fields"]["text"].get<std::string>() : "";
    const auto& hb = latest.contains("HEARTBEAT") ? latest["HEARTBEAT"]["fields"] : nlohmann::json::object();
    std::printf("%12.1f  %5u  %11u  %9u  %s\n", es["time_usec"].get<double>() * 1e-6, flags, hb.value("custom_mode", 0u),
                hb.value("base_mode", 0u), text.c_str());
    if (!(flags & kPosHorizAbs)) ++without_gps_position;
    with_gps_position_at_the_end = flags & kPosHorizAbs;
    if (said.find(text) == std::string::npos) said += text + "\n";
  }
  EXPECT_GT(without_gps_position, 0) << "the board's EKF should lose its absolute horizontal position in the GPS loss";
  EXPECT_TRUE(with_gps_position_at_the_end) << "and have it back after";
  EXPECT_NE(said.find("Disarmed by landing"), std::string::npos) << said;
  // The board's own account: it flew and landed, and got every HIL_GPS the sim sent.
  const auto b = nlohmann::json::parse(board.out_lines().back());
  EXPECT_EQ(b["hil_gps_received"].get<uint64_t>(), j["sent"]["HIL_GPS"]["count"].get<uint64_t>());
  EXPECT_FALSE(b["armed"].get<bool>());
}

TEST(FaultsE2E, BadFaultsAreRefusedWithExitTwoNamingTheProblem) {
  const std::pair<std::vector<std::string>, std::string> cases[] = {
      {{"--fault", "gps-los@20"}, "--fault 'gps-los@20': unknown fault 'gps-los'; did you mean 'gps-loss'?"},
      {{"--fault", "motor:2@15"}, "fault motor: takes 2 arguments (motor:i,k), got 1"},
      {{"--fault", "imu-bias:nan,0,0"}, "fault imu-bias: ax_m_s2: 'nan' is not a finite number"},
      {{"--fault", "gps-loss@20+-1"}, "the duration must be more than 0"},
      {{"--scenario", "/dev/zero"}, "--scenario: scenario '/dev/zero' is larger than 1 MiB"},
  };
  for (const auto& [args, message] : cases) {
    std::vector<std::string> argv{test::hitl_binary(), "sim"};
    argv.insert(argv.end(), args.begin(), args.end());
    test::Process p(argv);
    EXPECT_EQ(p.wait(20s), 2) << args[1];
    EXPECT_NE(p.err().find(message), std::string::npos) << p.err();
  }
}

TEST(FaultsE2E, ABadScenarioFileIsRefusedWithExitTwoNamingTheFileAndTheEvent) {
  // What is wrong inside the file is the file's (input): exit 2 before anything runs, the message
  // naming the option, the file and the event.
  const std::string dir = test::temp_dir();
  const std::pair<std::string, std::string> files[] = {
      {R"({"events": [{"at_s": 5, "fault": "gps-los"}]})", "events[0]: unknown fault 'gps-los'; did you mean 'gps-loss'?"},
      {R"({"events": [{"at_s": 5, "fault": "motor", "args": [7, 0.5]}]})", "events[0]: fault motor: i must be within 0..3"},
      {R"({"events": [{"at_s": 5, "fault": "gps-loss"}], "then": 1})", "unknown key 'then'"},
      {"{\"events\": [", "not JSON"},
  };
  int n = 0;
  for (const auto& [content, message] : files) {
    const std::string path = dir + "/bad" + std::to_string(n++) + ".json";
    std::ofstream(path) << content;
    test::Process p({test::hitl_binary(), "sim", "--scenario", path, "--local-port", "0", "--clients", "0", "--duration", "1"});
    EXPECT_EQ(p.wait(20s), 2) << content << ": " << p.err();
    EXPECT_NE(p.err().find("--scenario: scenario '" + path + "': "), std::string::npos) << p.err();
    EXPECT_NE(p.err().find(message), std::string::npos) << p.err();
  }
}

TEST(FaultsE2E, TheTextSummaryWritesEachFaultAsItWasGiven) {
  // No board needed: the session runs its 3 s in real time and sends into the void.
  test::Process sim({test::hitl_binary(), "sim", "-i", "127.0.0.1", "--hil-port", std::to_string(test::free_udp_port()),
                     "--local-port", "0", "--no-vio", "--clients", "0", "--duration", "1.5", "--fault", "motor:2,0.6@0.5",
                     "--fault", "hil-delay:15@1+0.25"});
  ASSERT_EQ(sim.wait(30s), 0) << sim.err();
  EXPECT_NE(sim.out().find("fault motor:2,0.6: from 0.500 s to the end"), std::string::npos) << sim.out();
  EXPECT_NE(sim.out().find("fault hil-delay:15: 1.000 s to 1.25"), std::string::npos) << sim.out();  // ends on the step after
}

}  // namespace
}  // namespace hitl
