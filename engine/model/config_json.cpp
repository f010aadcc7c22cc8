// The config files' keys, once: one field table per config (vehicle_fields, world_fields), read and
// written through the visitors of config_fields.h. docs/engine.md lists every key.
#include "engine/model/config_json.h"

#include "base/common/bounded_read.h"
#include "engine/model/config_fields.h"
#include "engine/model/x500_defaults.h"

namespace hitl::model {
namespace {

using namespace config_fields;  // Range, Reader, Writer, parse, write: config_fields.h

// ---- The field tables: the one list of keys, used for reading and for writing. ----

template <class V>
void inertial_noise_fields(V& v, InertialNoiseConfig& n) {
  v.number("noise_density", n.noise_density, kNonNegative);
  v.number("random_walk", n.random_walk, kNonNegative);
  v.number("bias_correlation_time_s", n.bias_correlation_time_s, kPositive);
  v.number("turn_on_bias_sigma", n.turn_on_bias_sigma, kNonNegative);
  v.number("bias_instability", n.bias_instability, kNonNegative);
  v.number("scale_error_sigma", n.scale_error_sigma, closed(0.0, 0.5));
  v.number("cross_axis_sigma", n.cross_axis_sigma, closed(0.0, 0.5));
}

template <class V>
void rotor_fields(V& v, RotorConfig& r) {
  v.vec3("position_FLU_m", r.position_FLU_m, closed(-10.0, 10.0));
  v.turning("turning", r.turning);
  v.number("mass_kg", r.mass_kg, kPositive);
  v.vec3("inertia_kgm2", r.inertia_kgm2, kPositive);
  v.number("time_constant_up_s", r.time_constant_up_s, kPositive);
  v.number("time_constant_down_s", r.time_constant_down_s, kPositive);
  v.number("max_rot_velocity_rad_s", r.max_rot_velocity_rad_s, kPositive);
  v.number("motor_constant_N_s2", r.motor_constant_N_s2, kNonNegative);
  v.number("moment_constant_m", r.moment_constant_m, kNonNegative);
  v.number("rotor_drag_coefficient", r.rotor_drag_coefficient, kNonNegative);
  v.number("rolling_moment_coefficient", r.rolling_moment_coefficient, kNonNegative);
  v.number("axial_speed_falloff_m_s", r.axial_speed_falloff_m_s, kPositive);
  v.number("input_offset", r.input_offset, kAny);
  v.number("input_scaling_rad_s", r.input_scaling_rad_s, kAny);
  v.number("zero_position_armed_rad_s", r.zero_position_armed_rad_s, kAny);
}

template <class V>
void vehicle_fields(V& v, VehicleConfig& c) {
  v.text("name", c.name);
  v.object("base", [&](auto& b) {
    b.number("mass_kg", c.base.mass_kg, kPositive);
    b.vec3("inertia_kgm2", c.base.inertia_kgm2, kPositive);
    b.vec3("linear_drag_N_s_m", c.base.linear_drag_N_s_m, kNonNegative);
  });
  v.object_array("rotors", c.rotors, [](auto& r, RotorConfig& rotor) { rotor_fields(r, rotor); });
  v.object("landing_gear", [&](auto& g) {
    LandingGearConfig& lg = c.landing_gear;
    g.vec3_array("contact_points_FLU_m", lg.contact_points_FLU_m, closed(-10.0, 10.0));
    g.number("stiffness_N_m", lg.stiffness_N_m, kPositive);
    g.number("damping_N_s_m", lg.damping_N_s_m, kNonNegative);
    g.number("damping_depth_m", lg.damping_depth_m, closed(0.0, 1.0));
    g.vec3_array("frame_points_FLU_m", lg.frame_points_FLU_m, closed(-10.0, 10.0));
    g.number("frame_stiffness_N_m", lg.frame_stiffness_N_m, kPositive);
    g.number("frame_damping_N_s_m", lg.frame_damping_N_s_m, kNonNegative);
    g.number("friction_coefficient", lg.friction_coefficient, kNonNegative);
    g.number("tangential_stiffness_N_m", lg.tangential_stiffness_N_m, kPositive);
    g.number("tangential_damping_N_s_m", lg.tangential_damping_N_s_m, kNonNegative);
  });
  v.object("sensors", [&](auto& s) {
    SensorsConfig& sc = c.sensors;
    s.object("imu", [&](auto& i) {
      i.number("rate_hz", sc.imu.rate_hz, closed(0.1, 10000.0));
      i.vec3("position_FLU_m", sc.imu.position_FLU_m, closed(-10.0, 10.0));
      i.number("accel_range_m_s2", sc.imu.accel_range_m_s2, kPositive);
      i.number("gyro_range_rad_s", sc.imu.gyro_range_rad_s, kPositive);
      i.number("accel_resolution_m_s2", sc.imu.accel_resolution_m_s2, closed(0.0, 10.0));
      i.number("gyro_resolution_rad_s", sc.imu.gyro_resolution_rad_s, closed(0.0, 1.0));
      i.object("gyro", [&](auto& n) { inertial_noise_fields(n, sc.imu.gyro); });
      i.object("accel", [&](auto& n) { inertial_noise_fields(n, sc.imu.accel); });
      i.object("vibration", [&](auto& vib) {
        VibrationConfig& vc = sc.imu.vibration;
        vib.number("imbalance_m_s2_per_rad2_s2", vc.imbalance_m_s2_per_rad2_s2, closed(0.0, 1e-2));
        vib.number("blade_pass_m_s2_per_rad2_s2", vc.blade_pass_m_s2_per_rad2_s2, closed(0.0, 1e-2));
        vib.number("gyro_imbalance_rad_s_per_rad2_s2", vc.gyro_imbalance_rad_s_per_rad2_s2, closed(0.0, 1e-3));
        vib.integer("blades", vc.blades, closed(1, 8));
      });
      i.object("filter", [&](auto& f) {
        ImuFilterConfig& fc = sc.imu.filter;
        f.number("output_data_rate_hz", fc.output_data_rate_hz, closed(0.0, 100000.0));
        f.number("anti_alias_hz", fc.anti_alias_hz, closed(0.0, 50000.0));
        f.number("ui_filter_hz", fc.ui_filter_hz, closed(0.0, 50000.0));
      });
    });
    s.object("mag", [&](auto& m) {
      m.number("rate_hz", sc.mag.rate_hz, closed(0.1, 10000.0));
      m.object("noise", [&](auto& n) { inertial_noise_fields(n, sc.mag.noise); });
      m.number("range_gauss", sc.mag.range_gauss, closed(0.0, 100.0));
      m.number("resolution_gauss", sc.mag.resolution_gauss, closed(0.0, 1.0));
    });
    s.object("baro", [&](auto& b) {
      b.number("rate_hz", sc.baro.rate_hz, closed(0.1, 10000.0));
      b.number("noise_pa", sc.baro.noise_pa, kNonNegative);
      b.number("drift_pa_sqrt_s", sc.baro.drift_pa_sqrt_s, kNonNegative);
      b.number("temperature_noise_c", sc.baro.temperature_noise_c, kNonNegative);
    });
    s.object("gps", [&](auto& g) {
      GpsConfig& gc = sc.gps;
      g.number("rate_hz", gc.rate_hz, closed(0.1, 10000.0));
      g.number("horizontal_noise_m", gc.horizontal_noise_m, kNonNegative);
      g.number("vertical_noise_m", gc.vertical_noise_m, kNonNegative);
      g.number("horizontal_error_sigma_m", gc.horizontal_error_sigma_m, kNonNegative);
      g.number("vertical_error_sigma_m", gc.vertical_error_sigma_m, kNonNegative);
      g.number("error_correlation_time_s", gc.error_correlation_time_s, kPositive);
      g.number("velocity_noise_m_s", gc.velocity_noise_m_s, kNonNegative);
      g.number("eph_m", gc.eph_m, kNonNegative);
      g.number("epv_m", gc.epv_m, kNonNegative);
      g.boolean("accuracy_follows_error", gc.accuracy_follows_error);
      g.integer("satellites", gc.satellites, closed(0, 255));
      g.number("delay_s", gc.delay_s, closed(0.0, 10.0));
    });
  });
}

template <class V>
void world_fields(V& v, WorldConfig& w) {
  v.number("gravity_m_s2", w.gravity_m_s2, closed(0.0, 100.0));
  v.object("home", [&](auto& h) {
    h.number("lat_deg", w.home.lat_deg, closed(-90.0, 90.0));
    h.number("lon_deg", w.home.lon_deg, closed(-180.0, 180.0));
    h.number("alt_m", w.home.alt_m, closed(-1000.0, 9000.0));
  });
  v.object("magnetic_field", [&](auto& m) {
    m.number("declination_deg", w.magnetic_field.declination_deg, closed(-180.0, 180.0));
    m.number("inclination_deg", w.magnetic_field.inclination_deg, closed(-90.0, 90.0));
    m.number("strength_gauss", w.magnetic_field.strength_gauss, closed(0.0, 10.0));
  });
  v.object("atmosphere", [&](auto& a) {
    a.number("sea_level_pressure_pa", w.atmosphere.sea_level_pressure_pa, closed(50000.0, 120000.0));
    a.number("sea_level_temperature_c", w.atmosphere.sea_level_temperature_c, closed(-80.0, 60.0));
  });
  v.object("wind", [&](auto& a) {
    a.vec3("velocity_ENU_m_s", w.wind.velocity_ENU_m_s, closed(-100.0, 100.0));
    a.vec3("gust_sigma_m_s", w.wind.gust_sigma_m_s, closed(0.0, 50.0));
    a.number("gust_correlation_time_s", w.wind.gust_correlation_time_s, kPositive);
  });
  v.object("physics", [&](auto& p) {
    p.number("step_s", w.physics.step_s, closed(1e-4, 0.1));
    p.number("max_substep_s", w.physics.max_substep_s, closed(1e-5, 0.1));
    p.number("max_speed_m_s", w.physics.max_speed_m_s, kPositive);
    p.number("max_angular_rate_rad_s", w.physics.max_angular_rate_rad_s, kPositive);
  });
}


Expected<std::string> read_file(const std::filesystem::path& file, const std::string& what) {
  return read_bounded_file(file.string(), what, kMaxConfigFileBytes);
}

template <class Config>
Status as_status(const Expected<Config>& parsed) {
  if (parsed) return Ok{};
  return parsed.error();
}

}  // namespace

Expected<VehicleConfig> parse_vehicle_config(std::string_view json_text, std::string_view source_name,
                                             const VehicleConfig& base) {
  return parse(json_text, source_name, base, [](auto& v, VehicleConfig& c) { vehicle_fields(v, c); });
}
Expected<VehicleConfig> parse_vehicle_config(std::string_view json_text, std::string_view source_name) {
  return parse_vehicle_config(json_text, source_name, x500_vehicle_config());
}
Expected<VehicleConfig> load_vehicle_config(const std::filesystem::path& file) {
  Expected<std::string> text = read_file(file, "vehicle file");
  if (!text) return text.error();
  return parse_vehicle_config(*text, file.string());
}

Expected<WorldConfig> parse_world_config(std::string_view json_text, std::string_view source_name,
                                         const WorldConfig& base) {
  return parse(json_text, source_name, base, [](auto& v, WorldConfig& c) { world_fields(v, c); });
}
Expected<WorldConfig> parse_world_config(std::string_view json_text, std::string_view source_name) {
  return parse_world_config(json_text, source_name, default_world_config());
}
Expected<WorldConfig> load_world_config(const std::filesystem::path& file) {
  Expected<std::string> text = read_file(file, "world file");
  if (!text) return text.error();
  return parse_world_config(*text, file.string());
}

std::string to_json_text(const VehicleConfig& config) {
  return write(config, [](auto& v, VehicleConfig& c) { vehicle_fields(v, c); });
}
std::string to_json_text(const WorldConfig& config) {
  return write(config, [](auto& v, WorldConfig& c) { world_fields(v, c); });
}

Status validate(const VehicleConfig& config) {
  return as_status(parse_vehicle_config(to_json_text(config), "vehicle config", config));
}
Status validate(const WorldConfig& config) {
  return as_status(parse_world_config(to_json_text(config), "world config", config));
}

}  // namespace hitl::model
