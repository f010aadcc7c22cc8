// The link faults (docs/faults.md: hil-* and vio-*) through the real hitl sim over loopback: a
// stand-in board on the HIL port and a stand-in VIO server on the VIO port stamp every datagram as
// it arrives and read its HIL_SENSOR's (ODOMETRY's) time_usec; what they saw is checked against the
// setting and against what the JSON summary says the link faults did (hil_link_faults,
// vio_link_faults). Counts and simulated time only, except delay and jitter, wall time by nature.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <mutex>
#include <set>
#include <thread>
#include <vector>

#include "base/common/clock.h"
#include "base/mavlink/frame_parser.h"
#include "base/mavlink/messages.h"
#include "tests/support/json_lines.h"
#include "tests/support/mavlink_peer.h"
#include "tests/support/process.h"

namespace hitl {
namespace {

using namespace std::chrono_literals;
namespace msg = mavlink::msg;

constexpr uint64_t kStep_us = 4000;  ///< the session's step: one HIL datagram each

struct Arrival {
  double wall_s = 0;     ///< monotonic, when the datagram arrived
  uint64_t time_us = 0;  ///< its HIL_SENSOR's or ODOMETRY's time_usec
};

/// A UDP socket on 127.0.0.1 that stamps each datagram carrying a HIL_SENSOR or an ODOMETRY.
class Receiver {
 public:
  Receiver() : peer_(0, 0) {
    thread_ = std::thread([this] {
      const auto set = mavlink::MessageSet::compiled();
      mavlink::FrameParser parser(set);
      while (running_) {
        if (!peer_.endpoint().wait_readable(20)) continue;
        while (auto d = peer_.endpoint().receive()) {
          Arrival a;
          a.wall_s = monotonic_s();
          bool stamped = false;
          parser.parse_datagram(d->bytes, [&](const mavlink::Frame& f) {
            if (f.is<msg::HilSensor>()) a.time_us = f.as<msg::HilSensor>().time_usec, stamped = true;
            if (f.is<msg::Odometry>()) a.time_us = f.as<msg::Odometry>().time_usec, stamped = true;
          });
          if (!stamped) continue;
          std::lock_guard<std::mutex> lock(mutex_);
          arrivals_.push_back(a);
        }
      }
    });
  }
  ~Receiver() { stop(); }
  void stop() {
    running_ = false;
    if (thread_.joinable()) thread_.join();
  }
  uint16_t port() { return peer_.endpoint().local_address().port(); }
  std::vector<Arrival> arrivals() {
    std::lock_guard<std::mutex> lock(mutex_);
    return arrivals_;
  }

 private:
  test::MavlinkPeer peer_;
  std::atomic<bool> running_{true};
  std::mutex mutex_;
  std::vector<Arrival> arrivals_;
  std::thread thread_;
};

/// hitl sim to `board` and `vio` with these extra arguments, to its end; its JSON summary.
nlohmann::json run_sim(Receiver& board, Receiver& vio, std::vector<std::string> extra) {
  std::vector<std::string> argv{test::hitl_binary(), "--json", "sim", "-i", "127.0.0.1", "--hil-port", std::to_string(board.port()),
                                "--local-port", std::to_string(test::free_udp_port()), "--vio-port", std::to_string(vio.port()),
                                "--clients", "0"};
  argv.insert(argv.end(), extra.begin(), extra.end());
  test::Process sim(argv);
  EXPECT_EQ(sim.wait(30s), 0) << sim.err();
  std::this_thread::sleep_for(200ms);  // the last datagrams in flight
  board.stop();
  vio.stop();
  const auto j = test::last_json_line(sim.out());
  EXPECT_EQ(j.value("type", ""), "summary") << sim.out() << sim.err();
  return j;
}

uint64_t counted(const nlohmann::json& summary, const char* link, const char* what) {
  return summary.at(link).at(what).get<uint64_t>();
}

uint64_t sent(const nlohmann::json& summary, const char* name) { return summary.at("sent").at(name).at("count").get<uint64_t>(); }

bool in_window(uint64_t time_us, double from_s, double to_s) {
  const double t_s = static_cast<double>(time_us) * 1e-6;
  return t_s >= from_s - 1e-6 && t_s < to_s - 1e-6;
}

double percentile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1))];
}

// hil-reorder / vio-reorder: a datagram held back and sent right after the next one; the receiver
// sees time_usec go back by one step exactly as often as the summary says it reordered, nothing lost.
TEST(LinkFaultsE2E, ReorderSwapsNeighboursAtTheReceiverAsOftenAsTheSummaryCounts) {
  Receiver board, vio;
  const auto j = run_sim(board, vio, {"--duration", "3", "--speed", "2", "--fault", "hil-reorder:0.2@0.5+2", "--fault",
                                      "vio-reorder:0.2@0.5+2"});
  for (const auto& [name, got, link, message] :
       {std::tuple{"HIL", board.arrivals(), "hil_link_faults", "HIL_SENSOR"}, std::tuple{"VIO", vio.arrivals(), "vio_link_faults", "ODOMETRY"}}) {
    SCOPED_TRACE(name);
    uint64_t back = 0;
    std::set<uint64_t> seen;
    for (std::size_t i = 0; i < got.size(); ++i) {
      seen.insert(got[i].time_us);
      if (i == 0 || got[i].time_us >= got[i - 1].time_us) continue;
      ++back;
      EXPECT_EQ(got[i - 1].time_us - got[i].time_us, kStep_us) << "only a neighbour overtakes";
      EXPECT_TRUE(in_window(got[i].time_us, 0.5, 2.5 + 0.01)) << got[i].time_us;
    }
    std::printf("%s: %llu of %zu datagrams out of order at the receiver\n", name, static_cast<unsigned long long>(back), got.size());
    EXPECT_EQ(back, counted(j, link, "reordered_datagrams"));
    EXPECT_GT(back, 50u);  // p = 0.2 over 500 datagrams: about 80 (a swap takes two)
    EXPECT_LT(back, 125u);
    EXPECT_EQ(seen.size(), got.size()) << "each once";
    EXPECT_EQ(got.size(), sent(j, message)) << "none lost";
    EXPECT_EQ(counted(j, link, "dropped_datagrams"), 0u);
  }
}

// hil-dup / vio-dup: a datagram sent twice; the receiver sees each repeated time_usec once more, as
// many as the summary says it duplicated, only in the fault's window, and the copies are not counted as sent.
TEST(LinkFaultsE2E, DuplicateRepeatsDatagramsAtTheReceiverAsOftenAsTheSummaryCounts) {
  Receiver board, vio;
  const auto j = run_sim(board, vio, {"--duration", "3", "--speed", "2", "--fault", "hil-dup:0.3@0.5+2", "--fault",
                                      "vio-dup:0.3@0.5+2"});
  for (const auto& [name, got, link, message] :
       {std::tuple{"HIL", board.arrivals(), "hil_link_faults", "HIL_SENSOR"}, std::tuple{"VIO", vio.arrivals(), "vio_link_faults", "ODOMETRY"}}) {
    SCOPED_TRACE(name);
    uint64_t twice = 0;
    std::set<uint64_t> seen;
    for (std::size_t i = 0; i < got.size(); ++i) {
      if (seen.insert(got[i].time_us).second) continue;
      ++twice;
      EXPECT_EQ(got[i].time_us, got[i - 1].time_us) << "the copy right after its original";
      EXPECT_TRUE(in_window(got[i].time_us, 0.5, 2.5 + 0.01)) << got[i].time_us;
    }
    std::printf("%s: %llu of %zu datagrams twice at the receiver\n", name, static_cast<unsigned long long>(twice), got.size());
    EXPECT_EQ(twice, counted(j, link, "duplicated_datagrams"));
    EXPECT_GT(twice, 110u);  // p = 0.3 over 500 datagrams: 150, sigma 10
    EXPECT_LT(twice, 190u);
    EXPECT_EQ(seen.size(), sent(j, message)) << "the copies are not counted as sent";
    EXPECT_EQ(got.size(), sent(j, message) + twice);
  }
}

// hil-rate / vio-rate: the link carries at most this many datagrams a second; counted over the
// window's simulated time (the receiver's time_usec), at twice real time so that a limit on wall
// time would show as half the rate.
TEST(LinkFaultsE2E, RateLimitPassesTheSetRateOverSimulatedTimeAndTheSummaryCountsTheRest) {
  Receiver board, vio;
  const auto j = run_sim(board, vio, {"--duration", "3", "--speed", "2", "--vio-rate", "50", "--fault", "hil-rate:20@1+1.5",
                                      "--fault", "vio-rate:10@1+1.5"});
  for (const auto& [name, got, link, message, rate_hz, link_rate_hz] :
       {std::tuple{"HIL", board.arrivals(), "hil_link_faults", "HIL_SENSOR", 20.0, 250.0},
        std::tuple{"VIO", vio.arrivals(), "vio_link_faults", "ODOMETRY", 10.0, 50.0}}) {
    SCOPED_TRACE(name);
    int before = 0, during = 0, after = 0;
    for (const auto& a : got) {
      if (in_window(a.time_us, 0.5, 1.0)) ++before;
      if (in_window(a.time_us, 1.0, 2.5)) ++during;
      if (in_window(a.time_us, 2.5, 3.0)) ++after;
    }
    std::printf("%s: %d datagrams in the 1.5 s of hil/vio-rate:%g (%.1f per simulated second)\n", name, during, rate_hz,
                during / 1.5);
    EXPECT_NEAR(during / 1.5, rate_hz, 2.0 / 1.5) << "within a datagram of the bucket at either end";
    EXPECT_NEAR(before, link_rate_hz * 0.5, 1.0);
    EXPECT_NEAR(after, link_rate_hz * 0.5, 2.0);  // the last may still be in flight at the end
    EXPECT_EQ(counted(j, link, "dropped_datagrams") + static_cast<uint64_t>(during), static_cast<uint64_t>(link_rate_hz * 1.5));
    EXPECT_EQ(got.size(), sent(j, message));
  }
}

// hil-burst / vio-burst, vio-drop: what the receiver misses is what the summary counts as dropped,
// in the window only; burst loss comes in runs (Gilbert-Elliott's mean burst 1/p_good), a drop mostly alone.
TEST(LinkFaultsE2E, BurstAndDropLoseWhatTheSummaryCountsBurstsInRuns) {
  Receiver board, vio;
  const auto j = run_sim(board, vio, {"--duration", "3", "--speed", "2", "--fault", "hil-burst:0.1,0.25@0.5+2", "--fault",
                                      "vio-burst:0.1,0.25@0.5+1", "--fault", "vio-drop:0.3@1.7+0.8"});
  for (const auto& [name, got, link, message] :
       {std::tuple{"HIL", board.arrivals(), "hil_link_faults", "HIL_SENSOR"}, std::tuple{"VIO", vio.arrivals(), "vio_link_faults", "ODOMETRY"}}) {
    SCOPED_TRACE(name);
    uint64_t missing = 0, runs = 0, burst_missing = 0, burst_runs = 0;
    for (std::size_t i = 1; i < got.size(); ++i) {
      ASSERT_GT(got[i].time_us, got[i - 1].time_us);
      const uint64_t gap = (got[i].time_us - got[i - 1].time_us) / kStep_us - 1;
      if (gap == 0) continue;
      missing += gap;
      ++runs;
      EXPECT_TRUE(in_window(got[i - 1].time_us + kStep_us, 0.5, 2.5)) << got[i - 1].time_us;
      if (got[i].time_us <= 1'500'000 || std::string(name) == "HIL") burst_missing += gap, ++burst_runs;
    }
    const double mean_burst = burst_runs ? static_cast<double>(burst_missing) / static_cast<double>(burst_runs) : 0;
    std::printf("%s: %llu datagrams lost in %llu runs (bursts: %.2f datagrams on average)\n", name,
                static_cast<unsigned long long>(missing), static_cast<unsigned long long>(runs), mean_burst);
    EXPECT_EQ(missing, counted(j, link, "dropped_datagrams"));
    EXPECT_EQ(got.size(), sent(j, message));
    EXPECT_GT(mean_burst, 2.5);  // 1 / 0.25 = 4 (a drop alone would be 1)
  }
}

// hil-jitter / vio-jitter: each datagram leaves up to ms later, order kept. Against the simulated
// clock (speed 1), the arrival offset spreads from about nothing to about the setting: the receiver
// sees its low and high percentiles apart by more than half of it, and none later than it.
TEST(LinkFaultsE2E, JitterSpreadsArrivalsOverTheSettingAndKeepsTheOrder) {
  constexpr double kJitter_ms = 40;
  Receiver board, vio;
  const auto j = run_sim(board, vio, {"--duration", "3", "--speed", "1", "--vio-rate", "50", "--fault", "hil-jitter:40@1+1.5",
                                      "--fault", "vio-jitter:40@1+1.5"});
  for (const auto& [name, got, link, message] :
       {std::tuple{"HIL", board.arrivals(), "hil_link_faults", "HIL_SENSOR"}, std::tuple{"VIO", vio.arrivals(), "vio_link_faults", "ODOMETRY"}}) {
    SCOPED_TRACE(name);
    std::vector<double> base_ms, jittered_ms;
    for (std::size_t i = 0; i < got.size(); ++i) {
      if (i > 0) {
        EXPECT_GT(got[i].time_us, got[i - 1].time_us) << "order kept";
      }
      const double offset_ms = (got[i].wall_s - static_cast<double>(got[i].time_us) * 1e-6) * 1e3;
      if (in_window(got[i].time_us, 0.3, 0.95)) base_ms.push_back(offset_ms);
      if (in_window(got[i].time_us, 1.1, 2.4)) jittered_ms.push_back(offset_ms);
    }
    ASSERT_GT(base_ms.size(), 20u);
    ASSERT_GT(jittered_ms.size(), 50u);
    const double zero_ms = percentile(base_ms, 0.5);
    for (auto& v : jittered_ms) v -= zero_ms;
    const double low_ms = percentile(jittered_ms, 0.05), median_ms = percentile(jittered_ms, 0.5),
                 high_ms = percentile(jittered_ms, 0.95);
    std::printf("%s jitter:%g: added %.1f / %.1f / %.1f ms (5 / 50 / 95 %%), without it %.1f ms apart (5..95 %%)\n", name,
                kJitter_ms, low_ms, median_ms, high_ms, percentile(base_ms, 0.95) - percentile(base_ms, 0.05));
    EXPECT_GT(high_ms - low_ms, 0.4 * kJitter_ms) << "spread over the setting";
    EXPECT_GT(median_ms, 0.4 * kJitter_ms);
    EXPECT_LT(high_ms, kJitter_ms + 8.0) << "never later than the setting (and two ticks of a busy machine)";
    EXPECT_GT(low_ms, -2.0);
    EXPECT_EQ(got.size(), sent(j, message)) << "none lost";
    EXPECT_EQ(counted(j, link, "dropped_datagrams"), 0u);
  }
}

// hil-delay / vio-delay: each datagram leaves this much later; the median arrival against the
// simulated clock (speed 1) moves by the setting, within a millisecond, nothing lost, order kept.
TEST(LinkFaultsE2E, DelayMovesArrivalsByTheSettingWithinAMillisecond) {
  constexpr double kDelay_ms = 20;
  Receiver board, vio;
  const auto j = run_sim(board, vio, {"--duration", "2.5", "--speed", "1", "--vio-rate", "50", "--fault", "hil-delay:20@1+1",
                                      "--fault", "vio-delay:20@1+1"});
  for (const auto& [name, got, link, message] :
       {std::tuple{"HIL", board.arrivals(), "hil_link_faults", "HIL_SENSOR"}, std::tuple{"VIO", vio.arrivals(), "vio_link_faults", "ODOMETRY"}}) {
    SCOPED_TRACE(name);
    std::vector<double> base_ms, delayed_ms;
    for (std::size_t i = 0; i < got.size(); ++i) {
      if (i > 0) {
        EXPECT_GT(got[i].time_us, got[i - 1].time_us) << "order kept";
      }
      const double offset_ms = (got[i].wall_s - static_cast<double>(got[i].time_us) * 1e-6) * 1e3;
      if (in_window(got[i].time_us, 0.3, 0.95)) base_ms.push_back(offset_ms);
      if (in_window(got[i].time_us, 1.1, 1.9)) delayed_ms.push_back(offset_ms);
    }
    ASSERT_GT(base_ms.size(), 20u);
    ASSERT_GT(delayed_ms.size(), 30u);
    const double measured_ms = percentile(delayed_ms, 0.5) - percentile(base_ms, 0.5);
    std::printf("%s delay:%g measured %.2f ms at the receiver (median over %zu)\n", name, kDelay_ms, measured_ms, delayed_ms.size());
    EXPECT_NEAR(measured_ms, kDelay_ms, 1.0);
    EXPECT_EQ(got.size(), sent(j, message)) << "none lost";
    EXPECT_GE(counted(j, link, "delayed_datagrams"), delayed_ms.size());
  }
}

}  // namespace
}  // namespace hitl
