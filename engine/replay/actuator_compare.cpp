#include "engine/replay/actuator_compare.h"

#include <cmath>
#include <unordered_map>
#include <unordered_set>

namespace hitl::replay {
namespace {

using Controls = std::array<float, 4>;

/// The answer for each step: by echo, the last answer stamped with the step's time; by step, the
/// last that arrived by then (in it, or held from an earlier step).
std::vector<std::optional<Controls>> per_step(const std::vector<RecordedStep>& steps, const std::vector<ActuatorSample>& answers,
                                              bool by_echo) {
  std::vector<std::optional<Controls>> out(steps.size());
  if (by_echo) {
    std::unordered_map<uint64_t, std::size_t> index;
    for (std::size_t k = 0; k < steps.size(); ++k) index.emplace(steps[k].sensor_time_usec, k);
    for (const auto& a : answers)
      if (auto it = index.find(a.time_usec); it != index.end()) out[it->second] = a.controls;
  } else {  // a board on its own clock: the controls in effect at each step, held until the next answer
    for (const auto& a : answers)
      if (a.step >= 0 && static_cast<std::size_t>(a.step) < out.size()) out[static_cast<std::size_t>(a.step)] = a.controls;
    for (std::size_t k = 1; k < out.size(); ++k)
      if (!out[k]) out[k] = out[k - 1];
  }
  return out;
}

bool echoes(const std::vector<RecordedStep>& steps, const std::vector<ActuatorSample>& answers) {
  if (answers.empty()) return false;
  std::unordered_set<uint64_t> times;
  for (const auto& s : steps) times.insert(s.sensor_time_usec);
  std::size_t echoed = 0;
  for (const auto& a : answers) echoed += times.count(a.time_usec);
  return echoed * 10 >= answers.size() * 9;  // nine in ten: a lockstep recording (the rest: before the first step)
}

}  // namespace

ActuatorComparison compare_actuators(const std::vector<RecordedStep>& steps, const std::vector<ActuatorSample>& recorded,
                                     const std::vector<ActuatorSample>& replayed, double tolerance) {
  ActuatorComparison c;
  c.by_echo = echoes(steps, recorded);
  const auto before = per_step(steps, recorded, c.by_echo);
  const auto now = per_step(steps, replayed, c.by_echo);
  std::array<double, 4> sum_sq{};
  for (std::size_t k = 0; k < steps.size(); ++k) {
    if (!before[k]) continue;
    if (!now[k]) {
      ++c.missing;
      continue;
    }
    ++c.steps_compared;
    for (int i = 0; i < 4; ++i) {
      const double r = (*before[k])[static_cast<std::size_t>(i)], p = (*now[k])[static_cast<std::size_t>(i)];
      const double d = std::fabs(r - p);
      const bool differs = !(d <= tolerance) && !(std::isnan(r) && std::isnan(p));
      auto& m = c.motors[static_cast<std::size_t>(i)];
      if (std::isfinite(d)) {
        m.max_abs = std::max(m.max_abs, d);
        sum_sq[static_cast<std::size_t>(i)] += d * d;
      }
      if (differs && !c.first_divergence)
        c.first_divergence = Divergence{static_cast<double>(steps[k].sensor_time_usec) * 1e-6, i, r, p};
    }
  }
  for (std::size_t i = 0; i < 4; ++i)
    c.motors[i].rms = c.steps_compared ? std::sqrt(sum_sq[i] / static_cast<double>(c.steps_compared)) : 0.0;
  return c;
}

}  // namespace hitl::replay
