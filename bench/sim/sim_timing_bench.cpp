// Timing of a real `hitl sim` session, measured from outside as a board sees it:
//  - HIL_SENSOR inter-arrival at the receiver (kernel receive timestamps): mean, std, p99, max
//  - CPU of the session process (utime + stime over the run) and its peak resident memory
//  - actuator-in to sensor-out latency: a HIL_ACTUATOR_CONTROLS sent, to the next HIL_SENSOR back
//  - --speed 0 --lockstep with an answering peer: steps per second (real-time factor)
// Prints figures; asserts nothing.   Usage: sim_timing_bench [SECONDS [EXTRA hitl sim ARGS...]]
// e.g. sim_timing_bench 20 --realtime
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numeric>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "base/mavlink/frame_parser.h"
#include "base/mavlink/messages.h"
#include "tests/support/mavlink_peer.h"
#include "tests/support/process.h"

using namespace std::chrono_literals;
namespace msg = hitl::mavlink::msg;

namespace {

struct ProcUsage {
  double cpu_s = 0;
  long rss_peak_kb = 0;
};

ProcUsage usage_of(int pid) {
  ProcUsage u;
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  std::getline(stat, line);
  std::istringstream ss(line.substr(line.rfind(')') + 2));
  std::vector<std::string> f((std::istream_iterator<std::string>(ss)), std::istream_iterator<std::string>());
  if (f.size() > 13) u.cpu_s = (std::stod(f[11]) + std::stod(f[12])) / static_cast<double>(sysconf(_SC_CLK_TCK));
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  while (std::getline(status, line))
    if (line.rfind("VmHWM:", 0) == 0) u.rss_peak_kb = std::stol(line.substr(6));
  return u;
}

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(q * static_cast<double>(v.size())))];
}

void summarize(const char* what, const std::vector<double>& v_us) {
  if (v_us.size() < 2) {
    std::printf("%s: too few samples\n", what);
    return;
  }
  const double mean = std::accumulate(v_us.begin(), v_us.end(), 0.0) / static_cast<double>(v_us.size());
  double var = 0;
  for (double x : v_us) var += (x - mean) * (x - mean);
  const double std_us = std::sqrt(var / static_cast<double>(v_us.size() - 1));
  std::printf("%-44s n %6zu  mean %8.1f us  std %6.1f us  p50 %8.1f  p99 %8.1f  max %8.1f us\n", what, v_us.size(), mean,
              std_us, percentile(v_us, 0.5), percentile(v_us, 0.99), *std::max_element(v_us.begin(), v_us.end()));
}

int pid_of(hitl::test::Process& p) { return p.pid(); }

}  // namespace

int main(int argc, char** argv) {
  const double seconds = argc > 1 ? std::atof(argv[1]) : 20.0;
  const auto set = hitl::mavlink::MessageSet::compiled();

  // 1. Real time: jitter at the receiver, CPU, memory, latency.
  {
    const uint16_t board_port = hitl::test::free_udp_port();
    const uint16_t sim_port = hitl::test::free_udp_port();
    hitl::test::MavlinkPeer board(board_port, sim_port);
    std::vector<std::string> args{hitl::test::hitl_binary(), "-q", "sim", "-i", "127.0.0.1", "--hil-port", std::to_string(board_port),
                                  "--local-port", std::to_string(sim_port), "--no-vio", "--clients", "0", "--duration",
                                  std::to_string(seconds)};
    for (int i = 2; i < argc; ++i) args.emplace_back(argv[i]);
    hitl::test::Process sim(args);
    hitl::mavlink::FrameParser parser(set);
    std::vector<double> gaps_us, latency_us;
    int64_t last_ns = 0;
    int64_t pending_actuator_ns = 0;
    int n = 0;
    const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds + 5);
    auto& ep = board.endpoint();
    ProcUsage start_usage{};
    bool started = false;
    bool reported = false;
    while (std::chrono::steady_clock::now() < until && sim.running()) {
      if (!ep.wait_readable(50)) continue;
      while (auto d = ep.receive()) {
        parser.parse_datagram(d->bytes, [&](const hitl::mavlink::Frame& f) {
          if (!f.is<msg::HilSensor>()) return;
          if (!started) {
            started = true;
            start_usage = usage_of(pid_of(sim));
          }
          if (last_ns != 0 && n > 250) gaps_us.push_back(static_cast<double>(d->rx_time_unix_ns - last_ns) / 1000.0);
          last_ns = d->rx_time_unix_ns;
          if (pending_actuator_ns != 0) {
            latency_us.push_back(static_cast<double>(d->rx_time_unix_ns - pending_actuator_ns) / 1000.0);
            pending_actuator_ns = 0;
          }
          // Answer every 5th sensor, at a random point in the step, like a 200 Hz board would.
          if (++n % 5 == 0) {
            std::this_thread::sleep_for(std::chrono::microseconds(std::rand() % 3500));
            msg::HilActuatorControls a;
            a.flags = 0x0F;
            board.send(a);
            pending_actuator_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(
                                      std::chrono::system_clock::now().time_since_epoch())
                                      .count();
          }
        });
      }
      if (started && n >= static_cast<int>(seconds * 250) - 25 && !reported) {
        reported = true;
        const auto end_usage = usage_of(pid_of(sim));
        const double span_s = static_cast<double>(n) / 250.0;
        std::printf("hitl sim at real time for %.0f s (this machine, loopback, a noisy 2-core VM):\n", seconds);
        std::printf("  CPU %.2f %% of one core, peak RSS %.1f MB\n", 100.0 * (end_usage.cpu_s - start_usage.cpu_s) / span_s,
                    static_cast<double>(end_usage.rss_peak_kb) / 1024.0);
        std::fflush(stdout);
      }
    }
    sim.wait(10s);
    summarize("  HIL_SENSOR inter-arrival at the receiver", gaps_us);
    summarize("  actuator-in to next sensor-out latency", latency_us);
  }

  // 2. As fast as possible in lockstep with an answering peer.
  {
    const uint16_t board_port = hitl::test::free_udp_port();
    const uint16_t sim_port = hitl::test::free_udp_port();
    hitl::test::MavlinkPeer board(board_port, sim_port);
    hitl::test::Process sim({hitl::test::hitl_binary(), "--json", "sim", "-i", "127.0.0.1", "--hil-port", std::to_string(board_port),
                             "--local-port", std::to_string(sim_port), "--no-vio", "--clients", "0", "--duration", "60",
                             "--speed", "0", "--lockstep"});
    hitl::mavlink::FrameParser parser(set);
    auto& ep = board.endpoint();
    while (sim.running()) {
      if (!ep.wait_readable(50)) continue;
      while (auto d = ep.receive())
        parser.parse_datagram(d->bytes, [&](const hitl::mavlink::Frame& f) {
          if (f.is<msg::HilSensor>()) board.send(msg::HilActuatorControls{});
        });
    }
    sim.wait(10s);
    const auto lines = sim.out_lines();
    if (!lines.empty()) {
      const auto j = nlohmann::json::parse(lines.back());
      std::printf("hitl sim --speed 0 --lockstep, a loopback peer answering each HIL_SENSOR:\n");
      std::printf("  60 s simulated in %.2f s wall: real-time factor %.1f, %.0f steps/s, lockstep fallbacks %d\n",
                  j["wall_time_s"].get<double>(), j["real_time_factor"].get<double>(),
                  j["steps"].get<double>() / j["wall_time_s"].get<double>(), j["lockstep"]["fallbacks"].get<int>());
    }
  }
  return 0;
}
