// The campaign file: a good one read whole; each kind of bad input refused with file, line and key.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "engine/campaign/campaign_file.h"
#include "engine/campaign/flight.h"

namespace hitl::campaign {
namespace {

/// A folder with a trajectory and a scenario beside the campaign files the tests write.
class CampaignFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("hitl-campaign-test-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
    write("hover.json", R"({"waypoints": [{"t": 0, "x": 0, "y": 0, "z": 2, "yaw": 0}, {"t": 4, "x": 0, "y": 0, "z": 2, "yaw": 0}]})");
    write("square.json", R"({"waypoints": [{"t": 0, "x": 0, "y": 0, "z": 2, "yaw": 0}, {"t": 4, "x": 2, "y": 0, "z": 2, "yaw": 0}]})");
    write("gust.json", R"({"events": [{"at_s": 3, "fault": "gust", "args": [2, 1], "duration_s": 2}]})");
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& text) {
    const auto path = (dir_ / name).string();
    std::ofstream(path) << text;
    return path;
  }
  Expected<Campaign> parse(const std::string& text) { return parse_campaign(text, (dir_ / "c.toml").string()); }
  /// The refusal's message, which must start with the file and the line.
  std::string refusal(const std::string& text, int line) {
    auto c = parse(text);
    if (c) return "accepted";
    EXPECT_EQ(c.error().kind, ErrorKind::Input);
    const std::string where = (dir_ / "c.toml").string() + ":" + std::to_string(line) + ": ";
    EXPECT_EQ(c.error().message.rfind(where, 0), 0u) << c.error().message << " (expected it to start with " << where << ")";
    return c.error().message;
  }
  std::filesystem::path dir_;
};

const char* kGood = R"([campaign]
name = "nightly"
stack = "target"
time_limit_s = 60
sim_limit_s = 40

[matrix]
trajectories = ["hover.json", "square.json"]
seeds = [1, 2, 3]
speeds = [0, 10]

[faults]
none = []
gps-loss = ["gps-loss@8+4", "motor:2,0.8@10"]
gust = { scenario = "gust.json" }

[criteria]
tracking = { figure = "trajectory.rms_m", max = 1.5 }
rate = { figure = "rates_hz.HIL_SENSOR", min = 240 }
disarmed = { figure = "stack.armed", equals = false }
)";

TEST_F(CampaignFileTest, AGoodFileIsReadWhole) {
  auto c = parse(kGood);
  ASSERT_TRUE(c) << c.error().message;
  EXPECT_EQ(c->name, "nightly");
  EXPECT_EQ(c->stack, Stack::Target);
  EXPECT_EQ(c->time_limit_s, 60);
  EXPECT_EQ(c->sim_limit_s, 40);
  ASSERT_EQ(c->trajectories.size(), 2u);
  EXPECT_EQ(c->trajectories[0].name, "hover");
  EXPECT_EQ(c->trajectories[1].path, (dir_ / "square.json").string());  // relative to the file's folder
  EXPECT_EQ(c->seeds, (std::vector<uint64_t>{1, 2, 3}));
  EXPECT_EQ(c->speeds, (std::vector<double>{0, 10}));
  ASSERT_EQ(c->fault_cases.size(), 3u);  // in the file's order, not toml++'s sorted one
  EXPECT_EQ(c->fault_cases[0].name, "none");
  EXPECT_TRUE(c->fault_cases[0].faults.empty());
  EXPECT_EQ(c->fault_cases[1].name, "gps-loss");
  ASSERT_EQ(c->fault_cases[1].faults.size(), 2u);
  EXPECT_EQ(c->fault_cases[1].faults[1].text(), "motor:2,0.8@10");
  EXPECT_EQ(c->fault_cases[2].name, "gust");
  ASSERT_EQ(c->fault_cases[2].faults.size(), 1u);
  EXPECT_EQ(c->fault_cases[2].faults[0].name(), "gust");
  ASSERT_EQ(c->criteria.size(), 3u);
  EXPECT_EQ(c->criteria[0].name, "tracking");
  EXPECT_EQ(c->criteria[0].comparison, Comparison::AtMost);
  EXPECT_EQ(c->criteria[0].limit, 1.5);
  EXPECT_EQ(c->criteria[0].line, 18);
  EXPECT_EQ(c->criteria[1].comparison, Comparison::AtLeast);
  EXPECT_EQ(c->criteria[2].equals_bool, std::optional<bool>(false));
}

TEST_F(CampaignFileTest, ExpectationsAreReadInTheFilesOrder) {
  auto c = parse(std::string(kGood) + "landed = { figure = \"stack.landed_state\", equals = \"on_ground\" }\n"
                                      "[expect]\nsays-gps = { statustext = \"GPS (lost|loss)\", after_fault = \"gps-loss\", within_s = 5 }\n"
                                      "lands = { mode = \"Land\" }\ndisarms = { event = \"^disarmed$\" }\n");
  ASSERT_TRUE(c) << c.error().message;
  ASSERT_EQ(c->expectations.size(), 3u);
  EXPECT_EQ(c->expectations[0].name, "says-gps");
  EXPECT_EQ(c->expectations[0].kind, ExpectKind::Statustext);
  EXPECT_EQ(c->expectations[0].pattern, "GPS (lost|loss)");
  EXPECT_EQ(c->expectations[0].after_fault, "gps-loss");
  EXPECT_EQ(c->expectations[0].within_s, std::optional<double>(5));
  EXPECT_EQ(c->expectations[1].kind, ExpectKind::Mode);
  EXPECT_EQ(c->expectations[2].kind, ExpectKind::Event);
  EXPECT_EQ(c->criteria.back().equals_text, std::optional<std::string>("on_ground"));
}

TEST_F(CampaignFileTest, BadExpectationsAreRefusedWithTheirKey) {
  const std::string head = "[campaign]\nname = \"x\"\n[matrix]\ntrajectories = [\"hover.json\"]\n[expect]\n";
  EXPECT_NE(refusal(head + "a = { statustext = \"(unclosed\" }\n", 6).find("expect.a.statustext: not a regular expression"),
            std::string::npos);
  EXPECT_NE(refusal(head + "a = { mode = \"Land\", event = \"x\" }\n", 6).find("expect.a: needs exactly one of statustext, mode, event"),
            std::string::npos);
  EXPECT_NE(refusal(head + "a = { mode = \"Land\", after_fault = \"gps-lost\" }\n", 6)
                .find("expect.a.after_fault: \"gps-lost\" is not a fault"), std::string::npos);
  EXPECT_NE(refusal(head + "a = { mode = \"Land\", within_s = -1 }\n", 6).find("expect.a.within_s: must be between"),
            std::string::npos);
  EXPECT_NE(refusal(head + "a = { mode = \"Land\", when = 3 }\n", 6).find("expect.a.when: unknown key"), std::string::npos);
  EXPECT_NE(refusal(head + "flown = { mode = \"Land\" }\n", 6).find("expect.flown: \"flown\" is already a criterion's name"),
            std::string::npos);
}

TEST_F(CampaignFileTest, DefaultsAreOneSeedSpeedZeroAndNoFault) {
  auto c = parse("[campaign]\nname = \"x\"\n[matrix]\ntrajectories = [\"hover.json\"]\n");
  ASSERT_TRUE(c) << c.error().message;
  EXPECT_EQ(c->seeds, (std::vector<uint64_t>{1}));
  EXPECT_EQ(c->speeds, (std::vector<double>{0}));
  ASSERT_EQ(c->fault_cases.size(), 1u);
  EXPECT_EQ(c->fault_cases[0].name, "none");
  EXPECT_EQ(c->time_limit_s, 300);
}

TEST_F(CampaignFileTest, TomlSyntaxNamesTheLine) {
  const auto m = refusal("[campaign]\nname = \"x\"\n[matrix\n", 3);
  EXPECT_NE(m.find("c.toml:3"), std::string::npos) << m;
}

TEST_F(CampaignFileTest, UnknownKeysAreRefusedWithTheirLine) {
  EXPECT_NE(refusal("[campaign]\nname = \"x\"\nnmae = 1\n[matrix]\ntrajectories = [\"hover.json\"]\n", 3)
                .find("campaign.nmae: unknown key"), std::string::npos);
  EXPECT_NE(refusal("[campaign]\nname = \"x\"\n[matrix]\ntrajectories = [\"hover.json\"]\nseed = [1]\n", 5)
                .find("matrix.seed: unknown key (known here: seeds, speeds, trajectories)"), std::string::npos);
  EXPECT_NE(refusal("[campaign]\nname = \"x\"\n[matrix]\ntrajectories = [\"hover.json\"]\n[extras]\nx = 1\n", 5)
                .find("extras: unknown key"), std::string::npos);
  EXPECT_NE(refusal("[campaign]\nname = \"x\"\n[matrix]\ntrajectories = [\"hover.json\"]\n[criteria]\n"
                    "a = { figure = \"trajectory.rms_m\", maximum = 1 }\n", 6)
                .find("criteria.a.maximum: unknown key"), std::string::npos);
}

TEST_F(CampaignFileTest, BadValuesAreRefusedWithTheirKey) {
  const std::string head = "[campaign]\nname = \"x\"\n";
  EXPECT_NE(refusal("[campaign]\nname = \"a b\"\n", 2).find("campaign.name: \"a b\" is not a name"), std::string::npos);
  EXPECT_NE(refusal(head + "time_limit_s = -1\n", 3).find("campaign.time_limit_s: must be between"), std::string::npos);
  EXPECT_NE(refusal(head + "stack = \"gazebo\"\n", 3).find("campaign.stack: \"gazebo\" is not a flight stack"), std::string::npos);
  EXPECT_NE(refusal(head + "stack = \"gazebo\"\n", 3).find("(known: target, px4)"), std::string::npos);
  EXPECT_NE(refusal(head + "[matrix]\ntrajectories = [\"missing.json\"]\n", 4).find("matrix.trajectories[0]: "), std::string::npos);
  EXPECT_NE(refusal(head + "[matrix]\ntrajectories = [\"hover.json\"]\nseeds = [1, -2]\n", 5)
                .find("matrix.seeds[1]: must be a whole number >= 0"), std::string::npos);
  EXPECT_NE(refusal(head + "[matrix]\ntrajectories = [\"hover.json\"]\nseeds = [1, 1]\n", 5).find("listed twice"),
            std::string::npos);
  EXPECT_NE(refusal(head + "[matrix]\ntrajectories = [\"hover.json\"]\n[faults]\nbad = [\"gps-lost@3\"]\n", 6)
                .find("faults.bad[0]: "), std::string::npos);
  EXPECT_NE(refusal(head + "[matrix]\ntrajectories = [\"hover.json\"]\n[faults]\nnone = []\ncalm = []\n", 7)
                .find("faults.calm: the same faults as faults.none"), std::string::npos);
  EXPECT_NE(refusal(head + "[matrix]\ntrajectories = [\"hover.json\"]\n[faults]\nnone = [\"gps-loss\"]\n", 6)
                .find("faults.none: the case \"none\" is the flight without faults"), std::string::npos);
  EXPECT_NE(refusal(head + "[matrix]\ntrajectories = [\"hover.json\"]\n[criteria]\nr = { figure = \"trajectory.rms\", max = 1 }\n", 6)
                .find("criteria.r.figure: \"trajectory.rms\" is not a figure"), std::string::npos);
  EXPECT_NE(refusal(head + "[matrix]\ntrajectories = [\"hover.json\"]\n[criteria]\nr = { figure = \"trajectory.rms_m\", max = 1, min = 0 }\n", 6)
                .find("criteria.r: needs exactly one of max, min, equals"), std::string::npos);
  EXPECT_NE(refusal(head + "[matrix]\ntrajectories = [\"hover.json\"]\n[criteria]\nr = { figure = \"trajectory.rms_m\", max = \"1\" }\n", 6)
                .find("criteria.r.max: must be a number"), std::string::npos);
}

TEST_F(CampaignFileTest, AnEmptyMatrixIsRefused) {
  const std::string head = "[campaign]\nname = \"x\"\n";
  EXPECT_NE(refusal(head + "[matrix]\ntrajectories = []\n", 4).find("matrix.trajectories: is empty"), std::string::npos);
  EXPECT_NE(refusal(head + "[matrix]\ntrajectories = [\"hover.json\"]\nseeds = []\n", 5).find("matrix.seeds: is empty"),
            std::string::npos);
  EXPECT_NE(refusal(head + "[matrix]\ntrajectories = [\"hover.json\"]\n[faults]\n", 5).find("faults: has no cases"),
            std::string::npos);
  EXPECT_NE(refusal(head, 1).find("matrix: missing"), std::string::npos);
}

TEST_F(CampaignFileTest, TheExamplesParse) {
  for (const char* name : {"regression.toml", "small.toml", "px4-square.toml"}) {
    auto c = load_campaign(std::string(HITL_SOURCE_DIR) + "/docs/examples/campaigns/" + name);
    ASSERT_TRUE(c) << c.error().message;
  }
  auto regression = load_campaign(std::string(HITL_SOURCE_DIR) + "/docs/examples/campaigns/regression.toml");
  ASSERT_TRUE(regression);
  EXPECT_EQ(expand(*regression).size(), 36u);  // 3 trajectories x 4 fault cases x 3 seeds
  auto px4 = load_campaign(std::string(HITL_SOURCE_DIR) + "/docs/examples/campaigns/px4-square.toml");
  ASSERT_TRUE(px4);
  EXPECT_EQ(px4->stack, Stack::Px4);
  EXPECT_EQ(expand(*px4).size(), 4u);  // square and hover x none and gps-loss, at 5x
}

TEST_F(CampaignFileTest, CriterionFiguresAreTheSummarysLeaves) {
  const auto figures = criterion_figures();
  for (const char* f : {"trajectory.rms_m", "trajectory.max_m", "landing.touchdowns", "landing.max_rebound_m",
                        "landing.peak_accel_m_s2", "loop_latency.p99_us", "rates_hz.HIL_SENSOR", "stack.armed", "armed",
                        "sim_time_s", "lockstep.fallbacks"})
    EXPECT_NE(std::find(figures.begin(), figures.end(), f), figures.end()) << f;
  EXPECT_EQ(std::find(figures.begin(), figures.end(), "flight.seed"), figures.end());
}

// --- stack = "px4" -------------------------------------------------------------------------------

/// A stand-in PX4 SITL build folder: bin/px4 (executable), etc/init.d-posix/rcS and the version header.
void make_px4_build(const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir / "bin");
  std::filesystem::create_directories(dir / "etc" / "init.d-posix");
  std::filesystem::create_directories(dir / "src" / "lib" / "version");
  std::ofstream(dir / "bin" / "px4") << "#!/bin/sh\n";
  std::filesystem::permissions(dir / "bin" / "px4", std::filesystem::perms::owner_all);
  std::ofstream(dir / "etc" / "init.d-posix" / "rcS") << "\n";
  std::ofstream(dir / "src" / "lib" / "version" / "build_git_version.h") << "#define PX4_GIT_TAG_STR \"v1.16.0\"\n";
}

const char* kPx4Head = "[campaign]\nname = \"p\"\nstack = \"px4\"\n";
const char* kPx4Matrix = "[matrix]\ntrajectories = [\"hover.json\"]\nspeeds = [5]\n";

TEST_F(CampaignFileTest, Px4StackTakesItsBuildRelativeToTheFileAndItsParameters) {
  make_px4_build(dir_ / "px4-build");
  auto c = parse(std::string(kPx4Head) + "px4 = \"px4-build\"\npx4_params = { SYS_FAILURE_EN = 1, MPC_XY_VEL_MAX = 5.5 }\n" + kPx4Matrix);
  ASSERT_TRUE(c) << c.error().message;
  EXPECT_EQ(c->stack, Stack::Px4);
  ASSERT_TRUE(c->px4);
  EXPECT_EQ(c->px4->dir, (dir_ / "px4-build").string());
  EXPECT_EQ(c->px4->line, 4);
  ASSERT_EQ(c->px4->params.size(), 2u);
  EXPECT_EQ(c->px4->params[0].name, "SYS_FAILURE_EN");  // the file's order
  EXPECT_EQ(c->px4->params[0].value, "1");
  EXPECT_EQ(c->px4->params[1].name, "MPC_XY_VEL_MAX");
  EXPECT_EQ(c->px4->params[1].value, "5.5");
  EXPECT_EQ(stack_version(*c), "");  // not found yet
  ASSERT_TRUE(find_campaign_px4(*c, "")) << "the stand-in build";
  EXPECT_EQ(stack_version(*c), "v1.16.0");
  EXPECT_EQ(c->px4->build->program, (dir_ / "px4-build" / "bin" / "px4").string());
  // PX4's parameters are part of a flight's id; its build is not (a new PX4 flies the same flights).
  const auto flights = expand(*c);
  ASSERT_EQ(flights.size(), 1u);
  EXPECT_NE(flight_parameters(*c, flights[0]).find("stack=px4\npx4_params=SYS_FAILURE_EN=1;MPC_XY_VEL_MAX=5.5;"), std::string::npos)
      << flight_parameters(*c, flights[0]);
  auto other = parse(std::string(kPx4Head) + "px4 = \"elsewhere\"\npx4_params = { SYS_FAILURE_EN = 1, MPC_XY_VEL_MAX = 5.5 }\n" + kPx4Matrix);
  ASSERT_TRUE(other);
  EXPECT_EQ(expand(*other)[0].id, flights[0].id);
}

TEST_F(CampaignFileTest, ABadPx4FolderIsRefusedWithTheFileLineAndKeyAndWhatIsMissing) {
  const std::string where = (dir_ / "c.toml").string() + ":5: campaign.px4: ";
  auto c = parse(std::string(kPx4Head) + "\npx4 = \"no-such\"\n" + kPx4Matrix);
  ASSERT_TRUE(c) << "found before the flights, not while parsing: --px4 DIR may stand in for it";
  auto found = find_campaign_px4(*c, "");
  ASSERT_FALSE(found);
  EXPECT_EQ(found.error().kind, ErrorKind::Input);
  EXPECT_EQ(found.error().message, where + "'" + (dir_ / "no-such").string() + "': no such folder");

  std::filesystem::create_directories(dir_ / "empty");
  c = parse(std::string(kPx4Head) + "\npx4 = \"empty\"\n" + kPx4Matrix);
  ASSERT_TRUE(c);
  found = find_campaign_px4(*c, "");
  ASSERT_FALSE(found);
  EXPECT_EQ(found.error().message, where + "'" + (dir_ / "empty").string() +
                                       "' is not a PX4 SITL build: no bin/px4, and not a PX4 tree with build/px4_sitl_default");

  // --px4 DIR over the file's: its refusal names the option, as hitl sim --px4's does.
  found = find_campaign_px4(*c, (dir_ / "empty").string());
  ASSERT_FALSE(found);
  EXPECT_EQ(found.error().message.rfind("--px4: '" + (dir_ / "empty").string() + "' is not a PX4 SITL build: no bin/px4", 0), 0u)
      << found.error().message;
  make_px4_build(dir_ / "good");
  EXPECT_TRUE(find_campaign_px4(*c, (dir_ / "good").string()));

  // Neither the file nor the command line names one.
  c = parse(std::string(kPx4Head) + kPx4Matrix);
  ASSERT_TRUE(c);
  found = find_campaign_px4(*c, "");
  ASSERT_FALSE(found);
  EXPECT_EQ(found.error().message.rfind((dir_ / "c.toml").string() + ":3: campaign.px4: missing: stack = \"px4\" needs px4 = \"DIR\"", 0), 0u)
      << found.error().message;

  // --px4 for a campaign against the emulated board is a mistake in the command.
  c = parse("[campaign]\nname = \"t\"\n[matrix]\ntrajectories = [\"hover.json\"]\n");
  ASSERT_TRUE(c);
  found = find_campaign_px4(*c, (dir_ / "good").string());
  ASSERT_FALSE(found);
  EXPECT_EQ(found.error().kind, ErrorKind::Usage);
}

TEST_F(CampaignFileTest, Px4KeysAndBadParameterValuesAreRefusedWithTheirKey) {
  const std::string target = "[campaign]\nname = \"t\"\n";
  EXPECT_NE(refusal(target + "px4 = \"x\"\n", 3).find("campaign.px4: only with stack = \"px4\""), std::string::npos);
  EXPECT_NE(refusal(target + "px4_params = { A = 1 }\n", 3).find("campaign.px4_params: only with stack = \"px4\""), std::string::npos);
  const std::string head = kPx4Head;
  EXPECT_NE(refusal(head + "px4 = 3\n", 4).find("campaign.px4: must be a string"), std::string::npos);
  EXPECT_NE(refusal(head + "px4 = \"\"\n", 4).find("campaign.px4: is empty"), std::string::npos);
  EXPECT_NE(refusal(head + "px4_params = 3\n", 4).find("campaign.px4_params: must be a table"), std::string::npos);
  EXPECT_NE(refusal(head + "px4_params = { SYS_FAILURE_EN = \"on\" }\n", 4)
                .find("campaign.px4_params.SYS_FAILURE_EN: must be a number"), std::string::npos);
  EXPECT_NE(refusal(head + "px4_params = { SYS_FAILURE_EN = true }\n", 4)
                .find("campaign.px4_params.SYS_FAILURE_EN: must be a number"), std::string::npos);
  EXPECT_NE(refusal(head + "px4_params = { sys_failure_en = 1 }\n", 4).find("campaign.px4_params.sys_failure_en: "), std::string::npos);
  EXPECT_NE(refusal(head + "px4_params = { A_NAME_LONGER_THAN_16 = 1 }\n", 4).find("campaign.px4_params.A_NAME_LONGER_THAN_16: "),
            std::string::npos);
  EXPECT_NE(refusal(head + "px4_params = { A = nan }\n", 4).find("campaign.px4_params.A: must be a finite number"), std::string::npos);
  // PX4 runs in lockstep at a stated factor: speeds above 0, given.
  EXPECT_NE(refusal(head + "[matrix]\ntrajectories = [\"hover.json\"]\n", 4).find("matrix.speeds: missing: stack = \"px4\" runs PX4"),
            std::string::npos);
  EXPECT_NE(refusal(head + "[matrix]\ntrajectories = [\"hover.json\"]\nspeeds = [5, 0]\n", 6).find("matrix.speeds[1]: stack = \"px4\""),
            std::string::npos);
}

}  // namespace
}  // namespace hitl::campaign
