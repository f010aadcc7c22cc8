#include "engine/sensors/rangefinder/rangefinder.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "base/mavlink/enums.h"
#include "base/mavlink/wire_units.h"

namespace hitl::sensors {
namespace {

constexpr double kNoReturnBeyond_m = 0.01;  ///< a reading with no valid return: max_distance + 1 cm
constexpr std::uint8_t kQualityValid = 100;
constexpr std::uint8_t kQualityInvalid = 1;  ///< MAVLink: 1 = invalid signal (0 = unknown)
constexpr std::uint8_t kCovarianceUnknown = 255;

}  // namespace

const std::vector<UnitFault<Rangefinder::Faults>>& Rangefinder::faults() {
  static const std::vector<UnitFault<Faults>> table = {
      {"rangefinder-stuck", {}, 0, "",
       "the rangefinder repeats the distance it reported last before the fault (a hung sensor)",
       [](Faults& f, const std::vector<double>&, double, double) { f.stuck = true; }},
      {"rangefinder-no-return", {}, 0, "",
       "the rangefinder gets no echo (a black or wet surface, a blocked lens): it reports max_distance + 1 cm "
       "with signal_quality 1 (invalid)",
       [](Faults& f, const std::vector<double>&, double, double) { f.no_return = true; }},
  };
  return table;
}

std::string Rangefinder::check(const Config& c) {
  if (!(c.min_distance_m < c.max_distance_m))
    return "min_distance_m must be less than max_distance_m (got " + std::to_string(c.min_distance_m) + " and " +
           std::to_string(c.max_distance_m) + ")";
  return "";
}

Rangefinder::Rangefinder(const Config& config, const model::WorldConfig&, std::uint64_t seed)
    : config_(config), seed_(seed), rng_(seed, kName) {}

void Rangefinder::reset() {
  rng_ = model::RandomStream(seed_, kName);
  last_.reset();
  held_.reset();
}

RangefinderSample Rangefinder::sample(const model::VehicleState& state, double t_s) {
  const Eigen::Vector3d mount_ENU_m = state.p_ENU_m + state.q_FLU_to_ENU * config_.position_FLU_m;
  const Eigen::Vector3d beam_ENU = state.q_FLU_to_ENU * Eigen::Vector3d(0.0, 0.0, -1.0);  // body down
  const double cos_down = -beam_ENU.z();
  const double height_m = mount_ENU_m.z();
  RangefinderSample s;
  s.time_s = t_s;
  s.true_distance_m = cos_down > 0.0 && height_m >= 0.0 ? height_m / cos_down : std::numeric_limits<double>::infinity();
  const double sigma_m = std::max(config_.noise_m, config_.noise_fraction * std::min(s.true_distance_m, config_.max_distance_m));
  const double noise_m = rng_.normal(sigma_m);  // drawn every sample, so the stream does not depend on the geometry
  s.valid = s.true_distance_m >= config_.min_distance_m && s.true_distance_m <= config_.max_distance_m;
  s.distance_m = s.valid ? std::clamp(s.true_distance_m + noise_m, 0.0, config_.max_distance_m)
                         : config_.max_distance_m + kNoReturnBeyond_m;
  return s;
}

void Rangefinder::apply(const Faults& faults, RangefinderSample& sample) {
  if (faults.no_return) {
    sample.valid = false;
    sample.distance_m = config_.max_distance_m + kNoReturnBeyond_m;
  }
  if (!faults.stuck) held_.reset();
  else {
    if (!held_) held_ = last_ ? last_ : sample;
    sample.distance_m = held_->distance_m;
    sample.valid = held_->valid;
  }
  last_ = sample;
}

mavlink::msg::DistanceSensor Rangefinder::message(const RangefinderSample& sample, std::uint64_t time_usec) const {
  namespace w = mavlink::wire;
  mavlink::msg::DistanceSensor m;
  m.time_boot_ms = static_cast<std::uint32_t>(time_usec / 1000);
  m.min_distance = w::m_to_cm_u16(config_.min_distance_m);
  m.max_distance = w::m_to_cm_u16(config_.max_distance_m);
  m.current_distance = w::m_to_cm_u16(sample.distance_m);
  m.type = static_cast<std::uint8_t>(mavlink::MavDistanceSensor::Laser);
  m.id = 0;
  m.orientation = static_cast<std::uint8_t>(mavlink::MavSensorOrientation::Pitch270);
  // The variance PX4 reads (cm^2; 255: unknown): sigma at this range, squared.
  const double range_m = sample.valid ? sample.distance_m : config_.max_distance_m;
  const double sigma_cm = 100.0 * std::max(config_.noise_m, config_.noise_fraction * range_m);
  m.covariance = static_cast<std::uint8_t>(std::min<long long>(std::llround(sigma_cm * sigma_cm), kCovarianceUnknown - 1));
  const auto fov_rad = static_cast<float>(config_.fov_deg * std::numbers::pi / 180.0);
  m.horizontal_fov = fov_rad;
  m.vertical_fov = fov_rad;
  m.quaternion = {0.0f, 0.0f, 0.0f, 0.0f};  // MAVLink: used with MAV_SENSOR_ROTATION_CUSTOM only
  m.signal_quality = sample.valid ? kQualityValid : kQualityInvalid;
  return m;
}

}  // namespace hitl::sensors
