#include "engine/sensors/unit_set.h"

namespace hitl::sensors {

std::vector<UnitInfo> unit_infos() {
  std::vector<UnitInfo> out;
  for_each_unit([&](auto i) { out.push_back({UnitAt<decltype(i)::value>::kName, UnitAt<decltype(i)::value>::kSummary}); });
  return out;
}

void enable_unit(UnitConfigs& configs, std::size_t index) {
  for_each_unit([&](auto i) {
    if (decltype(i)::value == index) std::get<decltype(i)::value>(configs).enabled = true;
  });
}

bool unit_enabled(const UnitConfigs& configs, std::size_t index) {
  bool on = false;
  for_each_unit([&](auto i) {
    if (decltype(i)::value == index) on = std::get<decltype(i)::value>(configs).enabled;
  });
  return on;
}

UnitConfigs without_noise(UnitConfigs configs) {
  for_each_unit([&](auto i) { std::get<decltype(i)::value>(configs) = UnitAt<decltype(i)::value>::without_noise(std::get<decltype(i)::value>(configs)); });
  return configs;
}

const std::vector<UnitFaultInfo>& unit_fault_infos() {
  static const std::vector<UnitFaultInfo> infos = [] {
    std::vector<UnitFaultInfo> out;
    for_each_unit([&](auto i) {
      for (const auto& f : UnitAt<decltype(i)::value>::faults()) out.push_back({decltype(i)::value, f.name, f.args, f.required_args, f.example, f.meaning});
    });
    return out;
  }();
  return infos;
}

std::string unit_off_for_fault(const UnitConfigs& configs, std::size_t fault) {
  const std::size_t unit = unit_fault_infos().at(fault).unit;
  if (unit_enabled(configs, unit)) return "";
  const std::string name = unit_infos()[unit].name;
  return "the " + name + " is off; turn it on with --" + name + " (or \"enabled\": true in the vehicle file's sensors." + name + ")";
}

void fold_unit_fault(UnitFaults& active, std::size_t fault, const std::vector<double>& args, double started_s, double t_s) {
  std::size_t first = 0;  // the flat index of this unit's first fault
  for_each_unit([&](auto i) {
    const auto& table = UnitAt<decltype(i)::value>::faults();
    if (fault >= first && fault < first + table.size()) table[fault - first].fold(std::get<decltype(i)::value>(active), args, started_s, t_s);
    first += table.size();
  });
}

UnitSet::UnitSet(const UnitConfigs& configs, const model::WorldConfig& world, std::uint64_t seed, double first_due_s)
    : first_due_s_(first_due_s) {
  for_each_unit([&](auto i) {
    const auto& config = std::get<decltype(i)::value>(configs);
    schedules_.emplace_back(config.rate_hz);
    if (!config.enabled) return;
    std::get<decltype(i)::value>(models_).emplace(config, world, seed);
    any_enabled_ = true;
  });
}

UnitSamples UnitSet::sample_due(const model::VehicleState& state, const UnitFaults& faults) {
  UnitSamples samples;
  if (!any_enabled_ || state.time_s + 1e-9 < first_due_s_) return samples;
  for_each_unit([&](auto i) {
    auto& model = std::get<decltype(i)::value>(models_);
    if (!model || !schedules_[decltype(i)::value].due(state.time_s)) return;
    auto sample = model->sample(state, state.time_s);
    model->apply(std::get<decltype(i)::value>(faults), sample);
    std::get<decltype(i)::value>(samples) = sample;
  });
  return samples;
}

void UnitSet::reset() {
  for_each_unit([&](auto i) {
    if (auto& model = std::get<decltype(i)::value>(models_)) model->reset();
    schedules_[decltype(i)::value].reset();
  });
}

}  // namespace hitl::sensors
