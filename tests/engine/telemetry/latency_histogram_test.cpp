#include "engine/telemetry/latency_histogram.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace hitl::telemetry {
namespace {

TEST(LatencyHistogram, EmptyIsAllZero) {
  LatencyHistogram h;
  const auto s = h.summary();
  EXPECT_EQ(s.count, 0u);
  EXPECT_EQ(s.p50_us, 0);
  EXPECT_EQ(s.max_us, 0);
  for (const auto& b : s.bins) EXPECT_EQ(b.count, 0u);
}

TEST(LatencyHistogram, OneValueRepeatedIsExact) {
  LatencyHistogram h;
  for (int i = 0; i < 1000; ++i) h.add(1234.0);
  const auto s = h.summary();
  EXPECT_EQ(s.count, 1000u);
  EXPECT_DOUBLE_EQ(s.p50_us, 1234.0);  // clamped to the exact min and max
  EXPECT_DOUBLE_EQ(s.p99_us, 1234.0);
  EXPECT_DOUBLE_EQ(s.max_us, 1234.0);
  EXPECT_DOUBLE_EQ(s.mean_us, 1234.0);
}

TEST(LatencyHistogram, PercentilesOfAUniformSpreadWithinTheBinResolution) {
  LatencyHistogram h;
  for (int v = 1; v <= 10000; ++v) h.add(v);  // 1 us .. 10 ms
  const auto s = h.summary();
  EXPECT_NEAR(s.p50_us, 5000, 5000 * 0.035);
  EXPECT_NEAR(s.p95_us, 9500, 9500 * 0.035);
  EXPECT_NEAR(s.p99_us, 9900, 9900 * 0.035);
  EXPECT_DOUBLE_EQ(s.max_us, 10000);
  EXPECT_DOUBLE_EQ(s.min_us, 1);
  EXPECT_LE(s.p50_us, s.p95_us);
  EXPECT_LE(s.p95_us, s.p99_us);
  EXPECT_LE(s.p99_us, s.max_us);
}

TEST(LatencyHistogram, TheTailDecidesP99) {
  LatencyHistogram h;
  for (int i = 0; i < 980; ++i) h.add(100);
  for (int i = 0; i < 20; ++i) h.add(20000);  // 2 % slow
  const auto s = h.summary();
  EXPECT_NEAR(s.p50_us, 100, 4);
  EXPECT_NEAR(s.p95_us, 100, 4);
  EXPECT_NEAR(s.p99_us, 20000, 20000 * 0.035);
}

TEST(LatencyHistogram, CoarseBinsCountEachSampleOnceAtTheirEdges) {
  LatencyHistogram h;
  h.add(0);       // [0, 250)
  h.add(249.9);   // [0, 250)
  h.add(250);     // [250, 500)
  h.add(3999);    // [2000, 4000)
  h.add(4000);    // [4000, 8000)
  h.add(1e9);     // above the last edge
  const auto s = h.summary();
  EXPECT_EQ(s.bins[0].lo_us, 0u);
  EXPECT_EQ(s.bins[0].hi_us, 250u);
  EXPECT_EQ(s.bins[0].count, 2u);
  EXPECT_EQ(s.bins[1].count, 1u);
  EXPECT_EQ(s.bins[4].hi_us, 4000u);
  EXPECT_EQ(s.bins[4].count, 1u);
  EXPECT_EQ(s.bins[5].lo_us, 4000u);
  EXPECT_EQ(s.bins[5].count, 1u);
  EXPECT_EQ(s.bins.back().hi_us, 0u);
  EXPECT_EQ(s.bins.back().count, 1u);
  uint64_t total = 0;
  for (const auto& b : s.bins) total += b.count;
  EXPECT_EQ(total, s.count);
}

TEST(LatencyHistogram, HostileValuesAreBoundedNotCrashes) {
  LatencyHistogram h;
  h.add(-5);
  h.add(std::numeric_limits<double>::quiet_NaN());
  h.add(std::numeric_limits<double>::infinity());
  h.add(1e300);
  const auto s = h.summary();
  EXPECT_EQ(s.count, 4u);
  EXPECT_EQ(s.min_us, 0);
  EXPECT_TRUE(std::isfinite(s.p99_us));
}

TEST(LatencyHistogram, MemoryIsFixed) {
  // Bounded memory: the object's size is all it ever holds.
  EXPECT_LT(sizeof(LatencyHistogram), 5000u);
}

}  // namespace
}  // namespace hitl::telemetry
