// The HIL link's faults in lockstep (docs/faults.md; link_faults.h): what they drop, repeat and
// reorder depends on --seed and the steps only, not on how fast the steps run, so a lockstep run
// against the same answers gives the board the same stream (the replay's premise). A stand-in
// board answers with the same command every step, at full speed and at real time.
#include <gtest/gtest.h>

#include <cstdio>

#include "tests/engine/hil/lockstep_board.h"

namespace hitl::hil {
namespace {

const std::vector<std::string> kLinkFaults = {"hil-rate:50@0.3", "hil-drop:0.2@0.3", "hil-burst:0.05,0.5@0.3", "hil-reorder:0.1@0.3",
                                              "hil-dup:0.1@0.3"};

/// The HIL_SENSORs the board got, in order, at `speed` (0: as fast as it goes) with `seed`.
std::vector<uint64_t> stream(double speed, uint64_t seed) {
  return test_lockstep::fly(kLinkFaults, 1.0, [](uint64_t) { return 0.0; }, true, seed, [speed](SessionConfig& c) {
           c.speed = speed;
           c.lockstep_timeout_s = 0.005;  // each lost HIL_SENSOR is an answer the session waits for
         }).arrivals;
}

TEST(LinkFaultsInLockstep, TheSameSeedGivesTheBoardTheSameStreamAtAnySpeed) {
  const auto fast = stream(0, 1), real_time = stream(1, 1), other_seed = stream(0, 2);
  std::printf("the board got %zu of 250 HIL_SENSORs (%zu with another seed)\n", fast.size(), other_seed.size());
  ASSERT_GT(fast.size(), 75u);   // 0.3 s whole, then at most 50 a second
  EXPECT_LT(fast.size(), 120u);
  EXPECT_EQ(fast, real_time) << "what the link faults did must not depend on the wall clock";
  EXPECT_NE(fast, other_seed);
}

}  // namespace
}  // namespace hitl::hil
