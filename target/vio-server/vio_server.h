// voxl-hitl-vio-server's loop: one thread. poll() on the UDP socket, the pipes' request and
// inotify descriptors and a signal descriptor; each ODOMETRY becomes one vio_data_t on hitl_vio
// and one ext_vio_data_t on hitl_vio_extended (odometry_to_vio.h); once a second the status file
// is rewritten. SIGTERM / SIGINT end it cleanly: the pipes and the status file are removed.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "base/common/expected.h"
#include "target/vio-server/odometry_receiver.h"
#include "target/vio-server/pipe_server.h"
#include "target/vio-server/server_status.h"
#include "target/vio-server/vio_server_config.h"

namespace hitl::vio {

inline constexpr const char* kServerName = "voxl-hitl-vio-server";
inline constexpr const char* kVioPipeName = "hitl_vio";                  ///< vio_data_t
inline constexpr const char* kExtendedVioPipeName = "hitl_vio_extended";  ///< ext_vio_data_t
/// hitl_vio_extended's pipe size: 1 MiB (/proc/sys/fs/pipe-max-size's default), 199 records, 0.8 s at 250 Hz.
inline constexpr int kExtendedPipeSize_bytes = 1024 * 1024;
/// At most this many malformed-datagram / invalid-ODOMETRY lines are logged one by one; after
/// that, one summary line per kLogSummaryPeriod_s.
inline constexpr int kDetailedLogLines = 10;
inline constexpr double kLogSummaryPeriod_s = 10.0;

struct VioServerOptions {
  VioServerConfig config;
  std::string mpa_dir = kDefaultMpaBaseDir;     ///< --mpa-dir
  std::string status_file = kDefaultStatusFile;  ///< --status-file
  /// --vision-hub-fifo: hitl_vio as the single FIFO voxl-vision-hub's en_hitl reader opens
  /// (raw_fifo_pipe.h) instead of an MPA pipe directory.
  bool vision_hub_fifo = false;
};

class VioServer {
 public:
  using Log = std::function<void(const std::string&)>;

  /// Binds the UDP socket and creates both pipes; fails saying which and why.
  static Expected<std::unique_ptr<VioServer>> start(const VioServerOptions& options, Log log);
  ~VioServer();

  /// Serves until `signal_fd` (a signalfd for SIGTERM / SIGINT) becomes readable.
  Status run(int signal_fd);
  uint16_t port() const;

 private:
  VioServer(VioServerOptions options, Log log);
  void on_odometry(const mavlink::msg::Odometry& odometry);
  void on_malformed(const std::string& why);
  void flush_events();
  void report();
  ServerStatus status() const;

  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace hitl::vio
