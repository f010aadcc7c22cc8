// hitl fly takeoff | land | hold: one command to the board, then wait for the outcome (altitude
// reached; landed and disarmed; Hold shown in HEARTBEAT) with progress and a timeout.
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>

#include "base/common/clock.h"
#include "base/mavlink/enums.h"
#include "cli/commands.h"
#include "cli/link_options.h"
#include "cli/number_check.h"
#include "engine/hil/session_config.h"
#include "engine/vehicle/command_client.h"
#include "engine/vehicle/param_client.h"
#include "engine/vehicle/trajectory_pilot.h"

namespace hitl::cli {
namespace {

namespace msg = mavlink::msg;

struct FlyOptions {
  vehicle::LinkOptions link;
  std::optional<double> alt_m;  ///< takeoff: metres above home (default: the board's MIS_TAKEOFF_ALT)
  double wait_s = 60;           ///< how long to wait for the outcome
  std::string trajectory_file;
  double rc_rate_hz = 20;
  vehicle::StickMode mode = vehicle::StickMode::Velocity;
};

// PX4 custom_mode of Hold: AUTO (4) << 16 | LOITER (3) << 24.
constexpr uint32_t kPx4Hold = (4u << 16) | (3u << 24);

int finish(const GlobalOptions& g, const char* action, bool ok, const std::string& text, nlohmann::json extra = {}) {
  if (g.json) {
    nlohmann::json j = {{"type", "summary"}, {"command", "fly"}, {"action", action}, {"ok", ok}, {"message", text}};
    for (auto& [k, v] : extra.items()) j[k] = v;
    print_json_line(j);
  } else {
    std::cout << text << '\n';
  }
  return ok ? kExitOk : kExitFailed;
}

/// The trajectory_rc pilot from the host, on the board's own estimate (LOCAL_POSITION_NED and
/// ATTITUDE, asked for at 50 Hz), on the board's clock (time_boot_ms), so any simulator speed works.
int fly_trajectory(const GlobalOptions& g, const FlyOptions& o, vehicle::VehicleLink& link, vehicle::Trajectory trajectory) {
  vehicle::CommandClient commands(link);
  for (uint32_t id : {msg::LocalPositionNed::kId, msg::Attitude::kId}) {
    auto r = commands.send(mavlink::cmd::kSetMessageInterval, {static_cast<float>(id), 20000.0f, 0, 0, 0, 0, 0});
    if (!r || !r->accepted()) log_info(g, "hitl fly: the board did not take a 50 Hz stream request; flying on its default rates");
  }
  vehicle::PilotConfig pc;
  pc.rc_rate_hz = o.rc_rate_hz;
  pc.mode = o.mode;
  pc.target_system = link.target_sysid();
  pc.target_component = link.target_compid();
  if (o.mode == vehicle::StickMode::Attitude) {  // the board's own Stabilized stick scaling
    vehicle::ParamClient params(link);
    const std::pair<const char*, double*> wanted[] = {{"MPC_MAN_TILT_MAX", &pc.max_tilt_rad}, {"MPC_THR_HOVER", &pc.thr_hover},
                                                      {"MPC_MANTHR_MIN", &pc.thr_min}, {"MPC_THR_MAX", &pc.thr_max}};
    for (const auto& [name, value] : wanted) {
      if (auto p = params.get(name)) *value = std::string(name) == "MPC_MAN_TILT_MAX" ? p->as_double() * M_PI / 180.0 : p->as_double();
      else log_info(g, std::string("hitl fly: could not read ") + name + " (" + p.error().message + "); assuming PX4's default");
    }
  }
  std::optional<double> home_amsl_m;
  std::optional<std::array<double, 3>> origin_NED_m;
  std::array<double, 3> p_NED_m{}, v_NED_m_s{};
  double yaw_NED_rad = 0, t_s = 0;
  // Through a session, the simulator's ground truth (ODOMETRY from its own system id, type MOCAP).
  std::optional<std::array<double, 3>> truth_NED_m, truth_origin_NED_m;
  link.on_other_systems([&](const mavlink::Frame& f) {
    if (f.sysid != hil::kSimulatorSystemId || !f.is<msg::Odometry>()) return;
    const auto odo = f.as<msg::Odometry>();
    if (odo.estimator_type != static_cast<uint8_t>(mavlink::MavEstimatorType::Mocap)) return;
    truth_NED_m = std::array<double, 3>{odo.x, odo.y, odo.z};
  });
  bool have_yaw = false;
  nlohmann::json trace = nlohmann::json::array();
  std::optional<vehicle::TrajectoryPilot> pilot;
  vehicle::PilotState last_state = vehicle::PilotState::Init;
  auto on_frame = [&](const mavlink::Frame& f) {
    if (f.is<msg::GlobalPositionInt>() && !home_amsl_m) {
      const auto p = f.as<msg::GlobalPositionInt>();
      home_amsl_m = (p.alt - p.relative_alt) / 1000.0;
    } else if (f.is<msg::Attitude>()) {
      yaw_NED_rad = f.as<msg::Attitude>().yaw;
      have_yaw = true;
    } else if (f.is<msg::LocalPositionNed>()) {
      const auto l = f.as<msg::LocalPositionNed>();
      p_NED_m = {l.x, l.y, l.z};
      v_NED_m_s = {l.vx, l.vy, l.vz};
      if (!origin_NED_m) origin_NED_m = p_NED_m;
      t_s = l.time_boot_ms / 1000.0;
    }
    if (pilot) pilot->on_board_frame(f);
    return false;
  };
  // Wait for the estimate and home before the pilot starts.
  link.wait(o.wait_s, [&](const mavlink::Frame& f) {
    on_frame(f);
    return home_amsl_m && origin_NED_m && have_yaw;
  });
  if (!home_amsl_m || !origin_NED_m)
    return finish(g, "trajectory", false, "no position estimate from the board (LOCAL_POSITION_NED, GLOBAL_POSITION_INT)");
  pc.home_alt_msl_m = *home_amsl_m;
  pilot.emplace(std::move(trajectory), pc);
  const double start_s = t_s;
  while (!pilot->finished()) {
    link.wait(0.02, on_frame);
    vehicle::PilotPose pose;
    // NED -> ENU relative to where the vehicle was at the start; yaw: ENU = pi/2 - NED heading.
    pose.p_ENU_m = {p_NED_m[1] - (*origin_NED_m)[1], p_NED_m[0] - (*origin_NED_m)[0], -(p_NED_m[2] - (*origin_NED_m)[2])};
    pose.v_ENU_m_s = {v_NED_m_s[1], v_NED_m_s[0], -v_NED_m_s[2]};
    pose.yaw_ENU_rad = vehicle::wrap_pi(M_PI / 2 - yaw_NED_rad);
    const auto state = pilot->state();
    if (truth_NED_m && !truth_origin_NED_m && (state == vehicle::PilotState::Init || state == vehicle::PilotState::Arm))
      truth_origin_NED_m = truth_NED_m;  // at rest, where the estimate's origin was taken
    std::optional<vehicle::PilotPose> truth;
    if (truth_NED_m && truth_origin_NED_m) {
      const auto& t = *truth_NED_m;
      const auto& t0 = *truth_origin_NED_m;
      truth.emplace();
      truth->p_ENU_m = {t[1] - t0[1], t[0] - t0[0], -(t[2] - t0[2])};
      pilot->observe_truth(t_s - start_s, *truth);
    }
    auto out = pilot->step(t_s - start_s, pose);
    for (const auto& c : out.commands) link.send(c);
    if (out.rc) link.send(*out.rc);
    if (out.event && !g.quiet) std::cerr << "hitl fly: " << *out.event << '\n';
    if (pilot->state() == vehicle::PilotState::Trajectory && g.json) {
      nlohmann::json row = {{"t_s", t_s - start_s}, {"p_enu_m", pose.p_ENU_m}};
      if (truth) row["truth_p_enu_m"] = truth->p_ENU_m;
      trace.push_back(std::move(row));
    }
    if (pilot->state() != last_state) last_state = pilot->state();
  }
  const auto track = pilot->tracking();
  const auto truth_track = pilot->truth_tracking();
  char text[300];
  int n = std::snprintf(text, sizeof text, "%s%s; %s mode; tracking error (board's estimate) RMS %.2f m, max %.2f m",
                        vehicle::to_string(pilot->state()), pilot->failure().empty() ? "" : (": " + pilot->failure()).c_str(),
                        vehicle::to_string(o.mode), track.rms_m, track.max_m);
  if (truth_track.samples > 0 && n > 0 && static_cast<std::size_t>(n) < sizeof text)
    std::snprintf(text + n, sizeof text - n, "; against the simulator's truth RMS %.2f m, max %.2f m", truth_track.rms_m,
                  truth_track.max_m);
  const auto or_null = [&](double v) { return truth_track.samples > 0 ? nlohmann::json(v) : nlohmann::json(nullptr); };
  return finish(g, "trajectory", pilot->state() == vehicle::PilotState::Done, text,
                {{"state", vehicle::to_string(pilot->state())},
                 {"mode", vehicle::to_string(o.mode)},
                 {"rms_m", track.rms_m},
                 {"max_m", track.max_m},
                 {"samples", track.samples},
                 {"truth_rms_m", or_null(truth_track.rms_m)},
                 {"truth_max_m", or_null(truth_track.max_m)},
                 {"truth_samples", truth_track.samples},
                 {"trace", trace}});
}

int run_fly(const GlobalOptions& g, const FlyOptions& o, const std::string& action) {
  std::optional<vehicle::Trajectory> trajectory;
  if (action == "trajectory") {  // a bad file is refused before anything is sent
    auto t = vehicle::Trajectory::load(o.trajectory_file);
    if (!t) {
      log_error("fly", t.error().message);
      return kExitUsage;
    }
    trajectory = std::move(t.value());
  }
  auto link = vehicle::VehicleLink::connect(o.link);
  if (!link) {
    log_error("fly", link.error().message);
    return kExitFailed;
  }
  log_info(g, "hitl fly " + action + ": autopilot " + std::to_string((*link)->target_sysid()) + " " + (*link)->description());
  if (trajectory) return fly_trajectory(g, o, **link, std::move(*trajectory));
  vehicle::CommandClient commands(**link);
  const bool progress = ::isatty(STDERR_FILENO) == 1 && !g.quiet;

  if (action == "hold") {
    auto r = commands.send(mavlink::cmd::kDoSetMode, {1, 4, 3, 0, 0, 0, 0});
    if (!r) return finish(g, "hold", false, r.error().message);
    if (!r->accepted()) return finish(g, "hold", false, "Hold " + r->text());
    const bool shown = (*link)->wait(5, [](const mavlink::Frame& f) {
      return f.is<msg::Heartbeat>() && f.as<msg::Heartbeat>().custom_mode == kPx4Hold;
    });
    return finish(g, "hold", shown, shown ? "holding position" : "Hold accepted, but HEARTBEAT did not show it within 5 s");
  }

  if (action == "takeoff") {
    double target_m = 2.5;
    float param7 = NAN;  // NaN: the board's MIS_TAKEOFF_ALT above home
    if (o.alt_m) {
      // NAV_TAKEOFF's altitude is AMSL: home's altitude from GLOBAL_POSITION_INT (alt - relative_alt).
      std::optional<double> home_amsl_m;
      (*link)->wait(3, [&](const mavlink::Frame& f) {
        if (!f.is<msg::GlobalPositionInt>()) return false;
        const auto p = f.as<msg::GlobalPositionInt>();
        home_amsl_m = (p.alt - p.relative_alt) / 1000.0;
        return true;
      });
      if (!home_amsl_m) return finish(g, "takeoff", false, "no GLOBAL_POSITION_INT from the board: is its position estimate valid?");
      target_m = *o.alt_m;
      param7 = static_cast<float>(*home_amsl_m + *o.alt_m);
    } else if (auto p = vehicle::ParamClient(**link).get("MIS_TAKEOFF_ALT")) {
      target_m = p->as_double();
    }
    // A refusal while the board's preflight checks are pending is retried within --wait, saying why.
    const double give_up_s = monotonic_s() + o.wait_s;
    auto r = commands.send(mavlink::cmd::kNavTakeoff, {0, 0, 0, NAN, NAN, NAN, param7});
    while (r && !r->accepted() && r->pending() && monotonic_s() < give_up_s) {
      log_info(g, "hitl fly takeoff: waiting for the board: " + r->text());
      (*link)->wait(1.0, [](const mavlink::Frame&) { return false; });
      r = commands.send(mavlink::cmd::kNavTakeoff, {0, 0, 0, NAN, NAN, NAN, param7});
    }
    if (!r) return finish(g, "takeoff", false, r.error().message);
    if (!r->accepted()) return finish(g, "takeoff", false, "Takeoff " + r->text());
    double alt_m = 0;
    const bool reached = (*link)->wait(o.wait_s, [&](const mavlink::Frame& f) {
      if (!f.is<msg::GlobalPositionInt>()) return false;
      alt_m = f.as<msg::GlobalPositionInt>().relative_alt / 1000.0;
      if (progress) std::fprintf(stderr, "\raltitude %5.2f / %.2f m", alt_m, target_m);
      return alt_m >= target_m - 0.3;
    });
    if (progress) std::fprintf(stderr, "\n");
    char text[128];
    std::snprintf(text, sizeof text, reached ? "at %.2f m (target %.2f m)" : "only %.2f m of %.2f m after the timeout", alt_m, target_m);
    return finish(g, "takeoff", reached, text, {{"altitude_m", alt_m}, {"target_m", target_m}});
  }

  // land: NAV_LAND, then wait for the board to detect the touchdown and disarm.
  auto r = commands.send(mavlink::cmd::kNavLand, {0, 0, 0, NAN, NAN, NAN, NAN});
  if (!r) return finish(g, "land", false, r.error().message);
  if (!r->accepted()) return finish(g, "land", false, "Land " + r->text());
  double alt_m = NAN;
  const bool disarmed = (*link)->wait(o.wait_s, [&](const mavlink::Frame& f) {
    if (f.is<msg::GlobalPositionInt>()) {
      alt_m = f.as<msg::GlobalPositionInt>().relative_alt / 1000.0;
      if (progress) std::fprintf(stderr, "\raltitude %5.2f m", alt_m);
    }
    return f.is<msg::Heartbeat>() && (f.as<msg::Heartbeat>().base_mode & mavlink::mode_flag::kSafetyArmed) == 0;
  });
  if (progress) std::fprintf(stderr, "\n");
  return finish(g, "land", disarmed, disarmed ? "landed and disarmed" : "not disarmed after the timeout (still landing?)",
                {{"altitude_m", std::isfinite(alt_m) ? nlohmann::json(alt_m) : nlohmann::json(nullptr)}});
}

}  // namespace

void add_fly_command(CLI::App& app, GlobalOptions& options, RunState& state) {
  auto o = std::make_shared<FlyOptions>();
  auto* sub = app.add_subcommand("fly", "Take off, land, hold or fly a trajectory file, and wait for the outcome");
  sub->require_subcommand(1);
  add_link_options(sub, o->link);
  sub->add_option("--wait", o->wait_s, "Seconds to wait for the outcome (takeoff: also retried while the board's preflight checks are pending)")->capture_default_str()->check(positive_number());
  sub->footer("Arm first (hitl arm). Exit: 0 the outcome was seen, 1 refused or timed out.");
  auto add = [&](const char* name, const char* help) {
    auto* c = sub->add_subcommand(name, help);
    c->callback([&options, &state, o, action = std::string(name)]() { state.exit_code = run_fly(options, *o, action); });
    return c;
  };
  add("takeoff", "NAV_TAKEOFF; done when the altitude is reached")
      ->add_option("--alt", o->alt_m, "Metres above home (default: the board's MIS_TAKEOFF_ALT)")->check(positive_number());
  add("land", "NAV_LAND; done when the board has landed and disarmed");
  add("hold", "Switch to Hold (PX4 AUTO.LOITER); done when HEARTBEAT shows it");
  auto* traj = add("trajectory",
                   "The spec's trajectory_rc automation from the host: arm, take off, fly the waypoints by stick "
                   "(RC_CHANNELS_OVERRIDE), hold, land, disarm; report the tracking error (--json: the trace)");
  traj->add_option("FILE", o->trajectory_file, "Waypoints {t, x, y, z, yaw} in ENU metres/radians")->required()
      ->check(CLI::ExistingFile);
  traj->add_option("--rate", o->rc_rate_hz, "RC_CHANNELS_OVERRIDE rate, Hz")->capture_default_str()->check(number_in(2.0, 100.0));
  traj->add_option("--mode", o->mode,
                   "velocity: Position mode, sticks are velocities; attitude: Stabilized, sticks are tilt and thrust "
                   "(the pilot closes position and velocity itself)")
      ->transform(CLI::CheckedTransformer(std::map<std::string, vehicle::StickMode>{{"velocity", vehicle::StickMode::Velocity},
                                                                                  {"attitude", vehicle::StickMode::Attitude}}))
      ->default_str("velocity");
}

}  // namespace hitl::cli
