// hitl sim under load, the strict figure: N clients each sending a HEARTBEAT every 3 s to the
// client port and a flood of datagrams (valid HEARTBEATs and junk, half to the client port from
// one of the clients, half to the HIL port from a stranger), while a receiver playing the board
// counts HIL_SENSOR per one-second window. Prints the windows and the worst (goal: >= 245 Hz).
// Usage: sim_load_bench [CLIENTS [FLOOD_DATAGRAMS [SECONDS [EXTRA hitl sim ARGS...]]]]
#include <cstdio>
#include <cstdlib>
#include <string>

#include "tests/support/sim_load.h"

int main(int argc, char** argv) {
  hitl::test::SimLoadConfig c;
  if (argc > 1) c.clients = std::atoi(argv[1]);
  if (argc > 2) c.flood_datagrams = std::strtoull(argv[2], nullptr, 10);
  if (argc > 3) c.measure_s = std::atof(argv[3]);
  for (int i = 4; i < argc; ++i) c.extra_args.emplace_back(argv[i]);
  const auto r = hitl::test::run_sim_load(c);
  std::printf("hitl sim under load: %d clients (HEARTBEAT every %.0f s), flood of %llu datagrams sent in %.2f s\n",
              r.clients_opened, c.heartbeat_period_s, static_cast<unsigned long long>(r.flood_sent), r.flood_s);
  std::printf("HIL_SENSOR per one-second window:");
  for (const double hz : r.per_second_hz) std::printf(" %.0f", hz);
  std::printf("\nworst one-second rate: %.0f Hz (goal >= 245), longest gap %.1f ms, exit %d\n", r.worst_1s_rate_hz,
              r.max_gap_s * 1000, r.exit_code);
  if (r.summary.is_object())
    std::printf("session: clients %s, clients_refused %s, client_frames_dropped %s, ignored other_address %s, late ticks %s\n",
                r.summary.value("clients", nlohmann::json()).dump().c_str(),
                r.summary.value("clients_refused", nlohmann::json()).dump().c_str(),
                r.summary.value("client_frames_dropped", nlohmann::json()).dump().c_str(),
                r.summary["ignored"].value("other_address", nlohmann::json()).dump().c_str(),
                r.summary.value("late_ticks", nlohmann::json()).dump().c_str());
  if (r.exit_code != 0) std::fprintf(stderr, "%s", r.err.c_str());
  return r.exit_code == 0 ? 0 : 1;
}
