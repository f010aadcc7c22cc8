#include "engine/campaign/flight_run.h"

#include <chrono>
#include <filesystem>
#include <fstream>

#include "base/common/bounded_read.h"
#include "engine/model/x500_defaults.h"
#include "engine/report/flight_log.h"
#include "engine/report/report.h"
#include "engine/sensors/vehicle_file.h"
#include "engine/vehicle/trajectory.h"

namespace hitl::campaign {

namespace {

const char* end_name(hil::Session::EndReason end) {
  switch (end) {
    case hil::Session::EndReason::Duration: return "duration";
    case hil::Session::EndReason::Stopped: return "stopped";
    case hil::Session::EndReason::FlightStackGone: return "flight_stack_gone";
    case hil::Session::EndReason::TrajectoryDone: return "trajectory_done";
    case hil::Session::EndReason::TrajectoryFailed: return "trajectory_failed";
  }
  return "stopped";
}

Expected<FlightResult> result_from_json(const nlohmann::json& j, const std::string& path);

Status write_json(const std::string& path, const nlohmann::json& j) {
  const std::string tmp = path + ".part";
  {
    std::ofstream out(tmp, std::ios::trunc);
    out << j.dump(2) << '\n';
    if (!out) return Error::unavailable("cannot write " + tmp);
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);  // whole or absent: a killed writer leaves no half file
  if (ec) return Error::unavailable("cannot write " + path + ": " + ec.message());
  return Ok{};
}

}  // namespace

void Px4FlightStack::configure(hil::SessionConfig& config) const {
  hil::Px4Options px4;
  if (campaign_.px4 && campaign_.px4->build) {
    px4.build = *campaign_.px4->build;
    px4.params = campaign_.px4->params;
  }
  px4.connect_timeout_s = kConnectTimeout_s;
  // Empty: beside the recording, FILE.px4/ and FILE.px4.log (kPx4WorkFolder, kPx4ConsoleFile), where
  // hitl report finds PX4's ULog as beside any hitl sim --px4 recording.
  px4.work_dir.clear();
  config.px4 = std::move(px4);
  config.vio = false;  // PX4 SITL's none_iris takes no ODOMETRY from hitl
}

StackFigures Px4FlightStack::figures(const hil::SessionSnapshot& s) const {
  StackFigures f;
  f.armed = s.stack_state.armed;
  f.mode = s.stack_state.mode;
  f.landed_state = s.stack_state.landed_state;
  auto count = [](const std::map<std::string, hil::StreamCount>& counts, const char* name) -> uint64_t {
    const auto it = counts.find(name);
    return it == counts.end() ? 0 : it->second.count;
  };
  f.hil_sensor_received = count(s.sent, "HIL_SENSOR");
  f.hil_gps_received = count(s.sent, "HIL_GPS");
  f.actuators_sent = count(s.received, "HIL_ACTUATOR_CONTROLS");
  f.malformed = s.crc_errors + s.parse_errors;
  return f;
}

bool reads_recording(const Campaign& campaign) {
  if (!campaign.expectations.empty()) return true;
  for (const auto& c : campaign.criteria)
    if (c.figure.rfind("ekf_test_ratios.", 0) == 0) return true;
  return false;
}

std::string flight_folder(const std::string& out_dir, const Flight& flight) {
  return (std::filesystem::path(out_dir) / "flights" / flight.id).string();
}

nlohmann::json to_json(const FlightResult& r) {
  nlohmann::json verdicts = nlohmann::json::array();
  for (const auto& v : r.verdicts) verdicts.push_back(to_json(v));
  return {{"index", r.index}, {"id", r.id}, {"name", r.name}, {"outcome", r.outcome}, {"reason", r.reason},
          {"criteria", verdicts}, {"summary_line", r.summary_line}, {"wall_s", r.wall_s}, {"process_wall_s", r.process_wall_s}};
}

Expected<FlightResult> read_result(const std::string& folder) {
  const std::string path = (std::filesystem::path(folder) / kResultFile).string();
  auto text = read_bounded_file(path, "flight result", 1 << 20);
  if (!text) return text.error();
  const auto j = nlohmann::json::parse(*text, nullptr, false);
  if (j.is_discarded() || !j.is_object()) return Error::input(path + ": not a flight result");
  try {
    return result_from_json(j, path);
  } catch (const nlohmann::json::exception& e) {  // a field of the wrong type: a damaged or hand-edited file
    return Error::input(path + ": not a flight result (" + e.what() + ")");
  }
}

Status write_result(const std::string& folder, const FlightResult& result) {
  return write_json((std::filesystem::path(folder) / kResultFile).string(), to_json(result));
}

namespace {

Expected<FlightResult> result_from_json(const nlohmann::json& j, const std::string& path) {
  FlightResult r;
  r.index = j.value("index", std::size_t{0});
  r.id = j.value("id", std::string());
  r.name = j.value("name", std::string());
  r.outcome = j.value("outcome", std::string());
  r.reason = j.value("reason", std::string());
  r.summary_line = j.value("summary_line", std::string());
  r.wall_s = j.value("wall_s", 0.0);
  r.process_wall_s = j.value("process_wall_s", 0.0);
  if (j.contains("criteria") && j["criteria"].is_array())
    for (const auto& v : j["criteria"]) {
      if (!v.is_object()) continue;
      Verdict d;
      d.criterion = v.value("criterion", std::string());
      d.figure = v.value("figure", std::string());
      d.ok = v.value("ok", false);
      d.value = v.contains("value") ? v["value"] : nlohmann::json(nullptr);
      d.limit = v.value("limit", std::string());
      d.message = v.value("message", std::string());
      r.verdicts.push_back(std::move(d));
    }
  if (r.outcome != "passed" && r.outcome != "failed" && r.outcome != "error") return Error::input(path + ": no outcome");
  return r;
}

}  // namespace

Expected<FlightResult> run_flight(const Campaign& campaign, const Flight& flight, FlightStack& stack, const std::string& out_dir,
                                  const std::atomic<bool>& stop, hil::Session::Observer& observer, bool& stopped) {
  const auto started = std::chrono::steady_clock::now();
  stopped = false;
  const std::string folder = flight_folder(out_dir, flight);
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec) return Error::unavailable("cannot make the flight's folder " + folder + ": " + ec.message());
  std::filesystem::remove(std::filesystem::path(folder) / kResultFile, ec);
  auto trajectory = vehicle::Trajectory::load(flight.trajectory->path);
  if (!trajectory) return trajectory.error();

  auto ports = stack.start();
  if (!ports) return ports.error().prefixed("the flight stack did not start: ");
  hil::SessionConfig cfg;
  cfg.target_ip = "127.0.0.1";
  cfg.bind_address = "127.0.0.1";
  cfg.hil_port = ports->hil_port;
  cfg.local_port = 0;    // the OS's port, kept by the session; the board answers whoever spoke to it
  cfg.vio = ports->vio_port != 0;
  cfg.vio_port = ports->vio_port;
  cfg.clients_port = 0;  // no clients: nothing else to bind, nothing to collide
  cfg.lockstep = true;
  cfg.speed = flight.speed;
  cfg.duration_s = campaign.sim_limit_s;
  const auto vehicle_file = sensors::default_vehicle_file();
  cfg.vehicle = vehicle_file.vehicle;
  cfg.sensor_units = vehicle_file.units;
  cfg.world = model::default_world_config();
  cfg.seed = flight.seed;
  cfg.trajectory = std::move(trajectory.value());
  cfg.faults = flight.fault_case->faults;
  cfg.record_path = (std::filesystem::path(folder) / kRecordingFile).string();
  stack.configure(cfg);
  auto session = hil::Session::create(cfg);
  if (!session) {
    stack.stop();
    return session.error();
  }
  auto end = (*session)->run(stop, observer);
  stack.stop();
  if (!end) return end.error();
  if (*end == hil::Session::EndReason::Stopped) {
    stopped = true;
    return Error::failed("stopped");
  }
  const auto snapshot = (*session)->snapshot();
  session->reset();  // the recording closed before the report reads it
  FlightResult r;
  r.index = flight.index;
  r.id = flight.id;
  r.name = flight.name;
  // The recording read back for the EKF's test ratios and the flight stack's events, when the
  // campaign judges them (it costs tens of milliseconds a flight: two passes over the .tlog).
  if (reads_recording(campaign)) {
    auto log = report::read_flight_log(cfg.record_path);
    r.figures = flight_summary_json(campaign, flight, snapshot, end_name(*end), stack.figures(snapshot), log ? &log.value() : nullptr);
    if (!log) r.figures["events_error"] = log.error().message;
  } else {
    r.figures = flight_summary_json(campaign, flight, snapshot, end_name(*end), stack.figures(snapshot), nullptr);
    r.figures.erase("ekf_test_ratios");
    r.figures.erase("events");
  }
  if (campaign.report) {
    auto written = report::write_report(cfg.record_path, (std::filesystem::path(folder) / kReportFile).string());
    r.figures["report"] = written ? nlohmann::json(written->html_path) : nlohmann::json(nullptr);
    if (!written) r.figures["report_error"] = written.error().message;
  }
  r.verdicts = judge(campaign, r.figures);
  r.outcome = passed(r.verdicts) ? "passed" : "failed";
  r.summary_line = summary_line(flight, r.figures);
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  if (auto ok = write_json((std::filesystem::path(folder) / kSummaryFile).string(), r.figures); !ok) return ok.error();
  if (auto ok = write_result(folder, r); !ok) return ok.error();
  return r;
}

}  // namespace hitl::campaign
