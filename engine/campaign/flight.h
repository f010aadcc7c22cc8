// One flight of a campaign: a point of its matrix, with a stable id (a hash of its parameters, so
// the same flight keeps its id and its results folder when the file grows), and the matrix
// expanded into flights in a fixed order (trajectory, then fault case, then seed, then speed).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "engine/campaign/campaign_file.h"

namespace hitl::campaign {

struct Flight {
  std::size_t index = 0;     ///< its place in the expanded matrix (`--only INDEX`)
  std::string id;            ///< 12 hex digits: FNV-1a 64 of its parameters (stable_id)
  std::string name;          ///< "square/gps-loss/seed-2" (with "/x10" when the file names speeds)
  const TrajectoryValue* trajectory = nullptr;
  const FaultCase* fault_case = nullptr;
  uint64_t seed = 1;
  double speed = 0;
};

/// The flights of the matrix, each with its index and id. The campaign must outlive them.
std::vector<Flight> expand(const Campaign& campaign);

/// The parameters that make a flight what it is, as one canonical text (hashed into its id): the
/// stack, the trajectory as written, the fault case's specs and scenario, the seed, the speed and
/// the simulated-time limit. The campaign's name and the flight's index are not part of it.
std::string flight_parameters(const Campaign& campaign, const Flight& flight);
/// FNV-1a 64 of `text`, as 12 lowercase hex digits (48 bits).
std::string stable_id(const std::string& text);

}  // namespace hitl::campaign
