// A recording read back as the series a report draws (docs/report.md): any .tlog, hitl's own or a
// ground station's. What a plain log lacks is said in words (FlightLog::missing), never guessed.
//
// Time: seconds of simulated time when the recording has the simulator's clock (the time_usec of
// the HIL_SENSOR it sent; every record is placed on it by its tlog timestamp, interpolated between
// two HIL_SENSOR), otherwise seconds since the first record. Positions are NED metres, every height
// on one datum: from home, the origin PX4's local position uses, 0.00 m on the ground (docs/sim.md).
// The simulator's truth ODOMETRY is its body origin in its world (0.22 m above the ground at rest);
// it, and the setpoints of a pilot that flies on it (hitl sim -t), are moved down by the truth's
// height at rest (FlightLog::truth_rest_down_m), as the session's status and JSON are.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "base/common/expected.h"
#include "base/common/severity.h"
#include "engine/report/field_expression.h"

namespace hitl::report {

struct Series {
  std::vector<double> t_s;
  std::vector<double> value;
  std::size_t size() const { return t_s.size(); }
};

struct Track {
  std::vector<double> t_s, north_m, east_m, down_m;
  std::size_t size() const { return t_s.size(); }
};

struct AttitudeTrack {
  std::vector<double> t_s, roll_deg, pitch_deg, yaw_deg;
  std::size_t size() const { return t_s.size(); }
};

struct VelocityTrack {
  std::vector<double> t_s, north_m_s, east_m_s, down_m_s;
  std::size_t size() const { return t_s.size(); }
};

/// Body rates (FRD: roll, pitch, yaw) in degrees per second.
struct RateTrack {
  std::vector<double> t_s, roll_deg_s, pitch_deg_s, yaw_deg_s;
  std::size_t size() const { return t_s.size(); }
};

/// The pilot's sticks, each -1..1: MANUAL_CONTROL's x (pitch), y (roll), z (thrust), r (yaw) / 1000,
/// or RC_CHANNELS_OVERRIDE's channels 1 to 4 (roll, pitch, throttle, yaw) as (us - 1500) / 500.
struct Sticks {
  Series roll, pitch, throttle, yaw;
  std::size_t size() const { return roll.size(); }
};

/// The simulator's IMU as it sent it (HIL_SENSOR): specific force and body rates, FRD.
struct ImuTrack {
  std::vector<double> t_s;
  std::array<std::vector<double>, 3> accel_FRD_m_s2;  ///< xacc, yacc, zacc
  std::array<std::vector<double>, 3> gyro_FRD_deg_s;  ///< xgyro, ygyro, zgyro
  std::size_t size() const { return t_s.size(); }
};

/// A GPS's quality as a message said it: fix type (0-1 none, 2 2D, 3 3D, ...), satellites visible,
/// eph and epv over 100 (HDOP and VDOP by MAVLink's words; metres as PX4 reads HIL_GPS); an unknown
/// value (UINT16_MAX, UINT8_MAX) is left out.
struct GpsQuality {
  Series fix_type, satellites, eph, epv;
  std::size_t size() const { return fix_type.size(); }
};

/// One data path's arrivals in 1 s windows of the log's time: rate per second of that time and the
/// standard deviation of the wall-clock inter-arrival time.
struct PathTiming {
  std::string name;                  ///< "HIL_SENSOR", "HIL_GPS", "ODOMETRY (VIO)", "HIL_ACTUATOR_CONTROLS"
  std::optional<double> expected_hz;  ///< per second of the log's time; nullopt: not known from the recording
  uint64_t count = 0;
  double mean_rate_hz = 0;            ///< count over the time between the first and the last
  Series rate_hz;                     ///< t_s at each window's middle
  Series jitter_ms;
};

struct LogEvent {
  double t_s = 0;
  Severity severity = Severity::Info;
  std::string source;  ///< "simulator", "pilot", "vehicle 1"
  std::string text;
};

/// A fault the simulator ran (fault_windows.h): from its start to its end, with its arguments.
struct FaultWindow {
  std::string name;                  ///< "imu-vibration"
  std::string args;                  ///< "8,90" as the simulator said them ("" : none)
  double start_s = 0;
  std::optional<double> end_s;       ///< nullopt: still active when the log ended
  std::optional<double> duration_s;  ///< as its start said it ("started (5 s)")
  std::string label() const { return args.empty() ? name : name + ":" + args; }
};

/// The vehicle's flight mode (PX4's name, from its HEARTBEAT) from one change to the next.
struct ModeSpan {
  std::string mode;  ///< "Position", "Land", ...
  double start_s = 0;
  double end_s = 0;  ///< the next change, or the log's last record
};

struct TrackingSummary {
  uint64_t samples = 0;
  double rms_m = 0;
  double max_m = 0;
};

/// The loop latency (HIL_SENSOR sent -> its HIL_ACTUATOR_CONTROLS received, wall time) as the
/// session's status said it each second: over the session so far, microseconds; only once something
/// was answered (the status says -1 before).
struct LoopLatencySeries {
  Series p50_us;  ///< NAMED_VALUE_INT sim_lat50
  Series p99_us;  ///< sim_lat99
  Series max_us;  ///< sim_latmx
  bool reported = false;  ///< the status carried sim_lat99 at all (-1 included)
};

/// One of PX4's EKF innovations or innovation test ratios from its ULog (px4_estimate.h's table).
struct Px4Innovation {
  std::string field;   ///< the topic's field, "gps_hvel[0]"
  std::string name;    ///< "GPS velocity north"
  std::string group;   ///< the plot it goes in: "velocity", "position", "height", "magnetometer", "heading"
  Series value;        ///< on the report's time axis; an innovation in its unit (heading in degrees)
};

/// PX4's own estimate from its ULog (hitl report --ulog; px4_estimate.h), on the report's time axis:
/// in lockstep PX4 SITL sets its clock to each HIL_SENSOR's time_usec, so a ULog timestamp of T us
/// is the simulator's T * 1e-6 s. NED metres from PX4's local origin (home, 0 m on the ground).
struct Px4Estimate {
  std::string path;              ///< the ULog read
  std::string version;           ///< PX4's "v1.16.0" (ver_sw_release), "" when the log has none
  Track position;                ///< vehicle_local_position x, y, z while xy_valid and z_valid
  AttitudeTrack attitude;        ///< vehicle_attitude q
  RateTrack rate_setpoint;       ///< vehicle_rates_setpoint roll, pitch, yaw (its rate controller's input), when logged
  RateTrack rates;               ///< vehicle_angular_velocity xyz (what its rate controller saw), when logged
  Track minus_truth;             ///< position minus the truth (interpolated at each time), where both are
  std::array<double, 3> mean_offset_NED_m{};  ///< the mean of minus_truth
  double rms_m = 0;              ///< of minus_truth's length
  /// How much later PX4's heights follow the truth's, fitted (the delay d, within +-0.5 s in 4 ms
  /// steps, that makes PX4's height at t + d agree best with the truth's at t, a constant offset
  /// aside): its estimator's lag on one clock, near 0 when the clocks are one.
  std::optional<double> lag_s;
  /// estimator_innovations and estimator_innovation_test_ratios (PX4 v1.16 SITL's default logging
  /// writes them at 100 Hz), the fields of kPx4InnovationFields / kPx4TestRatioFields that are not 0 throughout (a
  /// source EKF2 does not fuse stays 0: named in `innovations_zero`).
  std::vector<Px4Innovation> innovations;
  std::vector<Px4Innovation> test_ratios;
  std::vector<std::string> innovations_zero;  ///< "vision velocity north", ...: 0 throughout, not drawn
  std::string innovations_missing;            ///< why there are none ("" : read), e.g. "not in this log"
  std::map<std::string, double> parameters;          ///< the ULog's parameters ('P'), the last value of each
  std::map<std::string, double> parameter_defaults;  ///< its logged defaults ('Q'): the current setup's, else the system's
  std::vector<std::string> notes;  ///< the reader's notes and what was not drawn, in words
};

/// One series of a --plot (field_expression.h): its expression's value on each frame of its message,
/// from every sender; a value that is not finite (a division by a field that was 0) is left out, counted.
struct FieldSeries {
  std::string title;         ///< the expression as written
  std::string message;       ///< "ATTITUDE"
  std::string units;         ///< the field's units when the series is one field alone
  Series values;
  uint64_t not_finite = 0;
};

/// One --plot: its value as given and its series.
struct FieldPlot {
  std::string text;
  std::vector<FieldSeries> series;
};

/// The vehicle as its first HEARTBEAT said it.
struct VehicleInfo {
  uint8_t sysid = 0;
  uint8_t type = 0;       ///< MAV_TYPE (2: quadrotor)
  uint8_t autopilot = 0;  ///< MAV_AUTOPILOT (12: PX4)
};

struct FlightLog {
  std::string path;
  std::optional<uint64_t> first_unix_us;  ///< the first record's tlog timestamp (UNIX time, us)
  std::optional<VehicleInfo> vehicle;     ///< the first vehicle heard
  std::string generator;                  ///< what draws the page ("hitl 0.1.0"; set by write_report)
  uint64_t records = 0;         ///< tlog records read
  uint64_t frames = 0;          ///< MAVLink frames in them
  uint64_t skipped_bytes = 0;   ///< corruption the reader stepped over
  uint64_t parse_errors = 0;    ///< frames dropped by the parser (CRC, unknown ids)
  uint64_t segments = 0;        ///< stretches of the log's clock (more than 1: it jumped; engine/mavlink/tlog_timeline.h)
  uint64_t set_aside_records = 0;  ///< records whose stamp jumped: not drawn
  bool simulated_time = false;  ///< t_s is the simulator's clock
  double start_s = 0;           ///< the first record's t_s
  double duration_s = 0;        ///< first to last record, in t_s
  double wall_duration_s = 0;   ///< first to last record, tlog timestamps

  Track setpoint;               ///< the trajectory pilot's reference (POSITION_TARGET_LOCAL_NED from MAV_COMP_ID_PATHPLANNER), else the vehicle's
  Track truth;                  ///< the simulator's ground truth (ODOMETRY, estimator MOCAP, from the system that sent
                                ///< HIL_SENSOR, or from hitl's simulator id 250 in a log without HIL_SENSOR)
  Track estimate;               ///< the vehicle's LOCAL_POSITION_NED
  /// The truth's down at rest in the simulator's world (its first sample, before any arming):
  /// subtracted from the truth and from the simulator's pilot's setpoints. nullopt: no truth, or
  /// the vehicle was armed when it began (said in `missing`; those heights are left as recorded).
  std::optional<double> truth_rest_down_m;
  AttitudeTrack truth_attitude;
  AttitudeTrack estimate_attitude;  ///< ATTITUDE
  VelocityTrack setpoint_velocity;  ///< POSITION_TARGET_LOCAL_NED vx, vy, vz of the same sender as `setpoint`, where its type_mask gives them
  VelocityTrack truth_velocity;     ///< the truth ODOMETRY's body velocity turned to NED by its quaternion
  VelocityTrack estimate_velocity;  ///< LOCAL_POSITION_NED vx, vy, vz
  RateTrack rate_setpoint;          ///< the vehicle's ATTITUDE_TARGET body rates (where its type_mask gives them)
  RateTrack truth_rates;            ///< the truth ODOMETRY's rollspeed, pitchspeed, yawspeed
  RateTrack estimate_rates;         ///< ATTITUDE rollspeed, pitchspeed, yawspeed
  Sticks manual_control;            ///< MANUAL_CONTROL (any sender)
  Sticks rc_override;               ///< RC_CHANNELS_OVERRIDE (any sender)
  GpsQuality sent_gps;              ///< HIL_GPS from the simulator (what the flight stack was given)
  GpsQuality vehicle_gps;           ///< GPS_RAW_INT from the vehicle (what it made of it)
  ImuTrack imu;                     ///< HIL_SENSOR from the simulator whose fields_updated has the accelerometer and gyro
  Series tracking_error_m;      ///< NAMED_VALUE_FLOAT trk_err from the pilot: what the tracking RMS/max are of
  std::optional<TrackingSummary> tracking;
  std::array<Series, 4> motors;  ///< HIL_ACTUATOR_CONTROLS controls[0..3]
  std::array<Series, 6> ekf_ratios;  ///< ESTIMATOR_STATUS, in kEkfRatioNames' order
  std::vector<PathTiming> paths;
  std::vector<LogEvent> events;
  std::vector<FaultWindow> faults;        ///< the simulator's fault windows, in start order
  std::vector<ModeSpan> modes;            ///< the first vehicle's flight modes
  std::optional<int64_t> late_ticks;      ///< the session's last "sim_late"
  std::optional<bool> lockstep;           ///< the session's "sim_lockst"
  LoopLatencySeries loop_latency;
  std::vector<std::string> missing;       ///< what a report cannot draw from this log, in words
  std::vector<std::string> skipped;       ///< what a damaged log holds that is not drawn, in words
  std::optional<Px4Estimate> px4;         ///< PX4's ULog when the report was given one (px4_estimate.h)
  std::vector<FieldPlot> field_plots;     ///< hitl report --plot, in the order given
  /// PARAM_VALUE from the vehicle (any system but the simulator), by name: the last value of each
  /// (integers decoded byte-wise, as PX4 sends them), at most ReadLimits::max_parameters names.
  std::map<std::string, double> parameters;
  std::map<std::string, double> parameters_first;  ///< the first PARAM_VALUE of each name (a value set during the log differs)
};

inline constexpr std::array<const char*, 6> kEkfRatioNames = {"velocity", "horizontal position", "vertical position",
                                                              "magnetometer", "height above ground", "airspeed"};

struct ReadLimits {
  uint64_t max_records = 50'000'000;  ///< a larger log is read this far and said to be cut
  std::size_t max_events = 2000;       ///< further events are counted, not kept
  std::size_t max_parameters = 8192;   ///< PARAM_VALUE names kept (further names counted in `missing`)
};

/// Reads the tlog at `path` (two passes: the simulator's clock, then the series). An Error when it
/// cannot be opened or holds no MAVLink frame at all. `field_plots` (hitl report --plot) are evaluated
/// on every frame of their messages, into FlightLog::field_plots.
Expected<FlightLog> read_flight_log(const std::string& path, const ReadLimits& limits = {},
                                    const std::vector<FieldPlotSpec>& field_plots = {});

}  // namespace hitl::report
