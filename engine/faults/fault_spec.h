// A fault: what goes wrong, with its parameters in units, when (simulated seconds) and for how
// long. The catalogue names each kind, its arguments with their units and ranges, and what it means
// physically (docs/faults.md is its reference). Specs come from `--fault NAME[:ARGS][@T[+DUR]]` and
// from scenario files (scenario.h); the session's FaultSchedule (fault_schedule.h) starts and ends them.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/common/expected.h"
#include "engine/sensors/unit.h"

namespace hitl::faults {

enum class FaultKind {
  GpsLoss,     ///< no HIL_GPS sent
  GpsJump,     ///< the GPS position offset north/east (spoofing, a multipath jump)
  GpsDegrade,  ///< fix_type, satellites and eph/epv reported as given
  ImuBias,     ///< accelerometer bias step, body FRD, m/s^2
  GyroBias,    ///< gyro bias step, body FRD, rad/s
  MagOffset,   ///< magnetometer offset (a current near the sensor), body FRD, gauss
  BaroDrift,   ///< barometer pressure drifting at a rate, Pa/s
  Motor,       ///< motor i's thrust and torques x k (the model: engine/model)
  VioLoss,     ///< no ODOMETRY to the VIO server
  HilDrop,     ///< each outgoing HIL datagram dropped with probability p (seeded)
  HilDelay,    ///< each outgoing HIL datagram held back this long
  ImuNoise,      ///< the IMU's errors against truth (noise, bias walk) x k
  ImuStuck,      ///< the IMU repeats its last reading
  ImuClip,       ///< the IMU clips at a smaller full scale, m/s^2 and rad/s
  ImuVibration,  ///< a sinusoidal acceleration at the IMU, m/s^2 at Hz
  MagStuck,      ///< the magnetometer repeats its last reading
  MagScale,      ///< the magnetometer's reading x k
  BaroOffset,    ///< the static pressure offset, Pa
  BaroStuck,     ///< the barometer repeats its last reading
  GpsDrift,      ///< the GPS position walks away at a rate, m/s north and east (slow spoofing)
  GpsNoise,      ///< the GPS's position and velocity errors x k
  PropDamage,      ///< motor i's thrust and torques x k plus a once-per-revolution vibration at the IMU
  Payload,         ///< added mass hanging at the base origin, kg
  Wind,            ///< added steady wind, NED m/s
  Gust,            ///< a 1-cosine gust of this peak over the fault's duration, NED m/s
  Turbulence,      ///< added Gauss-Markov turbulence, sigma m/s and correlation time s
  ActuatorsStale,  ///< the board's actuator stream stale: the model holds the last commands
  VioDrift,        ///< the VIO position walks away at a rate, NED m/s
  VioJump,         ///< the VIO position jumps (reset_counter incremented at start and end), NED m
  VioQuality,      ///< ODOMETRY's quality field reports this percentage
  // the links' faults beyond drop and delay; each on the HIL link (to the flight stack) and the VIO link
  HilBurst, HilJitter, HilReorder, HilDuplicate, HilRate,
  VioDrop, VioDelay, VioBurst, VioJitter, VioReorder, VioDuplicate, VioRate,
  /// A sensor unit's fault (engine/sensors/unit.h): its folder names it and says what it does;
  /// FaultSpec::unit_fault says which. Stays last.
  SensorUnit,
};
/// How many kinds there are (SensorUnit is the last).
inline constexpr std::size_t kFaultKinds = static_cast<std::size_t>(FaultKind::SensorUnit) + 1;

/// Where a fault happens, for listing them by kind (the dashboard's fault menu), in this order.
enum class FaultGroup { Vehicle, Imu, Mag, Baro, Gps, OptionalSensors, Vio, Environment, HilLink, VioLink, Board };
/// "vehicle", "IMU", "mag", "baro", "GPS", "optional sensors" (the sensor units'), "VIO",
/// "environment", "HIL link", "VIO link", "board"
const char* to_string(FaultGroup group);
constexpr FaultGroup kFaultGroups[] = {FaultGroup::Vehicle,     FaultGroup::Imu,     FaultGroup::Mag,
                                       FaultGroup::Baro,        FaultGroup::Gps,     FaultGroup::OptionalSensors,
                                       FaultGroup::Vio,         FaultGroup::Environment, FaultGroup::HilLink,
                                       FaultGroup::VioLink,     FaultGroup::Board};

/// An argument with its unit in the name ("north_m", "pa_per_s") and its range; one type for every
/// fault, the sensor units' too (they sit below engine/faults, so it is defined with them).
using FaultArg = sensors::FaultArg;

struct FaultInfo {
  FaultKind kind;
  FaultGroup group;
  const char* name;  ///< "gps-loss"
  std::vector<FaultArg> args;
  std::size_t required_args;  ///< the rest are optional
  /// What follows the name in a typical use, as typed live (`:2,0.75`, `:5,0+6`, "" for none):
  /// values known to show an effect (bench/faults/fault_matrix.sh flies them); the dashboard's
  /// fault menu starts from it.
  const char* example;
  const char* meaning;        ///< one line: what it does where
  bool needs_duration = false;  ///< its shape spans its duration (gust)
  std::size_t unit_fault = 0;   ///< SensorUnit: which (of sensors::unit_fault_infos())
};

/// Every fault the simulator knows, in the order docs/faults.md lists them; the sensor units'
/// (engine/sensors/units.h) last.
const std::vector<FaultInfo>& fault_catalogue();
/// A built-in kind's entry (SensorUnit: the first unit fault's; use info(spec) for a spec).
const FaultInfo& info(FaultKind kind);
/// nullptr when `name` is no fault.
const FaultInfo* find_fault(std::string_view name);
std::vector<std::string> fault_names();
/// "motor:I,K" (what --help and errors show).
std::string usage(const FaultInfo& info);

/// A scenario event's condition (docs/faults.md "Conditions"): every part given must hold; it
/// counts from the first step where they all do (it latches), and is met `delay_s` later.
struct Condition {
  std::optional<double> altitude_above_m;  ///< the vehicle's altitude above home (truth)
  std::optional<double> altitude_below_m;
  std::optional<bool> armed;               ///< the board's armed bit (HIL_ACTUATOR_CONTROLS)
  std::optional<std::string> mode;         ///< the board's PX4 mode ("Position", "Land", ...)
  std::optional<std::string> after;        ///< another event's id: once it started
  double delay_s = 0;
};

struct FaultSpec {
  FaultKind kind = FaultKind::GpsLoss;
  std::size_t unit_fault = 0;  ///< SensorUnit: which (of sensors::unit_fault_infos())
  std::vector<double> args;  ///< in the catalogue's order and units
  double start_s = 0;        ///< simulated time (with start_when: the earliest)
  std::optional<double> duration_s;  ///< none: until the session ends (or end_when)
  std::string id;                    ///< a scenario event's name for "after" ("" none)
  std::optional<Condition> start_when;
  std::optional<Condition> end_when;

  std::string name() const;
  /// "2,0.6" ("" without arguments).
  std::string args_text() const;
  /// "motor:2,0.6@15+5"
  std::string text() const;
};

/// The catalogue's entry of a spec (a sensor unit's fault by its unit_fault).
const FaultInfo& info(const FaultSpec& spec);

/// A suggestion for an unknown fault name ("" for none); the CLI passes its did-you-mean.
using Suggest = std::function<std::string(const std::string& unknown_name)>;

/// A fault and its arguments checked against the catalogue: the count, numbers (NaN and inf are
/// refused), ranges and integers; errors name the fault and the argument.
Expected<FaultSpec> make_fault(const std::string& name, const std::vector<double>& args, double start_s,
                               std::optional<double> duration_s, const Suggest& suggest = {});
/// Parses "NAME[:ARGS][@T[+DUR]]": `gps-loss@20+10`, `motor:2,0.6@15`, `hil-delay:20`.
Expected<FaultSpec> parse_fault(const std::string& text, const Suggest& suggest = {});
/// A fault started by hand now: "NAME[:ARGS][+DUR]" (`gps-loss+10`, `motor:2,0.6`); no '@T'.
Expected<FaultSpec> parse_live_fault(const std::string& text, const Suggest& suggest = {});
/// A number as a fault argument or time: finite, the whole text.
Expected<double> parse_number(const std::string& text, const std::string& what);

}  // namespace hitl::faults
