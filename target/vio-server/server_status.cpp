#include "target/vio-server/server_status.h"

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

namespace hitl::vio {
namespace {

int64_t now_unix_ms() {
  return std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::system_clock::now().time_since_epoch()).count();
}

std::string fixed(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

}  // namespace

nlohmann::json to_json(const ServerStatus& s) {
  const ReceiverCounters& r = s.receiver;
  nlohmann::json pipes = nlohmann::json::array();
  for (const auto& p : s.pipes) {
    pipes.push_back({{"location", p.location},
                     {"type", p.type},
                     {"clients", p.clients},
                     {"records_written", p.counters.records_written},
                     {"records_dropped", p.counters.records_dropped},
                     {"clients_accepted", p.counters.clients_accepted},
                     {"requests_rejected", p.counters.requests_rejected}});
  }
  return {{"pid", s.pid},
          {"listen", s.listen},
          {"pipe_implementation", s.pipe_implementation},
          {"uptime_s", s.uptime_s},
          {"updated_unix_ms", s.updated_unix_ms},
          {"odometry_rate_hz", s.odometry_rate_hz},
          {"datagrams", r.datagrams},
          {"bytes", r.bytes},
          {"odometry", r.odometry},
          {"other_messages", r.other_messages},
          {"malformed_datagrams", r.malformed_datagrams},
          {"crc_errors", r.crc_errors},
          {"garbage_runs", r.garbage_runs},
          {"truncated", r.truncated},
          {"bad_incompat_flags", r.bad_incompat_flags},
          {"published", s.published},
          {"invalid_odometry", s.invalid_odometry},
          {"pipes", pipes}};
}

Expected<ServerStatus> status_from_json(const nlohmann::json& doc) {
  try {
    ServerStatus s;
    s.pid = doc.at("pid").get<int>();
    s.listen = doc.at("listen").get<std::string>();
    s.pipe_implementation = doc.at("pipe_implementation").get<std::string>();
    s.uptime_s = doc.at("uptime_s").get<double>();
    s.updated_unix_ms = doc.at("updated_unix_ms").get<int64_t>();
    s.odometry_rate_hz = doc.at("odometry_rate_hz").get<double>();
    ReceiverCounters& r = s.receiver;
    r.datagrams = doc.at("datagrams").get<uint64_t>();
    r.bytes = doc.at("bytes").get<uint64_t>();
    r.odometry = doc.at("odometry").get<uint64_t>();
    r.other_messages = doc.at("other_messages").get<uint64_t>();
    r.malformed_datagrams = doc.at("malformed_datagrams").get<uint64_t>();
    r.crc_errors = doc.at("crc_errors").get<uint64_t>();
    r.garbage_runs = doc.at("garbage_runs").get<uint64_t>();
    r.truncated = doc.at("truncated").get<uint64_t>();
    r.bad_incompat_flags = doc.at("bad_incompat_flags").get<uint64_t>();
    s.published = doc.at("published").get<uint64_t>();
    s.invalid_odometry = doc.at("invalid_odometry").get<uint64_t>();
    for (const auto& p : doc.at("pipes")) {
      PipeStatus ps;
      ps.location = p.at("location").get<std::string>();
      ps.type = p.at("type").get<std::string>();
      ps.clients = p.at("clients").get<int>();
      ps.counters.records_written = p.at("records_written").get<uint64_t>();
      ps.counters.records_dropped = p.at("records_dropped").get<uint64_t>();
      ps.counters.clients_accepted = p.at("clients_accepted").get<uint64_t>();
      ps.counters.requests_rejected = p.at("requests_rejected").get<uint64_t>();
      s.pipes.push_back(ps);
    }
    return s;
  } catch (const nlohmann::json::exception& e) {
    return Error{std::string("not a voxl-hitl-vio-server status report (") + e.what() + ")"};
  }
}

Status write_status_file(const std::string& path, const ServerStatus& status) {
  std::error_code ec;
  const auto dir = std::filesystem::path(path).parent_path();
  if (!dir.empty()) std::filesystem::create_directories(dir, ec);
  if (ec) return Error{"cannot create " + dir.string() + ": " + ec.message()};
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    out << to_json(status).dump() << "\n";
    if (!out) return Error{"cannot write " + tmp + ": " + std::strerror(errno)};
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) return Error{"cannot replace " + path + ": " + std::strerror(errno)};
  return Ok{};
}

Expected<StatusReport> read_status_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) return Error{"voxl-hitl-vio-server is not running (no status report at " + path + ")"};
  std::ostringstream text;
  text << in.rdbuf();
  const auto doc = nlohmann::json::parse(text.str(), nullptr, false);
  if (doc.is_discarded()) return Error{path + " is not JSON"};
  auto status = status_from_json(doc);
  if (!status.ok()) return Error{path + ": " + status.error().message};
  StatusReport report{status.value(), (now_unix_ms() - status->updated_unix_ms) / 1000.0};
  const int pid = report.status.pid;
  if (pid <= 0 || (::kill(pid, 0) != 0 && errno != EPERM)) {
    return Error{"voxl-hitl-vio-server is not running (process " + std::to_string(pid) + " of " + path + " has exited)"};
  }
  if (report.age_s > kStatusStaleAfter_s) {
    return Error{"voxl-hitl-vio-server (process " + std::to_string(pid) + ") has not reported for " +
                 fixed(report.age_s, 0) + " s (" + path + ")"};
  }
  return report;
}

std::string format_status(const StatusReport& report) {
  const ServerStatus& s = report.status;
  const ReceiverCounters& r = s.receiver;
  std::string out;
  out += "voxl-hitl-vio-server: process " + std::to_string(s.pid) + ", up " + fixed(s.uptime_s, 0) + " s, listening on UDP " +
         s.listen + ", pipes through " + s.pipe_implementation + " (report " + fixed(report.age_s, 1) + " s old)\n";
  out += "  ODOMETRY:  " + fixed(s.odometry_rate_hz, 1) + " Hz, " + std::to_string(r.odometry) + " received, " +
         std::to_string(s.published) + " published, " + std::to_string(s.invalid_odometry) + " invalid\n";
  out += "  datagrams: " + std::to_string(r.datagrams) + " (" + std::to_string(r.bytes) + " bytes), " +
         std::to_string(r.malformed_datagrams) + " malformed (" + std::to_string(r.crc_errors) + " checksum errors, " +
         std::to_string(r.garbage_runs) + " non-MAVLink runs, " + std::to_string(r.truncated) + " cut off, " +
         std::to_string(r.bad_incompat_flags) + " unknown incompat flags), " + std::to_string(r.other_messages) +
         " other messages ignored\n";
  for (const auto& p : s.pipes) {
    const std::string clients = p.clients < 0 ? "readers unknown" : std::to_string(p.clients) + " client(s)";
    out += "  " + p.location + " (" + p.type + "): " + clients + ", " +
           std::to_string(p.counters.records_written) + " records written, " + std::to_string(p.counters.records_dropped) +
           " dropped (client behind), " + std::to_string(p.counters.requests_rejected) + " requests refused\n";
  }
  return out;
}

}  // namespace hitl::vio
