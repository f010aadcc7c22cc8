// The simulator's fault windows read back from its STATUSTEXT (engine/faults FaultChange::text()).
#include <gtest/gtest.h>

#include "engine/report/fault_windows.h"

namespace hitl::report {
namespace {

TEST(FaultWindows, StartsAndEndsAsTheSimulatorSaysThem) {
  auto c = parse_fault_change("t=20.000 s fault imu-vibration:8,90 started (5 s)");
  ASSERT_TRUE(c);
  EXPECT_DOUBLE_EQ(c->t_s, 20.0);
  EXPECT_EQ(c->label, "imu-vibration:8,90");
  EXPECT_TRUE(c->started);
  EXPECT_EQ(c->duration_s, 5.0);
  c = parse_fault_change("t=25.000 s fault imu-vibration:8,90 ended");
  ASSERT_TRUE(c);
  EXPECT_FALSE(c->started);
  c = parse_fault_change("t=3.500 s fault gps-loss started");
  ASSERT_TRUE(c);
  EXPECT_FALSE(c->duration_s);
  for (const char* not_one : {"t=1.000 s fault gps-loss refused: 8 faults are active, the limit", "fault gps-loss started",
                              "t=x s fault gps-loss started", "t=1.000 s fault gps-loss started (5 s) and more", "t=1.000 s fault  ended",
                              "trajectory: HOLD (trajectory flown)", "", "t=nan s fault gps-loss started",
                              "t=inf s fault gps-loss ended", "t=-1 s fault gps-loss ended", "t=1e300 s fault gps-loss ended",
                              "t=1 s fault gps-loss started (nan s)", "t=1 s fault :8,90 started"})
    EXPECT_FALSE(parse_fault_change(not_one)) << not_one;
}

TEST(FaultWindows, AnEndClosesTheEarliestOpenWindowOfItsLabel) {
  std::vector<LogEvent> events = {
      {20.01, Severity::Info, "simulator", "t=20.000 s fault gps-loss started (10 s)"},
      {21.0, Severity::Info, "vehicle 1", "t=21.000 s fault gps-loss ended"},  // not the simulator's
      {30.01, Severity::Info, "simulator", "t=30.000 s fault imu-vibration:8,90 started (5 s)"},
      {30.02, Severity::Info, "simulator", "t=30.000 s fault gps-loss ended"},
      {40.0, Severity::Info, "simulator", "t=40.000 s fault motor:1,0.5 started"},
  };
  const auto w = fault_windows(events, true);
  ASSERT_EQ(w.size(), 3u);
  EXPECT_EQ(w[0].label(), "gps-loss");
  EXPECT_DOUBLE_EQ(w[0].start_s, 20.0);
  EXPECT_EQ(w[0].end_s, 30.0);
  EXPECT_EQ(w[1].name, "imu-vibration");
  EXPECT_EQ(w[1].args, "8,90");
  EXPECT_FALSE(w[1].end_s) << "still active when the log ended";
  EXPECT_EQ(w[1].duration_s, 5.0);
  EXPECT_FALSE(w[2].end_s);
  // Without the simulator's clock the events' times are the axis.
  EXPECT_DOUBLE_EQ(fault_windows(events, false)[0].start_s, 20.01);
}

TEST(FaultWindows, ArgumentsAreNamedAsTheCatalogueNamesThem) {
  EXPECT_EQ(named_fault_args("imu-vibration:8,90"), "amp_m_s2 8, freq_hz 90");
  EXPECT_EQ(named_fault_args("gps-loss"), "");
  EXPECT_EQ(named_fault_args("no-such-fault:1,2"), "1, 2");
}

}  // namespace
}  // namespace hitl::report
