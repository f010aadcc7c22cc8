// hitl bridge --tui's data paths: per-link packet rates from two health reports, the board's loss
// from its sources' sequence gaps, and the state of a link in words.
#include <gtest/gtest.h>

#include "tui/bridge_dashboard.h"

namespace hitl::tui {
namespace {

bridge::BridgeHealth report(double uptime_s, uint64_t board_in, uint64_t board_out, bool endpoint_up) {
  bridge::BridgeHealth h;
  h.uptime_s = uptime_s;
  h.board_state = "up";
  h.links = {{"board", "127.0.0.1:14558", true, board_in, board_in * 30, board_out, board_out * 20, 0},
             {"clients", "", true, 10, 300, 20, 600, 0},
             {"udp:127.0.0.1:14550", "127.0.0.1:14550", endpoint_up, 0, 0, board_in, 0, 0}};
  h.loss["1/1"] = {90, 10, 10.0};
  return h;
}

TEST(BridgePaths, RatesComeFromTheTwoLatestReports) {
  const auto before = report(10.0, 1000, 100, true);
  const auto now = report(12.0, 1400, 160, true);
  const auto panel = bridge_paths(now, before);
  ASSERT_EQ(panel.rows.size(), 6u);
  EXPECT_EQ(panel.rows[0].name, "rx board");
  EXPECT_DOUBLE_EQ(panel.rows[0].rate_hz, 200.0);
  EXPECT_EQ(panel.rows[0].count, 1400u);
  EXPECT_EQ(panel.rows[1].name, "tx board");
  EXPECT_DOUBLE_EQ(panel.rows[1].rate_hz, 30.0);
  EXPECT_DOUBLE_EQ(panel.rows[5].rate_hz, 200.0);  // the endpoint gets what the board sends
}

TEST(BridgePaths, BoardLossIsOverAllItsSourcesAndOnlyOnItsIncomingRow) {
  auto now = report(12.0, 1400, 160, true);
  now.loss["1/191"] = {300, 0, 0.0};
  const auto panel = bridge_paths(now, std::nullopt);
  ASSERT_TRUE(panel.rows[0].loss_pct.has_value());
  EXPECT_NEAR(*panel.rows[0].loss_pct, 100.0 * 10 / 400, 1e-9);
  EXPECT_FALSE(panel.rows[1].loss_pct.has_value());
  EXPECT_FALSE(panel.rows[2].loss_pct.has_value());
  EXPECT_DOUBLE_EQ(panel.rows[0].rate_hz, 0.0);  // one report: no rate yet
}

TEST(BridgePaths, ABoardGoneAndALinkDownAreRed) {
  auto now = report(12.0, 1400, 160, false);
  now.board_state = "gone";
  const auto panel = bridge_paths(now, report(11.0, 1400, 150, false));
  EXPECT_EQ(panel.rows[0].health, Health::Bad);
  EXPECT_EQ(panel.rows[0].note, "gone");
  EXPECT_EQ(panel.rows[2].health, Health::Good);
  EXPECT_EQ(panel.rows[4].health, Health::Bad);
  EXPECT_EQ(panel.rows[4].note, "down");
}

}  // namespace
}  // namespace hitl::tui
