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
  EXPECT_NE(refusal(head + "stack = \"px4\"\n", 3).find("not supported by campaigns yet"), std::string::npos);
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
  for (const char* name : {"regression.toml", "small.toml"}) {
    auto c = load_campaign(std::string(HITL_SOURCE_DIR) + "/docs/examples/campaigns/" + name);
    ASSERT_TRUE(c) << c.error().message;
  }
  auto regression = load_campaign(std::string(HITL_SOURCE_DIR) + "/docs/examples/campaigns/regression.toml");
  ASSERT_TRUE(regression);
  EXPECT_EQ(expand(*regression).size(), 36u);  // 3 trajectories x 4 fault cases x 3 seeds
}

TEST_F(CampaignFileTest, CriterionFiguresAreTheSummarysLeaves) {
  const auto figures = criterion_figures();
  for (const char* f : {"trajectory.rms_m", "trajectory.max_m", "landing.touchdowns", "landing.max_rebound_m",
                        "landing.peak_accel_m_s2", "loop_latency.p99_us", "rates_hz.HIL_SENSOR", "stack.armed", "armed",
                        "sim_time_s", "lockstep.fallbacks"})
    EXPECT_NE(std::find(figures.begin(), figures.end(), f), figures.end()) << f;
  EXPECT_EQ(std::find(figures.begin(), figures.end(), "flight.seed"), figures.end());
}

}  // namespace
}  // namespace hitl::campaign
