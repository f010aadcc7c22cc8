// The session's faults over time: which have started and ended at a simulated time, what is active
// now folded into one ActiveFaults the hooks read (sensors, the model, the HIL link, VIO), and the
// record of every start and end for the summary. Pure: no I/O, no clock but the time it is given.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "engine/faults/fault_spec.h"
#include "engine/sensors/unit_set.h"

namespace hitl::faults {

/// What the GPS receiver reports under gps-degrade.
struct GpsReport {
  std::uint8_t fix_type = 3;
  std::uint8_t satellites = 10;
  double eph_m = 0;
  double epv_m = 0;
};

/// What the faults do to one link's datagrams (engine/hil/link_faults.h carries it out).
struct LinkImpairment {
  double drop_p = 0;           ///< hil-drop / vio-drop, independent draws combined
  double burst_bad_p = 0;      ///< Gilbert-Elliott: good -> bad per datagram (0: no bursts)
  double burst_good_p = 1;     ///< bad -> good per datagram
  double delay_s = 0;
  double jitter_s = 0;         ///< up to this much more, uniform
  double reorder_p = 0;
  double duplicate_p = 0;
  double max_rate_hz = 0;      ///< 0: no limit
  bool any() const {
    return drop_p > 0 || burst_bad_p > 0 || delay_s > 0 || jitter_s > 0 || reorder_p > 0 || duplicate_p > 0 || max_rate_hz > 0;
  }
};

/// Everything active at one time, folded: biases and offsets add, motor scales and the chances of a
/// datagram getting through multiply (a product of scales stays within one fault's range: motor
/// 0..2, imu-noise and gps-noise 0..100, mag-scale 0..10), delays add, the latest gps-degrade wins; on a link, the latest
/// burst wins, the lowest rate, jitters add, reorder and duplicate chances combine as drops do.
struct ActiveFaults {
  bool gps_loss = false;
  double gps_north_m = 0;
  double gps_east_m = 0;
  std::optional<GpsReport> gps_report;
  Eigen::Vector3d accel_bias_FRD_m_s2 = Eigen::Vector3d::Zero();
  Eigen::Vector3d gyro_bias_FRD_rad_s = Eigen::Vector3d::Zero();
  Eigen::Vector3d mag_offset_FRD_gauss = Eigen::Vector3d::Zero();
  double baro_offset_Pa = 0;  ///< baro-offset, and baro-drift: rate x time since its start
  double imu_noise_scale = 1;
  bool imu_stuck = false;
  double imu_clip_accel_m_s2 = 0;  ///< 0: none (the smallest active range wins)
  double imu_clip_gyro_rad_s = 0;
  struct Vibration {
    double amp_m_s2 = 0;
    double freq_hz = 0;
    double started_s = 0;  ///< its phase counts from here
  };
  std::vector<Vibration> vibrations;  ///< imu-vibration
  bool mag_stuck = false;
  double mag_scale = 1;
  bool baro_stuck = false;
  Eigen::Vector2d gps_drift_NE_m_s = Eigen::Vector2d::Zero();  ///< gps-drift: added to the reported velocity
  double gps_noise_scale = 1;
  struct RotorVibration {
    std::size_t motor = 0;
    double amp_m_s2 = 0;
  };
  std::vector<RotorVibration> rotor_vibrations;  ///< prop-damage: once per revolution of the rotor
  double payload_kg = 0;
  Eigen::Vector3d wind_NED_m_s = Eigen::Vector3d::Zero();  ///< wind and gust (at its shape's value now)
  double turbulence_sigma_m_s = 0;  ///< the largest active (with its tau)
  double turbulence_tau_s = 0;
  bool actuators_stale = false;
  Eigen::Vector3d vio_offset_NED_m = Eigen::Vector3d::Zero();  ///< vio-drift and vio-jump
  unsigned vio_resets = 0;  ///< each vio-jump's start and end, counted
  std::optional<int> vio_quality;  ///< the latest vio-quality
  std::array<double, 4> motor_effectiveness{1.0, 1.0, 1.0, 1.0};
  bool vio_loss = false;
  LinkImpairment hil_link;  ///< to the flight stack
  LinkImpairment vio_link;  ///< ODOMETRY to the VIO server
  sensors::UnitFaults units;  ///< the sensor units' faults, each folded by its unit's table
};

/// One fault's start and end as it happened (the summary's `faults`).
struct FaultRecord {
  std::string name;
  std::vector<double> args;
  double start_s = 0;
  std::optional<double> end_s;  ///< none: still active when the session ended
  std::optional<double> duration_s;  ///< as it was given (none: to end_when or the session's end)
  /// "gps-loss", "motor:2,0.6" (as the status lines and active_faults name it)
  std::string text() const;
};

struct FaultChange {
  bool started = true;  ///< false: ended (or refused)
  FaultSpec spec;
  double t_s = 0;  ///< simulated time of the step it took effect in
  bool refused = false;  ///< due while kMaxActiveFaults were active: never started
  /// "t=20.000 s fault gps-loss started (10 s)", "t=30.000 s fault gps-loss ended",
  /// "t=30.000 s fault gps-loss refused: 64 faults are active, the limit"
  std::string text() const;
};

/// At most this many faults are active at once: a scenario or --fault list that would have more
/// is refused at load (check_active_limit); one due later (a condition, a fault started by hand)
/// while this many are active is refused then (a FaultChange with refused set).
inline constexpr std::size_t kMaxActiveFaults = 64;

/// Ok, or an Input error "at most 64 faults can be active at once; 1100 could be at t=0 s" when
/// more than kMaxActiveFaults of `specs` overlap in time. An event with a condition counts from its
/// earliest start (at_s) and, ending on a condition or never, to the end of the session.
Status check_active_limit(const std::vector<FaultSpec>& specs);

/// What the conditions of scenario events look at, each step.
struct VehicleObservation {
  double altitude_m = 0;  ///< above home, truth
  bool armed = false;
  std::string mode;       ///< the board's PX4 mode name ("" before its first HEARTBEAT)
};

class FaultSchedule {
 public:
  explicit FaultSchedule(std::vector<FaultSpec> specs = {});
  /// Starts and ends what is due at simulated time `t_s` (called every step, t increasing) and
  /// refolds active(); the changes in the order they happened. `seen` feeds the conditions.
  std::vector<FaultChange> update(double t_s, const VehicleObservation& seen = {});
  /// A fault started by hand (the dashboard): from the next update() on, its start_s ignored.
  void start_now(FaultSpec spec);
  /// Ends every active fault named `name` (every active one when empty) at `t_s`; what ended.
  std::vector<FaultChange> clear(const std::string& name, double t_s);
  const ActiveFaults& active() const { return active_; }
  const std::vector<FaultRecord>& records() const { return records_; }
  /// "gps-loss", "motor:2,0.6" for each active fault.
  std::vector<std::string> active_texts() const;
  /// The events that have not started (yet): at the session's end, those that never did.
  std::vector<std::string> pending_texts() const;
  std::size_t active_count() const;
  bool empty() const { return entries_.empty(); }

 private:
  enum class State { Pending, Active, Done };
  struct Entry {
    FaultSpec spec;
    State state = State::Pending;
    double started_s = 0;
    std::size_t record = 0;
    std::optional<double> start_held_s;  ///< when start_when first held (it latches)
    std::optional<double> end_held_s;
  };
  /// True once `c` has held (latched) for its delay at `t_s`.
  bool met(const Condition& c, std::optional<double>& held_s, double t_s, const VehicleObservation& seen) const;
  void fold(double t_s);

  std::vector<Entry> entries_;
  std::vector<FaultRecord> records_;
  ActiveFaults active_;
};

}  // namespace hitl::faults
