// A downward-facing lidar rangefinder, one sensor unit (engine/sensors/unit.h): its model, its
// vehicle-file keys (`sensors.rangefinder`), its faults and its DISTANCE_SENSOR. The defaults are
// a Benewake TFmini Plus (datasheet: 0.1-12 m, 100 Hz default frame rate, accuracy +-5 cm to 6 m and
// +-1 % beyond, 3.6 deg field of view), mounted 5 cm below the base origin, off until `hitl sim
// --rangefinder` or `"enabled": true`.
//
// Model, over flat ground at z = 0 (ENU), the beam along body down (FRD z) from the mount:
//   h    = height of the mount above the ground
//   cos  = the beam's component along world down (1 level, 0 horizontal)
//   d    = h / cos, the slant range where the beam meets the ground
//   read = d + N(0, sigma(d)),  sigma(d) = max(noise_m, noise_fraction d)
// A beam that meets no ground within range (cos <= 0, d < min_distance_m or d > max_distance_m)
// gets no valid return: the reading is max_distance + 1 cm with signal_quality 1 ("invalid" in
// MAVLink), which PX4 treats as out of range. A valid reading has signal_quality 100.
//
// Faults: rangefinder-stuck (repeats the last reading, as a hung sensor does) and
// rangefinder-no-return (no echo: a black or wet surface, a blocked lens; reported as above).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "base/mavlink/messages.h"
#include "engine/model/config_range.h"
#include "engine/model/random_stream.h"
#include "engine/model/vehicle_state.h"
#include "engine/model/world_config.h"
#include "engine/sensors/unit.h"

namespace hitl::sensors {

struct RangefinderSample {
  double time_s = 0.0;
  double distance_m = 0.0;  ///< the reported range (max_distance + 0.01 when there is no valid return)
  double true_distance_m = 0.0;  ///< the slant range to the ground without noise (inf: the beam misses it)
  bool valid = true;        ///< a return within range
};

class Rangefinder {
 public:
  using Sample = RangefinderSample;
  static constexpr const char* kName = "rangefinder";
  static constexpr const char* kSummary =
      "Also send DISTANCE_SENSOR from a downward lidar (a TFmini Plus: 0.1-12 m at 100 Hz; "
      "sensors.rangefinder in the --vehicle file)";

  struct Config {
    bool enabled = false;
    double rate_hz = 100.0;          ///< TFmini Plus default frame rate
    double min_distance_m = 0.1;
    double max_distance_m = 12.0;
    double noise_m = 0.025;          ///< white sigma at short range (+-5 cm as 2 sigma)
    double noise_fraction = 0.005;   ///< sigma as a fraction of the range, where larger (+-1 % as 2 sigma)
    double fov_deg = 3.6;            ///< reported as horizontal and vertical field of view
    Eigen::Vector3d position_FLU_m{0.0, 0.0, -0.05};  ///< the mount from the base origin (body axes)
  };

  /// Its keys under `sensors.rangefinder` (docs/engine.md).
  template <class V>
  static void fields(V& v, Config& c) {
    using namespace model::config_fields;
    v.boolean("enabled", c.enabled);
    v.number("rate_hz", c.rate_hz, closed(0.1, 10000.0));
    v.number("min_distance_m", c.min_distance_m, closed(0.0, kMaxDistance_m));
    v.number("max_distance_m", c.max_distance_m, closed(0.01, kMaxDistance_m));
    v.number("noise_m", c.noise_m, closed(0.0, 10.0));
    v.number("noise_fraction", c.noise_fraction, closed(0.0, 1.0));
    v.number("fov_deg", c.fov_deg, closed(0.0, 180.0));
    v.vec3("position_FLU_m", c.position_FLU_m, closed(-10.0, 10.0));
  }
  /// DISTANCE_SENSOR carries cm in a uint16, and a reading beyond range is sent 1 cm further.
  static constexpr double kMaxDistance_m = 655.0;
  /// What the keys' ranges cannot say: "" when the config is whole, else the problem.
  static std::string check(const Config& c);
  static Config without_noise(Config c) {
    c.noise_m = 0.0;
    c.noise_fraction = 0.0;
    return c;
  }

  /// What is active of its faults, folded.
  struct Faults {
    bool stuck = false;
    bool no_return = false;
  };
  static const std::vector<UnitFault<Faults>>& faults();

  Rangefinder(const Config& config, const model::WorldConfig& world, std::uint64_t seed);
  RangefinderSample sample(const model::VehicleState& state, double t_s);
  void reset();
  /// The faults on what it reports: no-return makes it invalid; stuck repeats the reading it
  /// reported last before the fault (sample times go on).
  void apply(const Faults& faults, RangefinderSample& sample);

  /// DISTANCE_SENSOR: cm, MAV_DISTANCE_SENSOR_LASER, MAV_SENSOR_ROTATION_PITCH_270 (downward),
  /// covariance sigma^2 in cm^2, the field of view, signal_quality 100 (valid) or 1 (no return).
  /// time_boot_ms: simulated time (PX4 stamps it on arrival).
  mavlink::msg::DistanceSensor message(const RangefinderSample& sample, std::uint64_t time_usec) const;

  const Config& config() const { return config_; }

 private:
  Config config_;
  std::uint64_t seed_;
  model::RandomStream rng_;
  std::optional<RangefinderSample> last_, held_;
};

}  // namespace hitl::sensors
