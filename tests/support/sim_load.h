// Load against a real `hitl sim` (loopback only): many clients on its client port, each sending a
// HEARTBEAT every few seconds, and a flood of datagrams (valid frames and junk) to the client port
// from one of those clients and to the HIL port from a stranger; meanwhile a receiver plays the
// board and times every HIL_SENSOR. Bounded in count and time. Used by tests/cli/sim_load_test
// (generous floors) and bench/sim/sim_load_bench (the strict figure).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace hitl::test {

struct SimLoadConfig {
  int clients = 2000;
  uint64_t flood_datagrams = 200000;  ///< half to the client port, half to the HIL port
  double measure_s = 6.0;             ///< HIL_SENSOR rate measured over this long, load running
  double heartbeat_period_s = 3.0;    ///< each client's HEARTBEAT
  std::vector<std::string> extra_args;  ///< appended to `hitl sim`
};

struct SimLoadResult {
  int exit_code = -1;
  std::string err;                   ///< hitl sim's stderr
  nlohmann::json summary;            ///< its final --json line
  std::vector<double> per_second_hz; ///< HIL_SENSOR received per one-second window
  double worst_1s_rate_hz = 0;
  double max_gap_s = 0;              ///< longest time between two HIL_SENSOR at the receiver
  uint64_t sensors = 0;              ///< HIL_SENSOR received in the measured window
  uint64_t flood_sent = 0;
  double flood_s = 0;                ///< how long sending the flood took
  int clients_opened = 0;
};

SimLoadResult run_sim_load(const SimLoadConfig& config);

}  // namespace hitl::test
