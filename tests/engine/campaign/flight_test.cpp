// The matrix expanded into flights: the order, the names, and ids that hang on the parameters only.
#include <gtest/gtest.h>

#include <set>

#include "engine/campaign/flight.h"

namespace hitl::campaign {
namespace {

Campaign two_by_two() {
  Campaign c;
  c.name = "c";
  c.trajectories = {{"hover", "hover.json", "/x/hover.json"}, {"square", "square.json", "/x/square.json"}};
  FaultCase none;
  none.name = "none";
  FaultCase gps;
  gps.name = "gps";
  gps.faults.push_back(*faults::parse_fault("gps-loss@8+4"));
  c.fault_cases = {none, gps};
  c.seeds = {1, 2};
  c.speeds = {0};
  return c;
}

TEST(CampaignFlights, TheMatrixInTrajectoryFaultSeedOrder) {
  const auto c = two_by_two();
  const auto flights = expand(c);
  ASSERT_EQ(flights.size(), 8u);
  EXPECT_EQ(flights[0].name, "hover/none/seed-1");
  EXPECT_EQ(flights[1].name, "hover/none/seed-2");
  EXPECT_EQ(flights[2].name, "hover/gps/seed-1");
  EXPECT_EQ(flights[7].name, "square/gps/seed-2");
  for (std::size_t i = 0; i < flights.size(); ++i) EXPECT_EQ(flights[i].index, i);
  std::set<std::string> ids;
  for (const auto& f : flights) {
    EXPECT_EQ(f.id.size(), 12u);
    ids.insert(f.id);
  }
  EXPECT_EQ(ids.size(), flights.size());  // every flight its own id
}

TEST(CampaignFlights, IdsDependOnTheParametersNotOnTheOrderOrName) {
  const auto c = two_by_two();
  const auto before = expand(c);
  auto grown = two_by_two();
  grown.name = "renamed";
  grown.seeds = {7, 1, 2};  // a seed added in front: indices move, ids stay
  const auto after = expand(grown);
  ASSERT_EQ(after.size(), 12u);
  EXPECT_EQ(after[1].name, "hover/none/seed-1");
  EXPECT_EQ(after[1].id, before[0].id);
  EXPECT_EQ(after[5].id, before[3].id);  // hover/gps/seed-2
  auto changed = two_by_two();
  changed.fault_cases[1].faults[0] = *faults::parse_fault("gps-loss@9+4");
  EXPECT_NE(expand(changed)[2].id, before[2].id);
  auto limited = two_by_two();
  limited.sim_limit_s = 30;
  EXPECT_NE(expand(limited)[0].id, before[0].id);
}

TEST(CampaignFlights, TheIdIsTheHashOfTheParameterText) {
  const auto c = two_by_two();
  const auto flights = expand(c);
  EXPECT_EQ(flights[0].id, stable_id(flight_parameters(c, flights[0])));
  EXPECT_EQ(flight_parameters(c, flights[2]),
            "stack=target\ntrajectory=hover.json\nfaults=gps-loss@8+4;\nseed=1\nspeed=0\nsim_limit_s=0");
  EXPECT_EQ(stable_id(""), "cbf29ce48422");  // FNV-1a 64's offset basis, its top 48 bits
}

TEST(CampaignFlights, SpeedsNamedInTheFileAreInTheName) {
  auto c = two_by_two();
  c.speeds = {0, 10};
  const auto flights = expand(c);
  ASSERT_EQ(flights.size(), 16u);
  EXPECT_EQ(flights[0].name, "hover/none/seed-1/x0");
  EXPECT_EQ(flights[1].name, "hover/none/seed-1/x10");
}

}  // namespace
}  // namespace hitl::campaign
