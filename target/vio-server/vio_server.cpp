#include "target/vio-server/vio_server.h"

#include <poll.h>
#include <sys/signalfd.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <vector>

#include "base/common/clock.h"
#include "target/vio-server/odometry_to_vio.h"
#include "target/vio-server/raw_fifo_pipe.h"

namespace hitl::vio {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_between(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); }

/// Logs the first few problems of a kind in full, then a count now and then.
class ThrottledLog {
 public:
  ThrottledLog(std::string one, std::string many) : one_(std::move(one)), many_(std::move(many)) {}
  void note(const VioServer::Log& log, const std::string& detail) {
    if (logged_ < kDetailedLogLines) {
      log(one_ + " " + detail);
      if (++logged_ == kDetailedLogLines) {
        log("further " + many_ + " are counted and summarised every " + std::to_string(int(kLogSummaryPeriod_s)) + " s");
      }
      last_summary_ = Clock::now();
      return;
    }
    ++unlogged_;
  }
  void summarise(const VioServer::Log& log) {
    if (unlogged_ == 0 || seconds_between(last_summary_, Clock::now()) < kLogSummaryPeriod_s) return;
    log(std::to_string(unlogged_) + " more " + many_ + " in the last " + std::to_string(int(kLogSummaryPeriod_s)) + " s");
    unlogged_ = 0;
    last_summary_ = Clock::now();
  }

 private:
  std::string one_;   ///< starts a detailed line: "malformed datagram"
  std::string many_;  ///< in summaries: "malformed datagrams"
  int logged_ = 0;
  uint64_t unlogged_ = 0;
  Clock::time_point last_summary_ = Clock::now();
};

}  // namespace

struct VioServer::Impl {
  VioServerOptions options;
  Log log;
  std::unique_ptr<OdometryReceiver> receiver;
  std::unique_ptr<PipeServer> vio_pipe;
  std::unique_ptr<PipeServer> extended_pipe;
  Clock::time_point started = Clock::now();
  Clock::time_point last_report = Clock::now();
  uint64_t odometry_at_last_report = 0;
  double odometry_rate_hz = 0;
  uint64_t published = 0;
  uint64_t invalid_odometry = 0;
  bool status_write_failed = false;
  ThrottledLog malformed_log{"malformed datagram", "malformed datagrams"};
  ThrottledLog invalid_log{"unpublishable ODOMETRY:", "unpublishable ODOMETRY messages"};
};

VioServer::VioServer(VioServerOptions options, Log log) : impl_(std::make_unique<Impl>()) {
  impl_->options = std::move(options);
  impl_->log = std::move(log);
}

VioServer::~VioServer() {
  // Pipes first (their destructors remove the directories), then the report.
  impl_->vio_pipe.reset();
  impl_->extended_pipe.reset();
  ::unlink(impl_->options.status_file.c_str());
}

uint16_t VioServer::port() const { return impl_->receiver->port(); }

Expected<std::unique_ptr<VioServer>> VioServer::start(const VioServerOptions& options, Log log) {
  std::unique_ptr<VioServer> server(new VioServer(options, std::move(log)));
  Impl& s = *server->impl_;
  auto receiver = OdometryReceiver::open(options.config.receiver_ip, options.config.receiver_port);
  if (!receiver.ok()) return receiver.error();
  s.receiver = std::move(receiver.value());

  if (options.vision_hub_fifo) {
    auto fifo = RawFifoPipe::create(options.mpa_dir, kVioPipeName, kVioRecommendedPipeSize_bytes);
    if (!fifo.ok()) return fifo.error();
    s.vio_pipe = std::move(fifo.value());
  } else {
    auto vio = make_pipe_server(options.mpa_dir, {kVioPipeName, "vio_data_t", kServerName, kVioRecommendedPipeSize_bytes});
    if (!vio.ok()) return vio.error();
    s.vio_pipe = std::move(vio.value());
  }
  auto ext = make_pipe_server(options.mpa_dir, {kExtendedVioPipeName, "ext_vio_data_t", kServerName, kExtendedPipeSize_bytes});
  if (!ext.ok()) return ext.error();
  s.extended_pipe = std::move(ext.value());

  server->flush_events();
  s.log("listening for ODOMETRY on UDP " + options.config.receiver_ip + ":" + std::to_string(s.receiver->port()) +
        "; publishing " + s.vio_pipe->location() + (options.vision_hub_fifo ? " (a FIFO, for vision-hub's en_hitl reader)" : "") +
        " and " + s.extended_pipe->location() + " through " + pipe_server_implementation());
  server->report();
  return server;
}

void VioServer::on_odometry(const mavlink::msg::Odometry& odometry) {
  Impl& s = *impl_;
  auto vio = vio_from_odometry(odometry, static_cast<int64_t>(monotonic_ns()));
  if (!vio.ok()) {
    ++s.invalid_odometry;
    s.invalid_log.note(s.log, vio.error().message);
    return;
  }
  ++s.published;
  const VioData& v = vio.value();
  s.vio_pipe->write({reinterpret_cast<const uint8_t*>(&v), sizeof v});
  if (s.extended_pipe->clients() > 0) {
    const ExtVioData e = extended_vio(v, static_cast<int32_t>(s.published));
    s.extended_pipe->write({reinterpret_cast<const uint8_t*>(&e), sizeof e});
  }
}

void VioServer::on_malformed(const std::string& why) { impl_->malformed_log.note(impl_->log, why); }

void VioServer::flush_events() {
  for (auto* pipe : {impl_->vio_pipe.get(), impl_->extended_pipe.get()}) {
    if (pipe == nullptr) continue;
    for (const auto& e : pipe->take_events()) impl_->log(e);
  }
}

ServerStatus VioServer::status() const {
  const Impl& s = *impl_;
  ServerStatus st;
  st.pid = static_cast<int>(::getpid());
  st.listen = s.options.config.receiver_ip + ":" + std::to_string(s.receiver->port());
  st.pipe_implementation = pipe_server_implementation();
  st.uptime_s = seconds_between(s.started, Clock::now());
  st.updated_unix_ms =
      std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::system_clock::now().time_since_epoch()).count();
  st.odometry_rate_hz = s.odometry_rate_hz;
  st.receiver = s.receiver->counters();
  st.published = s.published;
  st.invalid_odometry = s.invalid_odometry;
  st.pipes.push_back({s.vio_pipe->location(), s.options.vision_hub_fifo ? "vio_data_t, FIFO" : "vio_data_t",
                      s.vio_pipe->clients(), s.vio_pipe->counters()});
  st.pipes.push_back({s.extended_pipe->location(), "ext_vio_data_t", s.extended_pipe->clients(), s.extended_pipe->counters()});
  return st;
}

void VioServer::report() {
  Impl& s = *impl_;
  const auto now = Clock::now();
  const double dt = seconds_between(s.last_report, now);
  const uint64_t odometry = s.receiver->counters().odometry;
  if (dt > 0.1) s.odometry_rate_hz = static_cast<double>(odometry - s.odometry_at_last_report) / dt;
  s.odometry_at_last_report = odometry;
  s.last_report = now;
  auto written = write_status_file(s.options.status_file, status());
  if (!written.ok() && !s.status_write_failed) s.log("cannot write the status report: " + written.error().message);
  s.status_write_failed = !written.ok();
  s.malformed_log.summarise(s.log);
  s.invalid_log.summarise(s.log);
}

Status VioServer::run(int signal_fd) {
  Impl& s = *impl_;
  const auto report_period = std::chrono::seconds(1);
  for (;;) {
    std::vector<pollfd> fds;
    fds.push_back({signal_fd, POLLIN, 0});
    fds.push_back({s.receiver->fd(), POLLIN, 0});
    for (auto* pipe : {s.vio_pipe.get(), s.extended_pipe.get()}) {
      for (int fd : pipe->poll_fds()) fds.push_back({fd, POLLIN, 0});
    }
    const auto until_report = std::chrono::duration_cast<std::chrono::milliseconds>(s.last_report + report_period - Clock::now());
    int timeout_ms = static_cast<int>(std::max<int64_t>(0, until_report.count()));
    if (s.vio_pipe->connecting() || s.extended_pipe->connecting()) timeout_ms = std::min(timeout_ms, 1);
    const int n = ::poll(fds.data(), fds.size(), timeout_ms);
    if (n < 0 && errno != EINTR) return Error{std::string("poll: ") + std::strerror(errno)};
    if (n > 0 && (fds[0].revents & POLLIN)) {
      signalfd_siginfo info{};
      if (::read(signal_fd, &info, sizeof info) == static_cast<ssize_t>(sizeof info)) {
        s.log(std::string("received ") + ::strsignal(static_cast<int>(info.ssi_signo)) + ", removing the pipes and exiting");
      }
      return Ok{};
    }
    s.vio_pipe->service();
    s.extended_pipe->service();
    s.receiver->drain([this](const mavlink::msg::Odometry& m) { on_odometry(m); },
                      [this](const std::string& why) { on_malformed(why); });
    flush_events();
    if (Clock::now() >= s.last_report + report_period) report();
  }
}

}  // namespace hitl::vio
