#include "engine/campaign/flight.h"

#include <cstdio>

namespace hitl::campaign {

namespace {

std::string number_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

}  // namespace

std::string stable_id(const std::string& text) {
  uint64_t hash = 0xcbf29ce484222325ULL;  // FNV-1a 64: offset basis and prime
  for (const unsigned char c : text) {
    hash ^= c;
    hash *= 0x100000001b3ULL;
  }
  char out[17];
  std::snprintf(out, sizeof out, "%012llx", static_cast<unsigned long long>(hash >> 16));
  return out;
}

std::string flight_parameters(const Campaign& campaign, const Flight& flight) {
  std::string p = "stack=" + std::string(to_string(campaign.stack));
  if (campaign.px4 && !campaign.px4->params.empty()) {  // PX4's build is not: the same flight against a new PX4 keeps its id
    p += "\npx4_params=";
    for (const auto& param : campaign.px4->params) p += param.name + "=" + param.value + ";";
  }
  p += "\ntrajectory=" + flight.trajectory->as_written;
  p += "\nfaults=";
  for (const auto& spec : flight.fault_case->faults) p += spec.text() + ";";
  if (!flight.fault_case->scenario_as_written.empty()) p += "\nscenario=" + flight.fault_case->scenario_as_written;
  p += "\nseed=" + std::to_string(flight.seed);
  p += "\nspeed=" + number_text(flight.speed);
  p += "\nsim_limit_s=" + number_text(campaign.sim_limit_s);
  return p;
}

std::vector<Flight> expand(const Campaign& campaign) {
  std::vector<Flight> flights;
  const bool speeds_named = campaign.speeds.size() > 1 || (campaign.speeds.size() == 1 && campaign.speeds[0] != 0);
  for (const auto& trajectory : campaign.trajectories)
    for (const auto& fault_case : campaign.fault_cases)
      for (const uint64_t seed : campaign.seeds)
        for (const double speed : campaign.speeds) {
          Flight f;
          f.index = flights.size();
          f.trajectory = &trajectory;
          f.fault_case = &fault_case;
          f.seed = seed;
          f.speed = speed;
          f.name = trajectory.name + "/" + fault_case.name + "/seed-" + std::to_string(seed);
          if (speeds_named) f.name += "/x" + number_text(speed);
          f.id = stable_id(flight_parameters(campaign, f));
          flights.push_back(std::move(f));
        }
  return flights;
}

}  // namespace hitl::campaign
