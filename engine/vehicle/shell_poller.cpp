#include "engine/vehicle/shell_poller.h"

#include <chrono>

#include "base/common/clock.h"
#include "base/contract/dsp_hitl_status.h"
#include "engine/vehicle/patient_link.h"
#include "engine/vehicle/shell_client.h"

namespace hitl::vehicle {
namespace {

constexpr double kShellTimeout_s = 3.0;

/// The first line of a reply, for a reason that fits a panel.
std::string first_line(const std::string& text) {
  const auto begin = text.find_first_not_of("\r\n ");
  if (begin == std::string::npos) return "(no output)";
  const auto end = text.find_first_of("\r\n", begin);
  return text.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
}

}  // namespace

ShellPoller::ShellPoller(LinkOptions options, const telemetry::DspHitlExpectedRates& expected, double poll_period_s,
                         OutputSink output)
    : options_(std::move(options)), poll_period_s_(poll_period_s), output_(std::move(output)), meter_(expected) {
  thread_ = std::thread([this] { run(); });
}

ShellPoller::~ShellPoller() { stop(); }

void ShellPoller::stop() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_.store(true);
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

telemetry::DspHitlView ShellPoller::dsp_hitl() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return meter_.view(monotonic_s());
}

void ShellPoller::run_command(const std::string& line) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    commands_.push_back(line);
  }
  wake_.notify_all();
}

void ShellPoller::poll_dsp_hitl(ShellClient& shell) {
  auto out = shell.run(kDspHitlStatusCommand, kShellTimeout_s);
  std::lock_guard<std::mutex> lock(mutex_);
  // Each failure is retried at the next poll; the panel says so.
  if (!out) {
    meter_.on_unavailable("the board's shell did not answer (retrying each poll): " + out.error().message);
    return;
  }
  // The prompt alone: the command ran but nothing came back (a qshell whose DSP side did not
  // answer, a busy board), which says nothing about dsp_hitl being there.
  if (out->find_first_not_of("\r\n ") == std::string::npos) {
    meter_.on_unavailable(std::string("shell did not answer `") + kDspHitlStatusCommand + "` (an empty reply); retrying each poll");
    return;
  }
  target::DspHitlStatusReport report;
  std::string error;
  if (target::parse_dsp_hitl_status(*out, &report, &error)) meter_.on_report(report, monotonic_s());
  else meter_.on_unavailable("no dsp_hitl on this board (" + first_line(*out) + "); asking again each poll");
}

void ShellPoller::run() {
  auto link = connect_patiently(options_, stop_, [&](const std::string&) {
    std::lock_guard<std::mutex> lock(mutex_);
    meter_.on_unavailable("waiting for an autopilot HEARTBEAT through " + options_.connect);
  });
  if (!link) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    meter_.on_unavailable("");  // connected: waiting for the first status
  }
  ShellClient shell(*link);
  double next_poll_s = monotonic_s();
  while (!stop_.load()) {
    std::string command;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      const double wait_s = std::max(0.0, next_poll_s - monotonic_s());
      wake_.wait_for(lock, std::chrono::duration<double>(wait_s), [&] { return stop_.load() || !commands_.empty(); });
      if (stop_.load()) break;
      if (!commands_.empty()) {
        command = commands_.front();
        commands_.pop_front();
      }
    }
    if (!command.empty()) {
      auto out = shell.run(command, kShellTimeout_s);
      if (output_) output_(command, static_cast<bool>(out), out ? *out : out.error().message);
      continue;
    }
    if (monotonic_s() >= next_poll_s) {
      next_poll_s = monotonic_s() + poll_period_s_;
      poll_dsp_hitl(shell);
    }
  }
}

}  // namespace hitl::vehicle
