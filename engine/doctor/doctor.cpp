#include "engine/doctor/doctor.h"

#include <cmath>

#include "base/common/clock.h"
#include "base/contract/board_ports.h"
#include "base/contract/data_rates.h"
#include "base/contract/session_status.h"
#include "base/mavlink/enums.h"
#include "base/mavlink/messages.h"
#include "engine/doctor/apps_shell.h"
#include "engine/doctor/check_catalog.h"
#include "engine/doctor/estimator_checks.h"
#include "engine/doctor/host_checks.h"
#include "engine/doctor/host_probe.h"
#include "engine/doctor/link_checks.h"
#include "engine/doctor/observations.h"
#include "engine/doctor/param_checks.h"
#include "engine/doctor/px4_checks.h"
#include "engine/doctor/sensor_checks.h"
#include "engine/doctor/session_probe.h"
#include "engine/doctor/simulator_checks.h"
#include "engine/doctor/vio_checks.h"
#include "engine/px4/px4_instance.h"
#include "engine/vehicle/firmware_version.h"
#include "engine/vehicle/param_client.h"
#include "engine/vehicle/shell_client.h"
#include "engine/vehicle/shell_poller.h"

namespace hitl::doctor {
namespace {

namespace msg = mavlink::msg;

constexpr double kShellTimeout_s = 3.0;
constexpr const char* kVioStatusCommand = "voxl-hitl-vio-server --status --json";

/// Everything the board-facing checks decide on.
struct BoardFindings {
  Expected<std::string> link = Error::failed("not connected");
  Observations seen;
  Expected<std::string> mavlink_status = Error::failed("no link to the board");
  DspHitlRead dsp_first, dsp_second;
  Expected<std::vector<vehicle::Param>> params = Error::failed("no link to the board");
  Expected<std::string> commander_check = Error::failed("not needed");
  BoardOutput vio_status = Error::failed("no link to the board");
  BoardOutput vio_active = Error::failed("no link to the board");
  BoardOutput vio_pipes = Error::failed("no link to the board");
  BoardOutput vision_hub = Error::failed("no link to the board");
  std::optional<std::string> firmware;  ///< AUTOPILOT_VERSION, asked only of PX4 that the session started
};

void request_message(vehicle::VehicleLink& link, uint32_t id) {
  msg::CommandLong c;
  c.target_system = link.target_sysid();
  c.target_component = link.target_compid();
  c.command = mavlink::cmd::kRequestMessage;
  c.param1 = static_cast<float>(id);
  link.send(c);
}

bool needs_commander_check(const Observations& seen) {
  if (!seen.heartbeat || seen.heartbeat->armed()) return false;
  if (!seen.sys_status || (seen.sys_status->present & mavlink::sys_status::kPrearmCheck) == 0) return true;
  return (seen.sys_status->health & mavlink::sys_status::kPrearmCheck) == 0;
}

BoardFindings examine_board(const DoctorOptions& o, const AppsShell* adb_shell, const ProgressSink& progress) {
  BoardFindings b;
  ObservationTracker tracker;
  progress("connecting to the autopilot (" + o.link.connect + ")");
  auto link = vehicle::VehicleLink::connect(o.link);
  if (!link) {
    b.link = link.error();
    b.seen = tracker.observations();
    return b;
  }
  vehicle::VehicleLink& l = **link;
  b.link = l.description();
  l.on_other_systems([&](const mavlink::Frame& f) { tracker.on_other_frame(f, monotonic_s()); });
  auto listen = [&](double s) {
    l.wait(s, [&](const mavlink::Frame& f) {
      tracker.on_autopilot_frame(f, monotonic_s());
      return false;
    });
  };
  vehicle::ShellClient shell(l);
  std::string shell_broken;
  auto run_shell = [&](const std::string& line) -> Expected<std::string> {
    if (!shell_broken.empty()) return Error::failed(shell_broken);
    auto r = shell.run(line, kShellTimeout_s);
    if (!r) shell_broken = "the shell did not answer an earlier command (" + r.error().message + ")";
    return r;
  };

  progress("reading " + std::string(vehicle::kDspHitlStatusCommand) + " and mavlink status");
  b.dsp_first = {run_shell(vehicle::kDspHitlStatusCommand), monotonic_s()};
  b.mavlink_status = run_shell("mavlink status");
  progress("listening to the board and the session for " + std::to_string(o.listen_s).substr(0, 3) + " s");
  request_message(l, msg::EstimatorStatus::kId);
  request_message(l, msg::SysStatus::kId);
  listen(o.listen_s);
  b.dsp_second = {run_shell(vehicle::kDspHitlStatusCommand), monotonic_s()};

  progress("reading the parameters");
  vehicle::ParamClient params(l);
  auto all = params.download();
  if (all) b.params = std::move(all.value());
  else b.params = all.error();

  if (needs_commander_check(tracker.observations())) b.commander_check = run_shell("commander check");

  // The armed bit of HIL_ACTUATOR_CONTROLS and HEARTBEAT's are heard a second apart: a
  // disagreement may be an arming in between, so listen once more before calling it one.
  const auto& seen = tracker.observations();
  if (seen.heartbeat && seen.session.actuator_armed && *seen.session.actuator_armed >= 0 &&
      (*seen.session.actuator_armed == 1) != seen.heartbeat->armed())
    listen(1.5);

  // PX4 SITL that the session started (it says sim_px4): its version; it has no VOXL2 apps processor
  const bool px4_sitl = session_runs_px4(tracker.observations().session);
  if (px4_sitl) b.firmware = vehicle::request_firmware_version(l);
  if (o.vio && !px4_sitl) {
    progress("asking the board's apps processor about VIO");
    const AppsShell px4 = AppsShell::px4(run_shell);
    const AppsShell& apps = adb_shell != nullptr ? *adb_shell : px4;
    b.vio_status = apps.run(kVioStatusCommand, true);
    b.vio_active = apps.run("systemctl is-active voxl-hitl-vio-server", false);
    b.vio_pipes = apps.run("ls /run/mpa", false);
    b.vision_hub = apps.run("cat /etc/modalai/voxl-vision-hub.conf", false);
  }
  b.seen = tracker.observations();
  return b;
}

/// The build (--px4 DIR), the instances hitl sim --px4 would find busy before a free one, and what
/// hitl gives PX4.
Px4Findings find_px4(const DoctorOptions& o) {
  Px4Findings f;
  if (!o.px4_dir.empty()) f.build = px4::find_px4_build(o.px4_dir);
  for (int i = 0; i <= px4::Px4Instance::kMax; ++i) {
    const std::string why = px4::px4_instance_busy(px4::Px4Instance{i});
    if (why.empty()) {
      f.first_free = i;
      break;
    }
    if (f.busy.size() < 4) f.busy.push_back({i, why});
  }
  f.expected = o.px4_expected_params;
  return f;
}

}  // namespace

std::vector<CheckResult> run_doctor(const DoctorOptions& o, const ResultSink& on_result, const ProgressSink& progress) {
  std::vector<CheckResult> results;
  auto emit = [&](CheckResult r) {
    results.push_back(r);
    if (on_result) on_result(results.back());
  };
  const ProgressSink say = progress ? progress : [](const std::string&) {};

  // host
  emit(route_check(o.link.target_ip, list_interfaces()));
  const bool adb_wanted = o.adb || !o.adb_serial.empty();
  Expected<net::AdbDevices> listing = Error::failed("--adb not given");
  if (adb_wanted) {
    say("running adb devices");
    listing = net::list_adb_devices();
  }
  emit(adb_check(adb_wanted, o.adb_serial, listing));
  std::optional<AppsShell> adb_shell;
  if (listing) {
    if (auto chosen = net::choose_adb_device(listing->devices, o.adb_serial))
      adb_shell = AppsShell::adb(net::Adb(listing->adb_path, *chosen));
  }
  std::vector<PortProbe> probes{probe_udp_port(o.hil_port, "HIL")};
  if (o.vio) probes.push_back(probe_udp_port(o.vio_port, "VIO"));
  const CheckResult ports = ports_check(probes, is_loopback_host(o.link.target_ip));

  // everything the board says, then the checks on it in order
  BoardFindings b = examine_board(o, adb_shell ? &*adb_shell : nullptr, say);
  if (!b.seen.session.heard()) {
    say("no session status on the link: asking 127.0.0.1:" + std::to_string(o.link.session_port) + " directly");
    ObservationTracker probe;
    probe_session(o.link.session_port, o.listen_s,
                  [&](const mavlink::Frame& f, double t_s) { probe.on_other_frame(f, t_s); });
    b.seen.session = probe.observations().session;
  }
  const Observations& seen = b.seen;
  const SessionStatus& session = seen.session;
  const bool linked = b.link.ok();
  const std::string no_link = "no link to the board";
  auto skipped = [&](const char* id) { return make_result(id, Verdict::Skip, no_link); };
  // Against PX4 SITL that the session started, the VOXL2's own checks (its ports, HIL mode, HIL
  // instance, actuator flags, dsp_hitl, HITL parameters, VIO) have nothing to look at.
  const bool px4_sitl = session_runs_px4(session);
  auto board_only = [&](const char* id) { return make_result(id, Verdict::Skip, px4_sitl_skip_reason(session)); };
  emit(px4_sitl ? board_only(check::kPorts) : ports);

  // link
  emit(heartbeat_check(b.link, seen.heartbeat));
  emit(px4_sitl ? board_only(check::kHilMode) : hil_mode_check(seen.heartbeat));
  emit(px4_sitl ? board_only(check::kMavlinkInstances)
       : linked ? mavlink_instances_check(b.mavlink_status, o.hil_port)
                : skipped(check::kMavlinkInstances));
  const std::string no_session = no_session_reason(o.link.session_port);
  emit(session.heard() ? actuators_check(session) : make_result(check::kActuators, Verdict::Skip, no_session));
  emit(px4_sitl          ? board_only(check::kActuatorFlags)
       : session.heard() ? actuator_flags_check(session)
                         : make_result(check::kActuatorFlags, Verdict::Skip, no_session));
  emit(session.heard() ? armed_state_check(session, seen.heartbeat) : make_result(check::kArmedState, Verdict::Skip, no_session));

  // board sensors: the board's clock runs at the session's pace in lockstep, else at real time
  // (a real-time factor from the network that is not a positive number counts as real time)
  const double rtf = session.rtf && std::isfinite(*session.rtf) && *session.rtf > 0 ? *session.rtf : 1.0;
  const double pace = session.lockstep.value_or(false) ? rtf : 1.0;
  const std::optional<bool> sending = session.heard() ? std::optional<bool>(!session.paused.value_or(false)) : std::nullopt;
  emit(px4_sitl ? board_only(check::kDspHitl)
       : linked ? dsp_hitl_check(b.dsp_first, b.dsp_second, pace, sending)
                : skipped(check::kDspHitl));

  // parameters (the board's HITL set; PX4 SITL's are px4-params below)
  if (px4_sitl) {
    for (const char* id : {check::kParamsSystem, check::kParamsCalibration, check::kParamsEkf2, check::kParamsArming,
                           check::kParamsAllocation})
      emit(board_only(id));
  } else if (linked) {
    for (auto& r : param_checks(b.params)) emit(std::move(r));
  } else {
    for (const char* id : {check::kParamsSystem, check::kParamsCalibration, check::kParamsEkf2, check::kParamsArming,
                           check::kParamsAllocation})
      emit(skipped(id));
  }

  // estimator, arming
  emit(linked ? estimator_check(seen.estimator) : skipped(check::kEstimator));
  emit(linked ? arming_check(seen.heartbeat, seen.sys_status, seen.statustext, b.commander_check) : skipped(check::kArming));

  // VIO
  if (!o.vio || px4_sitl) {
    for (const char* id : {check::kVioOdometry, check::kVioServer, check::kVioPipe, check::kVisionHub})
      emit(px4_sitl ? board_only(id) : vio_skipped(id, "--no-vio: VIO not used"));
  } else {
    emit(vio_odometry_check(b.vio_status, hitl::kVioRate_hz * rtf));  // ODOMETRY is paced by simulated time
    emit(vio_server_check(b.vio_active));
    emit(vio_pipe_check(b.vio_pipes));
    emit(vision_hub_check(b.vision_hub));
  }

  // simulator
  const std::optional<bool> arriving = linked && b.dsp_first.text && b.dsp_second.text
                                           ? std::optional<bool>(dsp_hitl_counting(b.dsp_first, b.dsp_second))
                                           : std::nullopt;
  emit(session_check(session, o.link.session_port, arriving));
  emit(paused_check(session));
  emit(real_time_check(session));
  emit(late_ticks_check(session));
  emit(loop_latency_check(session));

  // PX4 SITL: the build (--px4 DIR), the instance, PX4 connected, its parameters as hitl set them
  Px4Findings px4 = find_px4(o);
  px4.running_version = b.firmware;
  emit(px4_build_check(px4));
  emit(px4_instance_check(px4, session));
  emit(px4_connected_check(px4, session, seen.heartbeat));
  emit(px4_params_check(px4, session, b.params));
  return results;
}

}  // namespace hitl::doctor
