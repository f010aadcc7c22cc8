#include "engine/replay/replayer.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "base/common/clock.h"
#include "base/mavlink/frame_parser.h"
#include "base/mavlink/message_set.h"
#include "base/mavlink/messages.h"
#include "engine/mavlink/tlog.h"
#include "engine/net/socket_address.h"
#include "engine/net/udp_endpoint.h"

namespace hitl::replay {
namespace msg = mavlink::msg;
namespace {

Expected<net::UdpEndpoint> open_endpoint(const ReplayConfig& config, uint16_t remote, uint16_t local, const char* name) {
  auto peer = net::resolve_board_address(config.target_ip, remote);
  if (!peer) return peer.error();
  net::UdpEndpoint::Config c;
  c.name = name;
  c.bind_address = config.bind_address;
  c.bind_port = local;
  c.peer = *peer;
  c.policy = net::PartnerPolicy::Fixed;
  return net::UdpEndpoint::open(c);
}

class Run {
 public:
  Run(const RecordedSession& session, const ReplayConfig& config, net::UdpEndpoint hil, std::optional<net::UdpEndpoint> vio,
      std::optional<mavlink::TlogWriter> record)
      : session_(session), config_(config), hil_(std::move(hil)), vio_(std::move(vio)), record_(std::move(record)),
        messages_(mavlink::MessageSet::compiled()), parser_(messages_) {}

  Expected<ReplayResult> go(const std::atomic<bool>& stop, const std::function<void(const ReplayProgress&)>& on_progress) {
    const double start_s = monotonic_s();
    last_heard_s_ = start_s;
    double next_progress_s = start_s + 1.0;
    const uint64_t t0_us = session_.steps.front().t_unix_us;
    for (std::size_t k = 0; k < session_.steps.size(); ++k) {
      if (stop.load()) {
        result_.stopped = true;
        break;
      }
      const auto& step = session_.steps[k];
      if (!config_.lockstep) {  // the recorded timing: wait for the step's time, reading answers meanwhile
        const double due_s = start_s + static_cast<double>(step.t_unix_us - std::min(step.t_unix_us, t0_us)) * 1e-6;
        while (monotonic_s() < due_s && !stop.load()) {
          const double left_ms = (due_s - monotonic_s()) * 1000.0;
          if (hil_.wait_readable(static_cast<int>(std::clamp(left_ms, 0.0, 100.0)))) drain();
          if (monotonic_s() - last_heard_s_ > config_.give_up_s) return silence(k);  // not waiting out a recorded gap
        }
      }
      current_step_ = static_cast<int64_t>(k);
      if (auto st = send_step(step); !st) return st.error();
      ++result_.steps_sent;
      if (config_.lockstep) wait_answer(step.sensor_time_usec, stop);
      else drain();
      if (monotonic_s() - last_heard_s_ > config_.give_up_s) return silence(k);
      if (monotonic_s() >= next_progress_s) {
        next_progress_s += 1.0;
        on_progress(progress(k));
      }
    }
    // The last step's answer, and anything still in flight.
    const double end_s = monotonic_s() + (config_.lockstep ? 0.0 : 0.05);
    while (monotonic_s() < end_s)
      if (hil_.wait_readable(10)) drain();
    drain();
    if (record_) record_->flush();
    if (record_ && !record_->ok()) return Error::failed("--record: " + record_->error());
    result_.wall_time_s = monotonic_s() - start_s;
    on_progress(progress(session_.steps.size() - 1));
    return std::move(result_);
  }

 private:
  Error silence(std::size_t k) const {
    return Error::failed("the board at " + config_.target_ip + ":" + std::to_string(config_.hil_port) + " said nothing for " +
                         std::to_string(static_cast<int>(config_.give_up_s)) + " s (step " + std::to_string(k) + " of " +
                         std::to_string(session_.steps.size()) + "): is it running, and on that port?");
  }

  Status send_step(const RecordedStep& step) {
    for (const auto& f : step.frames) {
      if (f.to == Destination::Vio && !vio_) continue;
      record(f.bytes);
      auto& endpoint = f.to == Destination::Vio ? *vio_ : hil_;
      if (auto st = endpoint.queue(f.bytes); !st) return st;
      ++result_.frames_sent;
    }
    if (auto st = hil_.flush(); !st) return st.error().prefixed("sending to the board: ");
    if (vio_)
      if (auto st = vio_->flush(); !st) return st.error().prefixed("sending ODOMETRY: ");
    return Ok{};
  }

  void wait_answer(uint64_t time_usec, const std::atomic<bool>& stop) {
    const double deadline_s = monotonic_s() + config_.lockstep_timeout_s;
    answered_ = false;
    awaited_us_ = time_usec;
    drain();
    while (!answered_ && !stop.load()) {
      const double left_ms = (deadline_s - monotonic_s()) * 1000.0;
      if (left_ms <= 0) {
        ++result_.fallbacks;
        return;
      }
      if (hil_.wait_readable(static_cast<int>(std::ceil(left_ms)))) drain();
    }
  }

  void drain() {
    for (int n = 0; n < 256; ++n) {
      auto d = hil_.receive();
      if (!d) return;
      last_heard_s_ = monotonic_s();
      parser_.parse_datagram(d->bytes, [&](const mavlink::Frame& f) {
        record(f.bytes());
        if (!f.is<msg::HilActuatorControls>()) return;
        const auto m = f.as<msg::HilActuatorControls>();
        ActuatorSample a;
        a.time_usec = m.time_usec;
        a.step = current_step_;
        for (std::size_t i = 0; i < 4; ++i) a.controls[i] = m.controls[i];
        a.mode = m.mode;
        result_.actuators.push_back(a);
        ++result_.answers;
        if (m.time_usec == awaited_us_) answered_ = true;
      });
    }
  }

  void record(std::span<const uint8_t> bytes) {
    if (record_ && record_->ok()) record_->write(static_cast<uint64_t>(unix_time_ns() / 1000), bytes);
  }

  ReplayProgress progress(std::size_t k) const {
    ReplayProgress p;
    p.step = k + 1;
    p.steps = session_.steps.size();
    p.answers = result_.answers;
    p.fallbacks = result_.fallbacks;
    p.sim_time_s = static_cast<double>(session_.steps[k].sensor_time_usec) * 1e-6;
    return p;
  }

  const RecordedSession& session_;
  const ReplayConfig& config_;
  net::UdpEndpoint hil_;
  std::optional<net::UdpEndpoint> vio_;
  std::optional<mavlink::TlogWriter> record_;
  mavlink::MessageSet messages_;
  mavlink::FrameParser parser_;
  ReplayResult result_;
  int64_t current_step_ = -1;
  uint64_t awaited_us_ = 0;
  bool answered_ = false;
  double last_heard_s_ = 0;
};

}  // namespace

Expected<ReplayResult> run_replay(const RecordedSession& session, const ReplayConfig& config, const std::atomic<bool>& stop,
                                  const std::function<void(const ReplayProgress&)>& on_progress) {
  if (session.steps.empty()) return Error::input("the recording holds no step to replay");
  auto hil = open_endpoint(config, config.hil_port, config.local_port, "HIL link (--local-port)");
  if (!hil) return hil.error();
  std::optional<net::UdpEndpoint> vio;
  if (config.vio_port != 0 && session.vio_frames > 0) {
    auto v = open_endpoint(config, config.vio_port, 0, "VIO link");
    if (!v) return v.error();
    vio.emplace(std::move(v.value()));
  }
  std::optional<mavlink::TlogWriter> record;
  if (!config.record_path.empty()) {
    auto w = mavlink::TlogWriter::open(config.record_path);
    if (!w) return w.error().prefixed("--record: ");
    record.emplace(std::move(w.value()));
  }
  Run run(session, config, std::move(hil.value()), std::move(vio), std::move(record));
  return run.go(stop, on_progress);
}

}  // namespace hitl::replay
