// What the engine does with the registered sensor units (units.h), generically: their settings,
// flags and faults as lists, and UnitSet, the enabled units' models on their schedules. Nothing
// here names a unit: a new one is picked up from its registration line.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "engine/model/vehicle_state.h"
#include "engine/model/world_config.h"
#include "engine/sensors/scheduler.h"
#include "engine/sensors/units.h"

namespace hitl::sensors {

namespace detail {
template <class List>
struct UnitTypes;
template <class... U>
struct UnitTypes<UnitList<U...>> {
  static_assert(UnitList<U...>::kWhole);
  using Units = std::tuple<U...>;
  using Configs = std::tuple<typename U::Config...>;
  using Samples = std::tuple<std::optional<typename U::Sample>...>;
  using Faults = std::tuple<typename U::Faults...>;
  using Models = std::tuple<std::optional<U>...>;
  static constexpr std::size_t kCount = sizeof...(U);
};
}  // namespace detail

using UnitTypes = detail::UnitTypes<SensorUnits>;
/// Unit I of the registration.
template <std::size_t I>
using UnitAt = std::tuple_element_t<I, UnitTypes::Units>;

/// Calls f(std::integral_constant<std::size_t, I>{}) for every unit I, in registration order.
template <class F>
void for_each_unit(F&& f) {
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    (f(std::integral_constant<std::size_t, I>{}), ...);
  }(std::make_index_sequence<UnitTypes::kCount>{});
}

/// Every unit's settings: the vehicle file's `sensors.<name>` sections (vehicle_file.h).
using UnitConfigs = UnitTypes::Configs;
/// The samples one step took (none for a unit that was off or not due), after their faults.
using UnitSamples = UnitTypes::Samples;
/// What is active of every unit's faults (engine/faults folds them in ActiveFaults::units).
using UnitFaults = UnitTypes::Faults;

/// A unit as the command line shows it: `--<name>` turns it on.
struct UnitInfo {
  std::string name;     ///< "rangefinder"
  std::string summary;  ///< the flag's help
};
std::vector<UnitInfo> unit_infos();
/// Turns unit `index` (of unit_infos()) on.
void enable_unit(UnitConfigs& configs, std::size_t index);
bool unit_enabled(const UnitConfigs& configs, std::size_t index);
/// Every unit's noise set to zero (--no-noise).
UnitConfigs without_noise(UnitConfigs configs);

/// Every unit's faults in registration order: the fault catalogue (engine/faults) appends them.
struct UnitFaultInfo {
  std::size_t unit = 0;  ///< of unit_infos()
  const char* name = "";
  std::vector<FaultArg> args;
  std::size_t required_args = 0;
  const char* example = "";
  const char* meaning = "";
};
const std::vector<UnitFaultInfo>& unit_fault_infos();
/// "" when fault `fault`'s unit is on, else why it cannot act: "the rangefinder is off; turn it on
/// with --rangefinder (...)".
std::string unit_off_for_fault(const UnitConfigs& configs, std::size_t fault);
/// Adds fault `fault` (of unit_fault_infos()) with its args, active since started_s, to `active`.
void fold_unit_fault(UnitFaults& active, std::size_t fault, const std::vector<double>& args, double started_s, double t_s);

/// The enabled units, each sampled at its own rate on absolute due times (scheduler.h), none
/// before `first_due_s` (the first IMU period, as the other sensors), with its faults applied.
class UnitSet {
 public:
  UnitSet(const UnitConfigs& configs, const model::WorldConfig& world, std::uint64_t seed, double first_due_s);
  /// The samples due at state.time_s.
  UnitSamples sample_due(const model::VehicleState& state, const UnitFaults& faults);
  void reset();
  bool any_enabled() const { return any_enabled_; }

  /// Calls send(message) with each sample's MAVLink message (a different type per unit).
  template <class Send>
  void send(const UnitSamples& samples, std::uint64_t time_usec, Send&& send) const {
    for_each_unit([&](auto i) {
      const auto& model = std::get<decltype(i)::value>(models_);
      const auto& sample = std::get<decltype(i)::value>(samples);
      if (model && sample) send(model->message(*sample, time_usec));
    });
  }

 private:
  UnitTypes::Models models_;
  std::vector<PeriodicSchedule> schedules_;  ///< per unit (unused for one that is off)
  double first_due_s_;
  bool any_enabled_ = false;
};

}  // namespace hitl::sensors
