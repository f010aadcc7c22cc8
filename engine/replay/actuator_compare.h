// How a board's actuator outputs in a replay differ from the recording's: per motor the largest
// and the RMS difference over the steps both have, and the first step where any motor differs by
// more than a tolerance. Steps are matched by the time_usec echo when the recording's answers echo
// their HIL_SENSOR (lockstep), else by step: the controls in effect at each step (the last answer
// that arrived by then, as the simulator flies on them). Pure.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "engine/replay/recorded_session.h"

namespace hitl::replay {

struct MotorDifference {
  double max_abs = 0;
  double rms = 0;
};

struct Divergence {
  double t_s = 0;        ///< the step's simulated time (its HIL_SENSOR's time_usec)
  int motor = 0;
  double recorded = 0;
  double replayed = 0;
};

struct ActuatorComparison {
  bool by_echo = false;           ///< matched by time_usec (lockstep), else by step
  uint64_t steps_compared = 0;    ///< steps with an answer in both
  uint64_t missing = 0;           ///< steps answered in the recording but not in the replay
  std::array<MotorDifference, 4> motors{};
  std::optional<Divergence> first_divergence;  ///< none: within the tolerance throughout
  bool identical() const { return !first_divergence && missing == 0; }
};

/// `steps`: the recording's steps (their times); `recorded` and `replayed`: the answers, each with
/// the step it arrived in. A motor differs when |recorded - replayed| > tolerance (0: any bit).
ActuatorComparison compare_actuators(const std::vector<RecordedStep>& steps, const std::vector<ActuatorSample>& recorded,
                                     const std::vector<ActuatorSample>& replayed, double tolerance);

}  // namespace hitl::replay
