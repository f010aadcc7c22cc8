#include "engine/faults/fault_spec.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "engine/sensors/unit_set.h"

namespace hitl::faults {
namespace {

// Ranges: far beyond any real fault, near enough to catch a slipped unit (mm for m, deg for rad).
constexpr double kMaxGpsJump_m = 100000;
constexpr double kMaxAccuracy_m = 655;       ///< HIL_GPS carries eph/epv in cm in a uint16
constexpr double kMaxAccelBias_m_s2 = 100;
constexpr double kMaxGyroBias_rad_s = 35;
constexpr double kMaxMagOffset_gauss = 10;
constexpr double kMaxBaroDrift_Pa_per_s = 10000;
constexpr double kMaxMotorScale = 2;
constexpr double kMaxHilDelay_ms = 5000;
constexpr double kMaxTime_s = 86400;
constexpr double kMaxNoiseScale = 100;
constexpr double kMaxClipAccel_m_s2 = 2000;  ///< above any MEMS full scale (+-200 g)
constexpr double kMaxClipGyro_rad_s = 70;    ///< +-4000 deg/s
constexpr double kMaxVibration_m_s2 = 500;
constexpr double kMaxVibration_Hz = 5000;
constexpr double kMaxMagScale = 10;
constexpr double kMaxBaroOffset_Pa = 20000;
constexpr double kMaxGpsDrift_m_s = 100;
constexpr double kMaxPayload_kg = 20;
constexpr double kMaxWind_m_s = 50;
constexpr double kMaxTurbulenceSigma_m_s = 20;
constexpr double kMaxVioDrift_m_s = 10;
constexpr double kMaxVioJump_m = 1000;
constexpr double kMaxLinkRate_Hz = 10000;         ///< a day of simulated time

std::string compact(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

}  // namespace

const std::vector<FaultInfo>& fault_catalogue() {
  static const std::vector<FaultInfo> catalogue = {
      {FaultKind::GpsLoss, FaultGroup::Gps, "gps-loss", {}, 0, "", "no HIL_GPS is sent (the receiver lost every satellite)"},
      {FaultKind::GpsJump, FaultGroup::Gps, "gps-jump", {{"north_m", -kMaxGpsJump_m, kMaxGpsJump_m}, {"east_m", -kMaxGpsJump_m, kMaxGpsJump_m}}, 2, ":20,0",
       "the reported position is offset north and east (spoofing, a multipath jump); velocity unchanged"},
      {FaultKind::GpsDegrade, FaultGroup::Gps, "gps-degrade",
       {{"fix", 0, 6, true}, {"sats", 0, 255, true}, {"eph_m", 0, kMaxAccuracy_m}, {"epv_m", 0, kMaxAccuracy_m}}, 3, ":2,4,5",
       "HIL_GPS reports this fix_type, satellites and eph (epv: the 4th argument, else eph); the position noise is unchanged"},
      {FaultKind::ImuBias, FaultGroup::Imu, "imu-bias",
       {{"ax_m_s2", -kMaxAccelBias_m_s2, kMaxAccelBias_m_s2}, {"ay_m_s2", -kMaxAccelBias_m_s2, kMaxAccelBias_m_s2},
        {"az_m_s2", -kMaxAccelBias_m_s2, kMaxAccelBias_m_s2}}, 3, ":0.3,0,0",
       "the accelerometer's bias steps by (ax, ay, az), body FRD, m/s^2"},
      {FaultKind::GyroBias, FaultGroup::Imu, "gyro-bias",
       {{"gx_rad_s", -kMaxGyroBias_rad_s, kMaxGyroBias_rad_s}, {"gy_rad_s", -kMaxGyroBias_rad_s, kMaxGyroBias_rad_s},
        {"gz_rad_s", -kMaxGyroBias_rad_s, kMaxGyroBias_rad_s}}, 3, ":0.05,0,0",
       "the gyro's bias steps by (gx, gy, gz), body FRD, rad/s"},
      {FaultKind::MagOffset, FaultGroup::Mag, "mag-offset",
       {{"x_gauss", -kMaxMagOffset_gauss, kMaxMagOffset_gauss}, {"y_gauss", -kMaxMagOffset_gauss, kMaxMagOffset_gauss},
        {"z_gauss", -kMaxMagOffset_gauss, kMaxMagOffset_gauss}}, 3, ":0.3,0,0",
       "the magnetometer reads an extra field (x, y, z), body FRD, gauss (a current-carrying cable nearby)"},
      {FaultKind::BaroDrift, FaultGroup::Baro, "baro-drift", {{"pa_per_s", -kMaxBaroDrift_Pa_per_s, kMaxBaroDrift_Pa_per_s}}, 1, ":5",
       "the static pressure drifts at this rate from the fault's start (pressure_alt follows)"},
      {FaultKind::Motor, FaultGroup::Vehicle, "motor", {{"i", 0, 3, true}, {"k", 0, kMaxMotorScale}}, 2, ":2,0.75",
       "motor i's (PX4 order) thrust and torques x k in the model; 0: out (the rotor spins but moves no air)"},
      {FaultKind::VioLoss, FaultGroup::Vio, "vio-loss", {}, 0, "", "no ODOMETRY is sent to the VIO server (tracking lost)"},
      {FaultKind::HilDrop, FaultGroup::HilLink, "hil-drop", {{"p", 0, 1}}, 1, ":0.1",
       "each datagram to the flight stack (a step's HIL_SENSOR, HIL_GPS, ...) is dropped with probability p (--seed)"},
      {FaultKind::HilDelay, FaultGroup::HilLink, "hil-delay", {{"ms", 0, kMaxHilDelay_ms}}, 1, ":15",
       "each datagram to the flight stack leaves this much later (queued; the 250 Hz loop does not wait)"},
      {FaultKind::ImuNoise, FaultGroup::Imu, "imu-noise", {{"k", 0, kMaxNoiseScale}}, 1, ":5",
       "the IMU's error against truth (white noise and bias walk, accel and gyro) x k; 0: a perfect IMU"},
      {FaultKind::ImuStuck, FaultGroup::Imu, "imu-stuck", {}, 0, "", "the IMU repeats the accel and gyro it read last before the fault (a hung sensor)"},
      {FaultKind::ImuClip, FaultGroup::Imu, "imu-clip", {{"accel_m_s2", 0.1, kMaxClipAccel_m_s2}, {"gyro_rad_s", 0.01, kMaxClipGyro_rad_s}}, 2, ":20,2",
       "the IMU clips each axis at +-accel_m_s2 and +-gyro_rad_s (a smaller full scale, saturation)"},
      {FaultKind::ImuVibration, FaultGroup::Imu, "imu-vibration", {{"amp_m_s2", 0, kMaxVibration_m_s2}, {"freq_hz", 0, kMaxVibration_Hz}}, 2, ":5,80",
       "a sinusoidal acceleration of this amplitude and frequency at the IMU, body x and y (sampled at the IMU's rate: it aliases)"},
      {FaultKind::MagStuck, FaultGroup::Mag, "mag-stuck", {}, 0, "", "the magnetometer repeats the field it read last before the fault"},
      {FaultKind::MagScale, FaultGroup::Mag, "mag-scale", {{"k", 0, kMaxMagScale}}, 1, ":1.5",
       "the magnetometer's reading x k (a gain error, soft iron); before mag-offset"},
      {FaultKind::BaroOffset, FaultGroup::Baro, "baro-offset", {{"pa", -kMaxBaroOffset_Pa, kMaxBaroOffset_Pa}}, 1, ":100",
       "the static pressure + pa (a pressure step: a door, a prop wash; pressure_alt follows)"},
      {FaultKind::BaroStuck, FaultGroup::Baro, "baro-stuck", {}, 0, "", "the barometer repeats the pressure, altitude and temperature it read last"},
      {FaultKind::GpsDrift, FaultGroup::Gps, "gps-drift", {{"north_m_s", -kMaxGpsDrift_m_s, kMaxGpsDrift_m_s}, {"east_m_s", -kMaxGpsDrift_m_s, kMaxGpsDrift_m_s}}, 2, ":0.5,0",
       "the reported position walks away at this rate from the fault's start, the velocity includes it (a slow, consistent spoof)"},
      {FaultKind::GpsNoise, FaultGroup::Gps, "gps-noise", {{"k", 0, kMaxNoiseScale}}, 1, ":5",
       "the GPS's position error (wander and white noise) and velocity noise x k"},
      {FaultKind::PropDamage, FaultGroup::Vehicle, "prop-damage", {{"i", 0, 3, true}, {"k", 0, kMaxMotorScale}, {"vib_m_s2", 0, kMaxVibration_m_s2}}, 3, ":1,0.85,2",
       "motor i's thrust and torques x k (a chipped blade) and an imbalance: vib_m_s2 at the IMU once per revolution of rotor i"},
      {FaultKind::Payload, FaultGroup::Vehicle, "payload", {{"kg", 0, kMaxPayload_kg}}, 1, ":0.5",
       "this mass hangs at the base origin (its weight pulls down; the inertia is the vehicle's own)"},
      {FaultKind::Wind, FaultGroup::Environment, "wind", {{"north_m_s", -kMaxWind_m_s, kMaxWind_m_s}, {"east_m_s", -kMaxWind_m_s, kMaxWind_m_s},
                                 {"down_m_s", -kMaxWind_m_s, kMaxWind_m_s}}, 2, ":5,0",
       "the air moves at this velocity (NED, blowing towards), added to the world's wind"},
      {FaultKind::Gust, FaultGroup::Environment, "gust", {{"north_m_s", -kMaxWind_m_s, kMaxWind_m_s}, {"east_m_s", -kMaxWind_m_s, kMaxWind_m_s},
                                 {"down_m_s", -kMaxWind_m_s, kMaxWind_m_s}}, 2, ":5,0+6",
       "a 1-cosine gust: the added wind rises from 0 to this peak at half the duration and back to 0 at its end", true},
      {FaultKind::Turbulence, FaultGroup::Environment, "turbulence", {{"sigma_m_s", 0, kMaxTurbulenceSigma_m_s}, {"tau_s", 0.05, 100}}, 1, ":1",
       "added turbulence: each axis a Gauss-Markov process of this sigma and correlation time (default 2 s), seeded"},
      {FaultKind::ActuatorsStale, FaultGroup::Board, "actuators-stale", {}, 0, "",
       "the board's actuator stream goes stale: the model holds the last commands it had, whatever the board sends"},
      {FaultKind::VioDrift, FaultGroup::Vio, "vio-drift", {{"north_m_s", -kMaxVioDrift_m_s, kMaxVioDrift_m_s}, {"east_m_s", -kMaxVioDrift_m_s, kMaxVioDrift_m_s},
                                          {"down_m_s", -kMaxVioDrift_m_s, kMaxVioDrift_m_s}}, 3, ":0.1,0,0",
       "the ODOMETRY position walks away at this rate (NED) from the fault's start (VIO drift); velocity unchanged"},
      {FaultKind::VioJump, FaultGroup::Vio, "vio-jump", {{"north_m", -kMaxVioJump_m, kMaxVioJump_m}, {"east_m", -kMaxVioJump_m, kMaxVioJump_m},
                                        {"down_m", -kMaxVioJump_m, kMaxVioJump_m}}, 3, ":5,0,0",
       "the ODOMETRY position jumps by this offset (NED) and reset_counter goes up by one, at the start and again at the end"},
      {FaultKind::VioQuality, FaultGroup::Vio, "vio-quality", {{"percent", -1, 100, true}}, 1, ":10",
       "ODOMETRY's quality reports this (-1: failed, 0: unknown, 1 worst .. 100 best)"},
      {FaultKind::HilBurst, FaultGroup::HilLink, "hil-burst", {{"p_bad", 0, 1}, {"p_good", 0.001, 1}}, 2, ":0.02,0.25",
       "burst loss on the HIL link (Gilbert-Elliott): each datagram the link turns bad with p_bad, back with p_good; all lost while bad"},
      {FaultKind::HilJitter, FaultGroup::HilLink, "hil-jitter", {{"ms", 0, kMaxHilDelay_ms}}, 1, ":5",
       "each datagram to the flight stack leaves up to ms later (uniform, seeded); order is kept"},
      {FaultKind::HilReorder, FaultGroup::HilLink, "hil-reorder", {{"p", 0, 1}}, 1, ":0.1", "each datagram to the flight stack swaps places with the next with probability p"},
      {FaultKind::HilDuplicate, FaultGroup::HilLink, "hil-dup", {{"p", 0, 1}}, 1, ":0.1", "each datagram to the flight stack is sent twice with probability p"},
      {FaultKind::HilRate, FaultGroup::HilLink, "hil-rate", {{"hz", 0.1, kMaxLinkRate_Hz}}, 1, ":20",
       "the HIL link carries at most hz datagrams a second of simulated time (a token bucket; the rest are dropped)"},
      {FaultKind::VioDrop, FaultGroup::VioLink, "vio-drop", {{"p", 0, 1}}, 1, ":0.5", "each ODOMETRY to the VIO server is dropped with probability p"},
      {FaultKind::VioDelay, FaultGroup::VioLink, "vio-delay", {{"ms", 0, kMaxHilDelay_ms}}, 1, ":20", "each ODOMETRY leaves this much later (queued; order kept)"},
      {FaultKind::VioBurst, FaultGroup::VioLink, "vio-burst", {{"p_bad", 0, 1}, {"p_good", 0.001, 1}}, 2, ":0.02,0.25", "burst loss on the VIO link (Gilbert-Elliott, as hil-burst)"},
      {FaultKind::VioJitter, FaultGroup::VioLink, "vio-jitter", {{"ms", 0, kMaxHilDelay_ms}}, 1, ":10", "each ODOMETRY leaves up to ms later (uniform, seeded); order is kept"},
      {FaultKind::VioReorder, FaultGroup::VioLink, "vio-reorder", {{"p", 0, 1}}, 1, ":0.1", "each ODOMETRY swaps places with the next with probability p"},
      {FaultKind::VioDuplicate, FaultGroup::VioLink, "vio-dup", {{"p", 0, 1}}, 1, ":0.1", "each ODOMETRY is sent twice with probability p"},
      {FaultKind::VioRate, FaultGroup::VioLink, "vio-rate", {{"hz", 0.1, kMaxLinkRate_Hz}}, 1, ":10", "the VIO link carries at most hz ODOMETRY a second of simulated time (the rest dropped)"},
  };
  // The sensor units' faults, from their folders (engine/sensors/units.h).
  static const std::vector<FaultInfo> with_units = [] {
    std::vector<FaultInfo> all = catalogue;
    const auto& units = sensors::unit_fault_infos();
    for (std::size_t i = 0; i < units.size(); ++i)
      all.push_back({FaultKind::SensorUnit, FaultGroup::OptionalSensors, units[i].name, units[i].args, units[i].required_args,
                     units[i].example, units[i].meaning, false, i});
    return all;
  }();
  return with_units;
}

const char* to_string(FaultGroup group) {
  switch (group) {
    case FaultGroup::Vehicle: return "vehicle";
    case FaultGroup::Imu: return "IMU";
    case FaultGroup::Mag: return "mag";
    case FaultGroup::Baro: return "baro";
    case FaultGroup::Gps: return "GPS";
    case FaultGroup::OptionalSensors: return "optional sensors";
    case FaultGroup::Vio: return "VIO";
    case FaultGroup::Environment: return "environment";
    case FaultGroup::HilLink: return "HIL link";
    case FaultGroup::VioLink: return "VIO link";
    case FaultGroup::Board: return "board";
  }
  return "?";
}

const FaultInfo& info(FaultKind kind) {
  for (const auto& f : fault_catalogue())
    if (f.kind == kind) return f;
  return fault_catalogue().front();  // unreachable: every kind is in the catalogue
}

const FaultInfo& info(const FaultSpec& spec) {
  if (spec.kind != FaultKind::SensorUnit) return info(spec.kind);
  for (const auto& f : fault_catalogue())
    if (f.kind == FaultKind::SensorUnit && f.unit_fault == spec.unit_fault) return f;
  return fault_catalogue().front();  // unreachable: make_fault takes unit_fault from the catalogue
}

std::string FaultSpec::name() const { return info(*this).name; }

const FaultInfo* find_fault(std::string_view name) {
  for (const auto& f : fault_catalogue())
    if (name == f.name) return &f;
  return nullptr;
}

std::vector<std::string> fault_names() {
  std::vector<std::string> names;
  for (const auto& f : fault_catalogue()) names.emplace_back(f.name);
  return names;
}

std::string usage(const FaultInfo& f) {
  std::string out = f.name;
  for (std::size_t i = 0; i < f.args.size(); ++i) {
    out += i == 0 ? ":" : ",";
    if (i >= f.required_args) out += "[";
    out += f.args[i].name;
    if (i >= f.required_args) out += "]";
  }
  return out;
}

std::string FaultSpec::args_text() const {
  std::string out;
  for (std::size_t i = 0; i < args.size(); ++i) out += (i ? "," : "") + compact(args[i]);
  return out;
}

std::string FaultSpec::text() const {
  std::string out = name();
  if (!args.empty()) out += ":" + args_text();
  out += "@" + compact(start_s);
  if (duration_s) out += "+" + compact(*duration_s);
  return out;
}

Expected<double> parse_number(const std::string& text, const std::string& what) {
  const char* begin = text.c_str();
  char* end = nullptr;
  const double v = std::strtod(begin, &end);
  if (text.empty() || end != begin + text.size()) return Error::input(what + ": '" + text + "' is not a number");
  if (!std::isfinite(v)) return Error::input(what + ": '" + text + "' is not a finite number");
  return v;
}

Expected<FaultSpec> make_fault(const std::string& name, const std::vector<double>& args, double start_s,
                               std::optional<double> duration_s, const Suggest& suggest) {
  const FaultInfo* f = find_fault(name);
  if (f == nullptr) {
    const std::string hint = suggest ? suggest(name) : std::string();
    return Error::input("unknown fault '" + name + "'" + (hint.empty() ? "" : "; did you mean '" + hint + "'?") +
                        " (faults: docs/faults.md)");
  }
  const std::string where = "fault " + std::string(f->name);
  if (args.size() < f->required_args || args.size() > f->args.size()) {
    const std::string wanted = f->required_args == f->args.size()
                                   ? std::to_string(f->args.size())
                                   : std::to_string(f->required_args) + " to " + std::to_string(f->args.size());
    return Error::input(where + ": takes " + wanted + " argument" + (f->args.size() == 1 ? "" : "s") + " (" + usage(*f) +
                        "), got " + std::to_string(args.size()));
  }
  for (std::size_t i = 0; i < args.size(); ++i) {
    const FaultArg& a = f->args[i];
    const double v = args[i];
    if (!std::isfinite(v)) return Error::input(where + ": " + a.name + " must be a finite number");
    if (v < a.min || v > a.max)
      return Error::input(where + ": " + a.name + " must be within " + compact(a.min) + ".." + compact(a.max) + " (got " + compact(v) + ")");
    if (a.integer && v != std::floor(v)) return Error::input(where + ": " + a.name + " must be a whole number (got " + compact(v) + ")");
  }
  if (!std::isfinite(start_s) || start_s < 0 || start_s > kMaxTime_s)
    return Error::input(where + ": the start time must be 0.." + compact(kMaxTime_s) + " s of simulated time (got " + compact(start_s) + ")");
  if (duration_s && (!std::isfinite(*duration_s) || !(*duration_s > 0) || *duration_s > kMaxTime_s))
    return Error::input(where + ": the duration must be more than 0 and at most " + compact(kMaxTime_s) + " s (got " +
                        compact(*duration_s) + ")");
  if (f->needs_duration && !duration_s)
    return Error::input(where + ": needs a duration (" + std::string(f->name) + "@T+DUR; its shape spans it)");
  FaultSpec spec;
  spec.kind = f->kind;
  spec.unit_fault = f->unit_fault;
  spec.args = args;
  spec.start_s = start_s;
  spec.duration_s = duration_s;
  return spec;
}

Expected<FaultSpec> parse_fault(const std::string& text, const Suggest& suggest) {
  std::string head = text;
  double start_s = 0;
  std::optional<double> duration_s;
  if (const auto at = text.find('@'); at != std::string::npos) {
    head = text.substr(0, at);
    std::string when = text.substr(at + 1);
    auto plus = when.find('+', 1);
    while (plus != std::string::npos && (when[plus - 1] == 'e' || when[plus - 1] == 'E')) plus = when.find('+', plus + 1);
    if (plus != std::string::npos) {
      auto d = parse_number(when.substr(plus + 1), "'" + text + "': the duration after '+'");
      if (!d) return d.error();
      duration_s = *d;
      when = when.substr(0, plus);
    }
    auto t = parse_number(when, "'" + text + "': the start time after '@'");
    if (!t) return t.error();
    start_s = *t;
  }
  std::string name = head;
  std::vector<double> args;
  if (const auto colon = head.find(':'); colon != std::string::npos) {
    name = head.substr(0, colon);
    const std::string list = head.substr(colon + 1);
    std::size_t pos = 0;
    for (;;) {
      const auto comma = list.find(',', pos);
      const FaultInfo* f = find_fault(name);
      const std::string what = f != nullptr && args.size() < f->args.size()
                                   ? "'" + text + "': fault " + name + ": " + f->args[args.size()].name
                                   : "'" + text + "': argument " + std::to_string(args.size() + 1);
      auto v = parse_number(list.substr(pos, comma == std::string::npos ? std::string::npos : comma - pos), what);
      if (!v) return v.error();
      args.push_back(*v);
      if (comma == std::string::npos) break;
      pos = comma + 1;
    }
  }
  auto spec = make_fault(name, args, start_s, duration_s, suggest);
  if (!spec) return spec.error().prefixed("'" + text + "': ");
  return spec;
}

}  // namespace hitl::faults

namespace hitl::faults {

Expected<FaultSpec> parse_live_fault(const std::string& text, const Suggest& suggest) {
  if (text.find('@') != std::string::npos)
    return Error::input("'" + text + "': a fault started by hand starts now: NAME[:ARGS][+DUR], no '@T'");
  // The duration: after the last '+' that is no exponent's sign.
  std::string head = text, tail;
  for (auto plus = text.rfind('+'); plus != std::string::npos && plus > 0; plus = text.rfind('+', plus - 1)) {
    if (text[plus - 1] == 'e' || text[plus - 1] == 'E') continue;
    head = text.substr(0, plus);
    tail = text.substr(plus);
    break;
  }
  auto spec = parse_fault(head + "@0" + tail, suggest);
  if (!spec) {
    std::string message = spec.error().message;
    if (const auto at = message.find("@0"); at != std::string::npos) message.erase(at, 2);  // name what was typed
    return Error::input(message);
  }
  return spec;
}

}  // namespace hitl::faults
