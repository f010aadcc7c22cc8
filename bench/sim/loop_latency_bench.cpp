// Loop latency at the board (docs/sim.md "Loop latency"), measured by the session itself against
// `hitl target`: hitl sim --json's loop_latency, and in lockstep the session's own share of each
// step (the step's wall time less the time spent waiting for the board's answer: physics, sensors,
// encoding, routing). Prints figures; asserts nothing.
// Usage: loop_latency_bench [SIM_SECONDS]   (default 20: lockstep --speed 0, then 5 s in real time)
#include <cstdio>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/support/process.h"

using namespace std::chrono_literals;

namespace {

nlohmann::json run(bool lockstep, double seconds) {
  const uint16_t hil = hitl::test::free_udp_port(), local = hitl::test::free_udp_port();
  std::vector<std::string> target{HITL_BINARY, "target", "--bind", "127.0.0.1", "--hil-port", std::to_string(hil),
                                  "--gcs-port", "0", "--vio-port", "0"};
  if (lockstep) target.push_back("--lockstep");
  hitl::test::Process board(target);
  board.wait_for_stderr("EMULATED", 10s);
  std::vector<std::string> sim{HITL_BINARY, "--json", "sim", "-i", "127.0.0.1", "--hil-port", std::to_string(hil),
                               "--local-port", std::to_string(local), "--no-vio", "--clients", "0",
                               "--duration", std::to_string(seconds)};
  if (lockstep) sim.insert(sim.end(), {"--lockstep", "--speed", "0"});
  hitl::test::Process p(sim);
  p.wait(600s);
  board.signal(2);
  board.wait(20s);
  const auto lines = p.out_lines();
  return lines.empty() ? nlohmann::json::object() : nlohmann::json::parse(lines.back());
}

void print(const char* what, const nlohmann::json& j) {
  if (!j.contains("loop_latency")) {
    std::printf("%s: no summary\n", what);
    return;
  }
  const auto& l = j["loop_latency"];
  std::printf("%s: %llu answered of %llu HIL_SENSORs: p50 %.1f us  p95 %.1f us  p99 %.1f us  max %.1f us  mean %.1f us\n", what,
              l["count"].get<unsigned long long>(), l["sensors"].get<unsigned long long>(), l["p50_us"].get<double>(),
              l["p95_us"].get<double>(), l["p99_us"].get<double>(), l["max_us"].get<double>(), l["mean_us"].get<double>());
  std::printf("  histogram:");
  for (const auto& b : l["histogram"])
    if (b["count"].get<uint64_t>() > 0)
      std::printf(" [%llu,%s us) %llu", b["lo_us"].get<unsigned long long>(),
                  b["hi_us"].is_null() ? "inf" : std::to_string(b["hi_us"].get<uint64_t>()).c_str(),
                  b["count"].get<unsigned long long>());
  std::printf("\n");
}

}  // namespace

int main(int argc, char** argv) {
  const double seconds = argc > 1 ? std::stod(argv[1]) : 20.0;
  const auto lockstep = run(true, seconds);
  print("lockstep --speed 0 against hitl target --lockstep", lockstep);
  if (lockstep.contains("steps") && lockstep["steps"].get<double>() > 0) {
    const double step_us = lockstep["wall_time_s"].get<double>() * 1e6 / lockstep["steps"].get<double>();
    const double waiting_us = lockstep["loop_latency"]["mean_us"].get<double>();
    std::printf("  per step: %.1f us of wall time, %.1f us waiting for the board's answer (mean), the session's own share "
                "%.1f us (%.0f %%); %.0f steps/s, %.0fx real time\n",
                step_us, waiting_us, step_us - waiting_us, 100.0 * (step_us - waiting_us) / step_us, 1e6 / step_us,
                lockstep["real_time_factor"].get<double>());
  }
  print("real time against hitl target (its 200 Hz stream, taken at the session's next 4 ms tick)", run(false, 5.0));
  return 0;
}
