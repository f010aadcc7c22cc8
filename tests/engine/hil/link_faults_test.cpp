// A link's faults on their own (engine/hil/link_faults.h): one datagram a step of 4 ms, what
// leaves when. Burst loss keeps Gilbert-Elliott's statistics, the rate limit its rate, reorder
// swaps neighbours, duplicate sends twice, jitter stays within its bound and keeps the order.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "engine/hil/link_faults.h"

namespace hitl::hil {
namespace {

constexpr double kStep_s = 0.004;

struct Left {
  int seq;       ///< which step's datagram
  double due_s;
};

/// `steps` datagrams, one per step (each frame: its step number), through `p`; what left, in order.
/// The steps run at `speed` times real time: simulated time k * step, wall time k * step / speed.
std::vector<Left> run(const faults::LinkImpairment& p, int steps, LinkFaults& link, double speed = 1) {
  std::vector<Left> out;
  auto leave = [&](LinkFaults::Datagram& d) { out.push_back({d.frames[0][0] | d.frames[0][1] << 8, d.due_s}); };
  for (int k = 0; k < steps; ++k) {
    link.set(p, k * kStep_s);  // as the session does, every step
    const double now_s = k * kStep_s / speed;
    const uint8_t frame[2] = {static_cast<uint8_t>(k & 0xff), static_cast<uint8_t>(k >> 8)};
    link.hold(frame, 1u);
    link.close_datagram(now_s);
    link.release_due(now_s, leave);  // as the session does, between its ticks
  }
  link.release_due(1e9, leave);
  return out;
}

TEST(LinkFaults, BurstLossHasGilbertElliottsLossRateAndBurstLength) {
  LinkFaults link(1, "test");
  faults::LinkImpairment p;
  p.burst_bad_p = 0.02;
  p.burst_good_p = 0.25;  // bursts of 4 datagrams on average; lost 0.02 / (0.02 + 0.25) = 7.4 %
  const int n = 50000;
  const auto left = run(p, n, link);
  const double lost = 1.0 - static_cast<double>(left.size()) / n;
  EXPECT_NEAR(lost, 0.02 / 0.27, 0.01);
  int bursts = 0;
  for (std::size_t i = 1; i < left.size(); ++i) bursts += left[i].seq - left[i - 1].seq > 1 ? 1 : 0;
  const double mean_burst = static_cast<double>(n - static_cast<int>(left.size())) / bursts;
  EXPECT_NEAR(mean_burst, 4.0, 0.4);
  EXPECT_EQ(link.counts().dropped, static_cast<uint64_t>(n) - left.size());
}

TEST(LinkFaults, RateLimitPassesAtMostItsRate) {
  LinkFaults link(1, "test");
  faults::LinkImpairment p;
  p.max_rate_hz = 50;  // from 250 a second
  const auto left = run(p, 2500, link);  // 10 s
  EXPECT_NEAR(static_cast<double>(left.size()), 500.0, 2.0);
  for (std::size_t i = 1; i < left.size(); ++i) EXPECT_GE(left[i].seq - left[i - 1].seq, 5);
}

TEST(LinkFaults, RateLimitCountsSimulatedSecondsWhateverTheSpeed) {
  faults::LinkImpairment p;
  p.max_rate_hz = 50;
  for (double speed : {0.5, 4.0}) {  // 10 s of simulated time in 20 s or 2.5 s of wall time
    LinkFaults link(1, "test");
    const auto left = run(p, 2500, link, speed);
    EXPECT_NEAR(static_cast<double>(left.size()), 500.0, 2.0) << "at " << speed << "x";
  }
}

TEST(LinkFaults, ReorderSwapsNeighboursDuplicateSendsTwice) {
  LinkFaults link(1, "test");
  faults::LinkImpairment p;
  p.reorder_p = 0.1;
  const auto left = run(p, 1000, link);
  int swapped = 0;
  for (std::size_t i = 1; i < left.size(); ++i) {
    if (left[i].seq < left[i - 1].seq) {
      EXPECT_EQ(left[i - 1].seq - left[i].seq, 1);  // only a neighbour overtakes
      ++swapped;
    }
  }
  EXPECT_GT(swapped, 60);
  EXPECT_EQ(static_cast<uint64_t>(swapped), link.counts().reordered);
  EXPECT_GE(left.size(), 999u);  // all but perhaps the last, still held back

  LinkFaults dup(1, "test");
  faults::LinkImpairment q;
  q.duplicate_p = 0.2;
  const auto twice = run(q, 1000, dup);
  EXPECT_NEAR(static_cast<double>(twice.size() - 1000), 200.0, 40.0);
  EXPECT_EQ(twice.size() - 1000, dup.counts().duplicated);
}

TEST(LinkFaults, JitterStaysWithinItsBoundAndKeepsTheOrder) {
  LinkFaults link(1, "test");
  faults::LinkImpairment p;
  p.delay_s = 0.010;
  p.jitter_s = 0.020;
  const auto left = run(p, 1000, link);
  ASSERT_EQ(left.size(), 1000u);
  double min_s = 1, max_s = 0;
  for (std::size_t i = 0; i < left.size(); ++i) {
    EXPECT_EQ(left[i].seq, static_cast<int>(i));
    const double added_s = left[i].due_s - left[i].seq * kStep_s;
    min_s = std::min(min_s, added_s);
    max_s = std::max(max_s, added_s);
    if (i > 0) {
      EXPECT_GE(left[i].due_s, left[i - 1].due_s);
    }
  }
  EXPECT_GE(min_s, 0.010 - 1e-12);
  EXPECT_LE(max_s, 0.030 + 1e-12);
  EXPECT_GT(max_s - min_s, 0.015);  // spread over the jitter
}

}  // namespace
}  // namespace hitl::hil
