// `hitl inspect`'s engine: reads MAVLink from a UDP port, a connection or a .tlog,
// measures it (TrafficStats), optionally records it, and reports each frame and
// each second to an observer. Never prints.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "base/common/expected.h"
#include "base/contract/board_ports.h"
#include "base/mavlink/frame_encoder.h"
#include "base/mavlink/frame_parser.h"
#include "base/mavlink/message_set.h"
#include "engine/mavlink/tlog.h"
#include "engine/mavlink/tlog_timeline.h"
#include "engine/net/udp_endpoint.h"
#include "engine/telemetry/traffic_stats.h"

namespace hitl::inspect {

struct InspectConfig {
  enum class Source { Port, Connect, Tlog };
  Source source = Source::Port;
  std::string bind_address = "0.0.0.0";  ///< --bind (Port)
  uint16_t port = 0;                      ///< --port: listen passively
  std::string connect;                    ///< --connect HOST:PORT: send HEARTBEAT at 1 Hz so a PX4 instance streams to us
  uint16_t local_port = kDirectLocalPort;  ///< --local-port (Connect): fixed, since PX4 keeps the first port it hears
  std::string tlog_path;                  ///< --tlog FILE: offline, as fast as it reads
  std::string record_path;                ///< --record FILE.tlog: save every frame received
  double duration_s = 0;                  ///< --duration: 0 = until stopped (tlog: log time)
  uint64_t count = 0;                     ///< --count: stop after this many frames (0 = no limit)
  std::vector<uint32_t> count_ids;        ///< the ids --count counts (empty: every frame)
  uint8_t sysid = 255;                    ///< our HEARTBEAT identity (Connect)
  uint8_t compid = 190;
  mavlink::ParserOptions parser;
};

class Inspector {
 public:
  class Observer {
   public:
    virtual ~Observer() = default;
    virtual void on_frame(const mavlink::Frame& /*frame*/, const std::string& /*source*/, int64_t /*t_unix_ns*/) {}
    /// Once, when a table that grows with the input (message ids, senders) reaches its bound.
    virtual void on_notice(const std::string& /*text*/) {}
    /// Once a second of wall time, with the stats so far.
    virtual void on_tick(const telemetry::TrafficSummary& /*summary*/) {}
    /// --connect: the first refused send to the partner, at once (errno and the likely fix).
    virtual void on_send_error(const std::string& /*text*/) {}
  };
  enum class EndReason { Duration, Count, EndOfLog, Stopped };

  static Expected<std::unique_ptr<Inspector>> open(const InspectConfig& config, const mavlink::MessageSet& messages);

  /// Runs until the duration or count is reached, the log ends, or `stop` turns true.
  Expected<EndReason> run(const std::atomic<bool>& stop, Observer& observer);

  telemetry::TrafficSummary summary() const;
  /// Where the Connect source sends ("127.0.0.1:14558") or the Port source listens.
  std::string where() const;
  /// Frames that could not be written to --record (a full disk is reported, not ignored).
  bool record_failed() const { return recorder_ && !recorder_->ok(); }
  /// Why (mavlink::TlogWriter::error(): the file and errno's words), empty while ok.
  std::string record_error() const { return recorder_ ? recorder_->error() : std::string(); }
  /// --connect: HEARTBEATs the kernel refused to send (an unreachable partner).
  uint64_t send_errors() const { return endpoint_ ? endpoint_->stats().send_errors : 0; }

 private:
  Inspector(const InspectConfig& config, const mavlink::MessageSet& messages);
  Expected<EndReason> run_live(const std::atomic<bool>& stop, Observer& observer);
  Expected<EndReason> run_tlog(const std::atomic<bool>& stop, Observer& observer);
  void handle(const mavlink::Frame& frame, const std::string& source, int64_t t_ns, Observer& observer);
  void send_heartbeat(Observer& observer);
  bool counted_out() const { return config_.count > 0 && counted_ >= config_.count; }

  InspectConfig config_;
  mavlink::FrameParser parser_;
  telemetry::TrafficStats stats_;
  std::optional<net::UdpEndpoint> endpoint_;
  std::optional<mavlink::TlogTimeline> reader_;
  std::optional<mavlink::TlogWriter> recorder_;
  uint64_t counted_ = 0;
  mavlink::FrameEncoder encoder_;
  int64_t now_ns_ = 0;  ///< "now" on the source's clock (wall for live, log time for tlog)
};

}  // namespace hitl::inspect
