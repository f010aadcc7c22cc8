// The doctor's VIO checks (engine/doctor/vio_checks) on fixed inputs: the server's report, its pipe
// and voxl-vision-hub's configuration.
#include <gtest/gtest.h>

#include "engine/doctor/vio_checks.h"
#include "tests/engine/doctor/check_fixtures.h"

namespace hitl::doctor {
namespace {

using namespace fixtures;

TEST(DoctorVio, ServerReportPipeAndVisionHub) {
  const std::string report = R"({"running":true,"listen":"0.0.0.0:14570","odometry_rate_hz":249.6,"odometry":12000})";
  EXPECT_EQ(vio_odometry_check(report, 250).result, Verdict::Pass);
  EXPECT_EQ(vio_odometry_check("voxl-hitl-vio-server --status --json\n" + report + "\n", 250).result, Verdict::Pass);
  EXPECT_EQ(vio_odometry_check(report, 1250).result, Verdict::Fail);
  EXPECT_EQ(vio_odometry_check(std::string(R"({"running":true,"listen":"0.0.0.0:14570","odometry_rate_hz":0})"), 250).result, Verdict::Fail);
  auto down = vio_odometry_check(std::string(R"({"running":false,"error":"voxl-hitl-vio-server is not running"})"), 250);
  EXPECT_EQ(down.result, Verdict::Fail);
  EXPECT_TRUE(has(down.fix, "systemctl enable --now voxl-hitl-vio-server")) << down.fix;
  EXPECT_EQ(vio_odometry_check(std::string("sh: voxl-hitl-vio-server: not found"), 250).result, Verdict::Fail);
  EXPECT_EQ(vio_odometry_check(Error{"needs adb"}, 250).result, Verdict::Skip);
  EXPECT_EQ(vio_server_check(std::string("active\n")).result, Verdict::Pass);
  EXPECT_EQ(vio_server_check(std::string("inactive\n")).result, Verdict::Fail);
  EXPECT_EQ(vio_server_check(Error{"needs adb"}).result, Verdict::Skip);
  EXPECT_EQ(vio_pipe_check(std::string("hitl_vio/\nhitl_vio_extended/\nimu_apps/\n")).result, Verdict::Pass);
  EXPECT_EQ(vio_pipe_check(std::string("hitl_vio_extended\nqvio\n")).result, Verdict::Fail);
  const std::string hub = "{\n  // the spec's settings\n  \"en_vio\": false, \"vio_pipe\": \"qvio\", \"en_hitl\": true, \"offboard_mode\": \"vfc\"\n}";
  auto ok = vision_hub_check(hub);
  EXPECT_EQ(ok.result, Verdict::Pass) << ok.saw;
  EXPECT_TRUE(has(ok.saw, "offboard_mode vfc"));
  EXPECT_EQ(vision_hub_check(std::string(R"({"en_hitl": false})")).result, Verdict::Fail);
  EXPECT_EQ(vision_hub_check(std::string(R"({"en_vio": true})")).result, Verdict::Fail);
  EXPECT_EQ(vision_hub_check(std::string("cat: /etc/modalai/voxl-vision-hub.conf: No such file")).result, Verdict::Fail);
}

}  // namespace
}  // namespace hitl::doctor
