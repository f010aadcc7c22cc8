#include "engine/inspect/inspector.h"

#include "engine/net/link_spec.h"

#include "base/common/clock.h"
#include <algorithm>
#include <chrono>

#include "base/mavlink/enums.h"
#include "base/mavlink/heartbeat.h"
#include "base/mavlink/messages.h"

namespace hitl::inspect {
namespace {

using Clock = std::chrono::steady_clock;

}  // namespace

namespace {

/// --connect: the grammar's udp:HOST:PORT, or HOST:PORT as before (net::parse_udp_peer). Inspect
/// times each datagram as the kernel received it, so it takes UDP only; udpin:PORT is --port.
Expected<net::SocketAddress> connect_address(const std::string& text) {
  if (text.rfind("udpin:", 0) == 0)
    if (auto in = net::parse_link_spec(text))
      return Error::input("--connect '" + text + "': inspect listens with --port " + std::to_string(in->port) + ", not udpin:");
  auto spec = net::parse_udp_peer(text, "inspect times UDP datagrams as the kernel received them");
  if (!spec) return spec.error().prefixed("--connect ");
  auto peer = net::SocketAddress::resolve(spec->host, spec->port);
  if (!peer) return peer.error().prefixed("--connect: ");
  return peer;
}

}  // namespace

Inspector::Inspector(const InspectConfig& config, const mavlink::MessageSet& messages)
    : config_(config), parser_(messages, config.parser), encoder_(config.sysid, config.compid) {}

Expected<std::unique_ptr<Inspector>> Inspector::open(const InspectConfig& config, const mavlink::MessageSet& messages) {
  std::unique_ptr<Inspector> in(new Inspector(config, messages));
  switch (config.source) {
    case InspectConfig::Source::Port: {
      net::UdpEndpoint::Config ec;
      ec.name = "--port";
      ec.bind_address = config.bind_address;
      ec.bind_port = config.port;
      ec.policy = net::PartnerPolicy::LastSender;
      auto ep = net::UdpEndpoint::open(ec);
      if (!ep) return ep.error();
      in->endpoint_.emplace(std::move(ep.value()));
      break;
    }
    case InspectConfig::Source::Connect: {
      auto peer = connect_address(config.connect);
      if (!peer) return peer.error();
      net::UdpEndpoint::Config ec;
      ec.name = "--connect";
      ec.bind_address = peer->family() == AF_INET6 ? "::" : "0.0.0.0";
      ec.bind_port = config.local_port;
      ec.peer = *peer;
      ec.policy = net::PartnerPolicy::Fixed;
      auto ep = net::UdpEndpoint::open(ec);
      if (!ep) return ep.error().suffixed(" (is another hitl command talking to the board? run `hitl bridge`)");
      in->endpoint_.emplace(std::move(ep.value()));
      break;
    }
    case InspectConfig::Source::Tlog: {
      auto reader = mavlink::TlogReader::open(config.tlog_path, mavlink::TlogInput::FileOrPipe);
      if (!reader) return reader.error();
      in->reader_.emplace(std::move(reader.value()), &messages);
      break;
    }
  }
  if (!config.record_path.empty()) {
    auto writer = mavlink::TlogWriter::open(config.record_path);
    if (!writer) return writer.error();
    in->recorder_.emplace(std::move(writer.value()));
  }
  return in;
}

std::string Inspector::where() const {
  switch (config_.source) {
    case InspectConfig::Source::Port: return endpoint_->local_address().to_string();
    case InspectConfig::Source::Connect:
      return endpoint_->partner()->to_string() + " from " + endpoint_->local_address().to_string();
    case InspectConfig::Source::Tlog: return config_.tlog_path;
  }
  return "";
}

void Inspector::handle(const mavlink::Frame& frame, const std::string& source, int64_t t_ns, Observer& observer) {
  if (counted_out()) return;
  if (recorder_) recorder_->write(static_cast<uint64_t>(t_ns / 1000), frame.bytes());
  // An id the message set does not know has no checkable checksum: not a message (counted in the
  // parser's `unverified`); --dialect makes its ids checkable.
  if (frame.desc == nullptr) return;
  switch (stats_.on_frame(frame, source, t_ns)) {
    case telemetry::TrafficStats::Bound::MessageIds:
      observer.on_notice("more than " + std::to_string(telemetry::kMaxMessageIds) +
                         " message ids: the others are counted in untracked_id_frames, not listed");
      break;
    case telemetry::TrafficStats::Bound::Sources:
      observer.on_notice("more than " + std::to_string(telemetry::kMaxSources) +
                         " sources: the others are counted in untracked_source_frames, not listed");
      break;
    case telemetry::TrafficStats::Bound::None: break;
  }
  if (config_.count > 0 &&
      (config_.count_ids.empty() ||
       std::find(config_.count_ids.begin(), config_.count_ids.end(), frame.msgid) != config_.count_ids.end()))
    ++counted_;
  observer.on_frame(frame, source, t_ns);
}

void Inspector::send_heartbeat(Observer& observer) {
  mavlink::FrameBuffer buf;
  const std::size_t n = encoder_.encode(mavlink::gcs_heartbeat(), buf);
  (void)endpoint_->send({buf.data(), n});
  for (const auto& text : endpoint_->take_send_errors()) observer.on_send_error(text);
}

telemetry::TrafficSummary Inspector::summary() const {
  mavlink::ParserStats parser = parser_.stats();
  // A log's last record cut off by the end of the file (a killed writer) is a truncated frame too,
  // and bytes between records that are no timestamp + frame are garbage.
  if (reader_) {
    parser.truncated += reader_->stats().truncated;
    parser.garbage_bytes += reader_->stats().skipped_bytes;
  }
  auto s = stats_.summary(now_ns_, parser);
  if (reader_) {
    s.segments = reader_->timeline().segments;
    s.set_aside_records = reader_->timeline().set_aside_records;
  }
  return s;
}

Expected<Inspector::EndReason> Inspector::run(const std::atomic<bool>& stop, Observer& observer) {
  auto result = config_.source == InspectConfig::Source::Tlog ? run_tlog(stop, observer) : run_live(stop, observer);
  if (recorder_) recorder_->flush();
  return result;
}

Expected<Inspector::EndReason> Inspector::run_live(const std::atomic<bool>& stop, Observer& observer) {
  now_ns_ = unix_time_ns();
  stats_.restart(now_ns_);
  const auto start = Clock::now();
  auto next_tick = start + std::chrono::seconds(1);
  const auto deadline = config_.duration_s > 0
                            ? start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(config_.duration_s))
                            : Clock::time_point::max();
  const bool connect = config_.source == InspectConfig::Source::Connect;
  if (connect) send_heartbeat(observer);
  while (!stop.load()) {
    const auto now = Clock::now();
    const auto until = std::min({next_tick, deadline, now + std::chrono::milliseconds(200)});
    const auto wait_ms = std::max<int64_t>(0, std::chrono::duration_cast<std::chrono::milliseconds>(until - now).count());
    if (endpoint_->wait_readable(static_cast<int>(wait_ms))) {
      while (auto d = endpoint_->receive()) {
        stats_.on_datagram();
        const std::string source = d->from.to_string();
        const int64_t t = d->rx_time_unix_ns;
        parser_.parse_datagram(d->bytes, [&](const mavlink::Frame& f) { handle(f, source, t, observer); });
        if (counted_out()) break;
      }
    }
    now_ns_ = unix_time_ns();
    if (counted_out()) return EndReason::Count;
    const auto after = Clock::now();
    if (after >= deadline) return EndReason::Duration;
    if (after >= next_tick) {
      next_tick += std::chrono::seconds(1);
      if (connect) send_heartbeat(observer);
      stats_.roll(now_ns_);
      observer.on_tick(summary());
    }
  }
  now_ns_ = unix_time_ns();
  return EndReason::Stopped;
}

Expected<Inspector::EndReason> Inspector::run_tlog(const std::atomic<bool>& stop, Observer& observer) {
  // The log's time is checked as it is read (tlog_timeline.h): measured per segment, each record
  // the timeline set aside counted, not measured. --duration counts measured log time.
  reader_->reader().set_stop(&stop);
  mavlink::TimedRecord timed;
  bool started = false;
  double elapsed_before_ns = 0;  // measured time of the segments before this one
  int64_t segment_start_ns = 0;
  auto next_tick = Clock::now() + std::chrono::seconds(1);
  while (!stop.load()) {
    if (!reader_->next(timed)) return reader_->reader().stopped() ? EndReason::Stopped : EndReason::EndOfLog;
    const mavlink::TlogRecord& rec = timed.record;
    if (timed.unchecked) {  // its frame does not check: counted by the parser, its stamp ignored
      stats_.on_datagram();
      parser_.parse_datagram(rec.frame, [&](const mavlink::Frame& f) { handle(f, "tlog", now_ns_, observer); });
      continue;
    }
    // A log's clock is outside input: saturate rather than overflow (a corrupt stamp reads as ~2262).
    const int64_t t = rec.time_unix_us > static_cast<uint64_t>(INT64_MAX / 1000) ? INT64_MAX
                                                                                : static_cast<int64_t>(rec.time_unix_us) * 1000;
    if (!started) {
      started = true;
      stats_.restart(t);
      segment_start_ns = now_ns_ = t;
    } else if (timed.new_segment) {
      elapsed_before_ns += static_cast<double>(now_ns_) - static_cast<double>(segment_start_ns);
      stats_.new_segment(now_ns_, t);
      segment_start_ns = now_ns_ = t;
    }
    if (config_.duration_s > 0 && elapsed_before_ns + static_cast<double>(t) - static_cast<double>(segment_start_ns) > config_.duration_s * 1e9)
      return EndReason::Duration;
    now_ns_ = std::max(now_ns_, t);
    stats_.on_datagram();
    parser_.parse_datagram(rec.frame, [&](const mavlink::Frame& f) { handle(f, "tlog", t, observer); });
    if (counted_out()) return EndReason::Count;
    if (Clock::now() >= next_tick) {
      next_tick += std::chrono::seconds(1);
      observer.on_tick(summary());
    }
  }
  return EndReason::Stopped;
}

}  // namespace hitl::inspect
