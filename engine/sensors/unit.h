// A sensor unit: one sensor that sends its own MAVLink message, written as one type in one folder
// (engine/sensors/<name>/), as Drake adds a sensor as one System. The type holds every part of the
// sensor, and the SensorUnit concept below names them, so a unit that lacks one does not compile
// (GCC names the missing requirement):
//
//   kName, kSummary    "rangefinder": its key under `sensors` in the vehicle file, its `hitl sim
//                      --rangefinder` flag and its faults' prefix; the flag's one-line help
//   Config             its settings with their defaults (member initialisers), `enabled` (off by
//                      default: the flag or the vehicle file turns it on) and `rate_hz`
//   fields(v, config)  its vehicle-file keys, once, for reading and writing (config_fields.h)
//   check(config)      what the keys' ranges cannot say ("" when whole: min < max, ...)
//   without_noise(c)   the config with every noise set to zero (--no-noise)
//   U(config, world, seed), sample(state, t_s), reset()   the model: a sample from the vehicle's state
//   Faults, faults(), apply(faults, sample)   its faults: what is active folded into Faults by each
//                      catalogue entry's fold(), applied to what it reports (after the truth)
//   message(sample, time_usec) const   its wire encoding: one typed MAVLink message (base/mavlink)
//
// Registering it is one line in engine/sensors/units.h. The session samples it on its own schedule
// (absolute due times at rate_hz), applies its faults, and sends its message to the flight stack in
// the step's datagram; `hitl sim` gets its flag and docs/faults.md's catalogue its faults from there.
#pragma once

#include <concepts>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "engine/model/vehicle_state.h"
#include "engine/model/world_config.h"

namespace hitl::sensors {

/// One argument of a fault, with its unit in the name ("north_m", "pa_per_s") and its range. The
/// fault catalogue (engine/faults) uses the same type for every fault.
struct FaultArg {
  const char* name;
  double min;
  double max;
  bool integer = false;
};

/// One fault of a sensor unit: what the catalogue lists (docs/faults.md) and how it acts.
template <class Active>
struct UnitFault {
  const char* name;              ///< "rangefinder-stuck"
  std::vector<FaultArg> args;
  std::size_t required_args;     ///< the rest are optional
  const char* example;           ///< what follows the name in a typical use (":0.5", "" for none)
  const char* meaning;           ///< one line: what it does where
  /// Adds this fault (its `args`, active since `started_s`) to what is active at `t_s`.
  void (*fold)(Active& active, const std::vector<double>& args, double started_s, double t_s);
};

/// A field visitor that only collects key names: it checks at compile time that a unit's fields()
/// uses only the kinds of key the config files know, and lists them (the docs test).
struct KeyNames {
  std::vector<std::string> keys;
  template <class Range>
  void number(const char* key, double&, Range) { keys.emplace_back(key); }
  template <class Range>
  void integer(const char* key, int&, Range) { keys.emplace_back(key); }
  void boolean(const char* key, bool&) { keys.emplace_back(key); }
  template <class Vec3, class Range>
  void vec3(const char* key, Vec3&, Range) { keys.emplace_back(key); }
};

template <class U>
concept SensorUnit =
    std::constructible_from<U, const typename U::Config&, const model::WorldConfig&, std::uint64_t> &&
    std::default_initializable<typename U::Config> && std::default_initializable<typename U::Faults> &&
    requires(U unit, const U& const_unit, typename U::Config config, KeyNames keys, const model::VehicleState& state, double t_s,
             typename U::Sample sample, const typename U::Faults& faults, std::uint64_t time_usec) {
      { U::kName } -> std::convertible_to<std::string_view>;
      { U::kSummary } -> std::convertible_to<std::string_view>;
      { config.enabled } -> std::convertible_to<bool>;
      { config.rate_hz } -> std::convertible_to<double>;
      U::fields(keys, config);
      { U::check(config) } -> std::convertible_to<std::string>;
      { U::without_noise(config) } -> std::same_as<typename U::Config>;
      { unit.sample(state, t_s) } -> std::same_as<typename U::Sample>;
      unit.reset();
      unit.apply(faults, sample);
      { U::faults() } -> std::convertible_to<const std::vector<UnitFault<typename U::Faults>>&>;
      { const_unit.message(sample, time_usec).kName } -> std::convertible_to<std::string_view>;  // a typed MAVLink message
    };

/// A unit checked on its own, so that the compiler's note names the part it lacks.
template <class U>
consteval bool whole_unit() {
  static_assert(SensorUnit<U>, "a registered sensor unit lacks a part of engine/sensors/unit.h (the note below names it)");
  return true;
}

/// The registered units (engine/sensors/units.h); each must be a whole SensorUnit.
template <class... U>
struct UnitList {
  static constexpr bool kWhole = (whole_unit<U>() && ...);
};

}  // namespace hitl::sensors
