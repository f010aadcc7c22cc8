#include "engine/faults/fault_schedule.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace hitl::faults {
namespace {

constexpr double kTimeEpsilon_s = 1e-9;
constexpr double kDefaultTurbulenceTau_s = 2.0;

std::string compact(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

std::string label(const FaultSpec& spec) { return FaultRecord{spec.name(), spec.args}.text(); }

}  // namespace

std::string FaultRecord::text() const {
  FaultSpec spec;
  spec.args = args;
  return args.empty() ? name : name + ":" + spec.args_text();
}

std::string FaultChange::text() const {
  char t[48];
  std::snprintf(t, sizeof t, "t=%.3f s fault ", t_s);
  if (refused) return t + label(spec) + " refused: " + std::to_string(kMaxActiveFaults) + " faults are active, the limit";
  std::string out = t + label(spec) + (started ? " started" : " ended");
  if (started && spec.duration_s) out += " (" + compact(*spec.duration_s) + " s)";
  return out;
}

Status check_active_limit(const std::vector<FaultSpec>& specs) {
  // Starts and ends over time; at one time ends count before starts (a fault ending at t and one
  // starting at t do not overlap).
  std::vector<std::pair<double, int>> steps;
  for (const auto& s : specs) {
    steps.push_back({s.start_s, +1});
    if (s.duration_s && !s.start_when) steps.push_back({s.start_s + *s.duration_s, -1});
  }
  std::sort(steps.begin(), steps.end());
  std::size_t active = 0, most = 0;
  double most_at_s = 0;
  for (const auto& [t_s, step] : steps) {
    active = step > 0 ? active + 1 : active - 1;
    if (active > most) most = active, most_at_s = t_s;
  }
  if (most <= kMaxActiveFaults) return Ok{};
  return Error::input("at most " + std::to_string(kMaxActiveFaults) + " faults can be active at once; " + std::to_string(most) +
                      " could be at t=" + compact(most_at_s) + " s");
}

FaultSchedule::FaultSchedule(std::vector<FaultSpec> specs) {
  // In start order (stable: equal times keep the order they were given in).
  std::stable_sort(specs.begin(), specs.end(), [](const FaultSpec& a, const FaultSpec& b) { return a.start_s < b.start_s; });
  for (auto& s : specs) entries_.push_back({std::move(s)});
}

bool FaultSchedule::met(const Condition& c, std::optional<double>& held_s, double t_s, const VehicleObservation& seen) const {
  if (!held_s) {
    bool holds = true;
    if (c.altitude_above_m) holds = holds && seen.altitude_m > *c.altitude_above_m;
    if (c.altitude_below_m) holds = holds && seen.altitude_m < *c.altitude_below_m;
    if (c.armed) holds = holds && seen.armed == *c.armed;
    if (c.mode) holds = holds && seen.mode == *c.mode;
    if (c.after) {
      bool started = false;
      for (const auto& other : entries_)
        if (other.spec.id == *c.after && other.state != State::Pending) started = true;
      holds = holds && started;
    }
    if (holds) held_s = t_s;
  }
  return held_s && t_s + kTimeEpsilon_s >= *held_s + c.delay_s;
}

std::vector<FaultChange> FaultSchedule::update(double t_s, const VehicleObservation& seen) {
  std::vector<FaultChange> changes;
  for (auto& e : entries_) {
    if (e.state == State::Pending && t_s + kTimeEpsilon_s >= e.spec.start_s &&
        (!e.spec.start_when || met(*e.spec.start_when, e.start_held_s, t_s, seen))) {
      if (active_count() >= kMaxActiveFaults) {
        e.state = State::Done;
        changes.push_back({false, e.spec, t_s, true});
        continue;
      }
      e.state = State::Active;
      e.started_s = t_s;
      e.record = records_.size();
      records_.push_back({e.spec.name(), e.spec.args, t_s, std::nullopt, e.spec.duration_s});
      changes.push_back({true, e.spec, t_s});
    }
    const bool duration_over = e.spec.duration_s && t_s + kTimeEpsilon_s >= e.started_s + *e.spec.duration_s;
    if (e.state == State::Active && (duration_over || (e.spec.end_when && met(*e.spec.end_when, e.end_held_s, t_s, seen)))) {
      e.state = State::Done;
      records_[e.record].end_s = t_s;
      changes.push_back({false, e.spec, t_s});
    }
  }
  fold(t_s);
  return changes;
}

void FaultSchedule::fold(double t_s) {
  ActiveFaults a;
  // Chances that nothing happens to a datagram, over every active fault: 1 - p combined.
  double hil_pass = 1.0, vio_pass = 1.0, hil_keep = 1.0, vio_keep = 1.0, hil_single = 1.0, vio_single = 1.0;
  auto rate = [](LinkImpairment& l, double hz) { l.max_rate_hz = l.max_rate_hz > 0 ? std::min(l.max_rate_hz, hz) : hz; };
  for (const auto& e : entries_) {
    if (e.spec.kind == FaultKind::VioJump) a.vio_resets += e.state == State::Active ? 1 : e.state == State::Done ? 2 : 0;
    if (e.state != State::Active) continue;
    const auto& v = e.spec.args;
    switch (e.spec.kind) {
      case FaultKind::GpsLoss: a.gps_loss = true; break;
      case FaultKind::GpsJump:
        a.gps_north_m += v[0];
        a.gps_east_m += v[1];
        break;
      case FaultKind::GpsDegrade:
        a.gps_report = GpsReport{static_cast<std::uint8_t>(v[0]), static_cast<std::uint8_t>(v[1]), v[2], v.size() > 3 ? v[3] : v[2]};
        break;
      case FaultKind::ImuBias: a.accel_bias_FRD_m_s2 += Eigen::Vector3d(v[0], v[1], v[2]); break;
      case FaultKind::GyroBias: a.gyro_bias_FRD_rad_s += Eigen::Vector3d(v[0], v[1], v[2]); break;
      case FaultKind::MagOffset: a.mag_offset_FRD_gauss += Eigen::Vector3d(v[0], v[1], v[2]); break;
      case FaultKind::BaroDrift: a.baro_offset_Pa += v[0] * (t_s - e.started_s); break;
      case FaultKind::Motor: a.motor_effectiveness[static_cast<std::size_t>(v[0])] *= v[1]; break;
      case FaultKind::VioLoss: a.vio_loss = true; break;
      case FaultKind::HilDrop: hil_pass *= 1.0 - v[0]; break;
      case FaultKind::HilDelay: a.hil_link.delay_s += v[0] * 1e-3; break;
      case FaultKind::HilBurst: a.hil_link.burst_bad_p = v[0], a.hil_link.burst_good_p = v[1]; break;
      case FaultKind::HilJitter: a.hil_link.jitter_s += v[0] * 1e-3; break;
      case FaultKind::HilReorder: hil_keep *= 1.0 - v[0]; break;
      case FaultKind::HilDuplicate: hil_single *= 1.0 - v[0]; break;
      case FaultKind::HilRate: rate(a.hil_link, v[0]); break;
      case FaultKind::VioDrop: vio_pass *= 1.0 - v[0]; break;
      case FaultKind::VioDelay: a.vio_link.delay_s += v[0] * 1e-3; break;
      case FaultKind::VioBurst: a.vio_link.burst_bad_p = v[0], a.vio_link.burst_good_p = v[1]; break;
      case FaultKind::VioJitter: a.vio_link.jitter_s += v[0] * 1e-3; break;
      case FaultKind::VioReorder: vio_keep *= 1.0 - v[0]; break;
      case FaultKind::VioDuplicate: vio_single *= 1.0 - v[0]; break;
      case FaultKind::VioRate: rate(a.vio_link, v[0]); break;
      case FaultKind::ImuNoise: a.imu_noise_scale *= v[0]; break;
      case FaultKind::ImuStuck: a.imu_stuck = true; break;
      case FaultKind::ImuClip:
        a.imu_clip_accel_m_s2 = a.imu_clip_accel_m_s2 > 0 ? std::min(a.imu_clip_accel_m_s2, v[0]) : v[0];
        a.imu_clip_gyro_rad_s = a.imu_clip_gyro_rad_s > 0 ? std::min(a.imu_clip_gyro_rad_s, v[1]) : v[1];
        break;
      case FaultKind::ImuVibration: a.vibrations.push_back({v[0], v[1], e.started_s}); break;
      case FaultKind::MagStuck: a.mag_stuck = true; break;
      case FaultKind::MagScale: a.mag_scale *= v[0]; break;
      case FaultKind::BaroOffset: a.baro_offset_Pa += v[0]; break;
      case FaultKind::BaroStuck: a.baro_stuck = true; break;
      case FaultKind::GpsDrift:
        a.gps_north_m += v[0] * (t_s - e.started_s);
        a.gps_east_m += v[1] * (t_s - e.started_s);
        a.gps_drift_NE_m_s += Eigen::Vector2d(v[0], v[1]);
        break;
      case FaultKind::GpsNoise: a.gps_noise_scale *= v[0]; break;
      case FaultKind::PropDamage:
        a.motor_effectiveness[static_cast<std::size_t>(v[0])] *= v[1];
        a.rotor_vibrations.push_back({static_cast<std::size_t>(v[0]), v[2]});
        break;
      case FaultKind::Payload: a.payload_kg += v[0]; break;
      case FaultKind::Wind: a.wind_NED_m_s += Eigen::Vector3d(v[0], v[1], v.size() > 2 ? v[2] : 0.0); break;
      case FaultKind::Gust: {
        const double shape = 0.5 * (1.0 - std::cos(2.0 * M_PI * (t_s - e.started_s) / *e.spec.duration_s));
        a.wind_NED_m_s += shape * Eigen::Vector3d(v[0], v[1], v.size() > 2 ? v[2] : 0.0);
        break;
      }
      case FaultKind::Turbulence:
        if (v[0] >= a.turbulence_sigma_m_s) {
          a.turbulence_sigma_m_s = v[0];
          a.turbulence_tau_s = v.size() > 1 ? v[1] : kDefaultTurbulenceTau_s;
        }
        break;
      case FaultKind::ActuatorsStale: a.actuators_stale = true; break;
      case FaultKind::VioDrift: a.vio_offset_NED_m += Eigen::Vector3d(v[0], v[1], v[2]) * (t_s - e.started_s); break;
      case FaultKind::VioJump: a.vio_offset_NED_m += Eigen::Vector3d(v[0], v[1], v[2]); break;
      case FaultKind::VioQuality: a.vio_quality = static_cast<int>(v[0]); break;
      case FaultKind::SensorUnit: sensors::fold_unit_fault(a.units, e.spec.unit_fault, v, e.started_s, t_s); break;
    }
  }
  // Products of scales within one fault's range (1,100 stacked motor:0,2 are 2, not 2^1100).
  auto scale_max = [](FaultKind kind) { return info(kind).args.back().max; };
  for (double& k : a.motor_effectiveness) k = std::min(k, info(FaultKind::Motor).args[1].max);
  a.imu_noise_scale = std::min(a.imu_noise_scale, scale_max(FaultKind::ImuNoise));
  a.gps_noise_scale = std::min(a.gps_noise_scale, scale_max(FaultKind::GpsNoise));
  a.mag_scale = std::min(a.mag_scale, scale_max(FaultKind::MagScale));
  a.hil_link.drop_p = 1.0 - hil_pass;
  a.vio_link.drop_p = 1.0 - vio_pass;
  a.hil_link.reorder_p = 1.0 - hil_keep;
  a.vio_link.reorder_p = 1.0 - vio_keep;
  a.hil_link.duplicate_p = 1.0 - hil_single;
  a.vio_link.duplicate_p = 1.0 - vio_single;
  active_ = a;
}

void FaultSchedule::start_now(FaultSpec spec) {
  spec.start_s = 0;  // due at once
  spec.start_when.reset();
  entries_.push_back({std::move(spec)});
}

std::vector<FaultChange> FaultSchedule::clear(const std::string& name, double t_s) {
  std::vector<FaultChange> changes;
  for (auto& e : entries_) {
    if (e.state != State::Active || (!name.empty() && e.spec.name() != name)) continue;
    e.state = State::Done;
    records_[e.record].end_s = t_s;
    changes.push_back({false, e.spec, t_s});
  }
  fold(t_s);
  return changes;
}

std::size_t FaultSchedule::active_count() const {
  return static_cast<std::size_t>(std::count_if(entries_.begin(), entries_.end(), [](const Entry& e) { return e.state == State::Active; }));
}

std::vector<std::string> FaultSchedule::pending_texts() const {
  std::vector<std::string> out;
  for (const auto& e : entries_)
    if (e.state == State::Pending) out.push_back(e.spec.id.empty() ? label(e.spec) : e.spec.id + " (" + label(e.spec) + ")");
  return out;
}

std::vector<std::string> FaultSchedule::active_texts() const {
  std::vector<std::string> out;
  for (const auto& e : entries_)
    if (e.state == State::Active) out.push_back(label(e.spec));
  return out;
}

}  // namespace hitl::faults
