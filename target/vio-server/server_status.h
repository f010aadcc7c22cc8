// What a running voxl-hitl-vio-server reports about itself: written once a second to a status
// file (JSON, replaced atomically), read back by `voxl-hitl-vio-server --status`.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "base/common/expected.h"
#include "target/vio-server/odometry_receiver.h"
#include "target/vio-server/pipe_server.h"

namespace hitl::vio {

inline constexpr const char* kDefaultStatusFile = "/run/voxl-hitl-vio-server/status.json";
/// A report older than this means the server is not running (it rewrites it every second).
inline constexpr double kStatusStaleAfter_s = 5.0;

struct PipeStatus {
  std::string location;  ///< "/run/mpa/hitl_vio/"
  std::string type;      ///< "vio_data_t"
  int clients = 0;       ///< -1: not known (a plain FIFO does not say who reads it)
  PipeCounters counters;
};

struct ServerStatus {
  int pid = 0;
  std::string listen;             ///< "0.0.0.0:14570"
  std::string pipe_implementation;
  double uptime_s = 0;
  int64_t updated_unix_ms = 0;    ///< wall clock of this report
  double odometry_rate_hz = 0;    ///< ODOMETRY received over the last report period
  ReceiverCounters receiver;
  uint64_t published = 0;         ///< poses published (one per valid ODOMETRY)
  uint64_t invalid_odometry = 0;  ///< ODOMETRY that could not be published (NaN, bad quaternion, frames)
  std::vector<PipeStatus> pipes;
};

nlohmann::json to_json(const ServerStatus& status);
Expected<ServerStatus> status_from_json(const nlohmann::json& doc);

/// Replaces `path` atomically (temporary file + rename), creating its directory.
Status write_status_file(const std::string& path, const ServerStatus& status);

struct StatusReport {
  ServerStatus status;
  double age_s = 0;  ///< how old the report is
};
/// Reads a running server's report. Fails, saying why, when there is none, it is unreadable, the
/// process is gone, or it is older than kStatusStaleAfter_s.
Expected<StatusReport> read_status_file(const std::string& path);

/// The report in words, for `--status`.
std::string format_status(const StatusReport& report);

}  // namespace hitl::vio
