#include "engine/hil/px4_launch.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "base/common/clock.h"
#include "engine/hil/pacer.h"
#include "engine/hil/px4_vehicle_params.h"

namespace hitl::hil {
namespace {

/// "flight.tlog" -> "flight"; the recording's name without its extension.
std::string recording_stem(const std::string& path) {
  const std::string ext = ".tlog";
  if (path.size() > ext.size() && path.compare(path.size() - ext.size(), ext.size(), ext) == 0)
    return path.substr(0, path.size() - ext.size());
  return path;
}

/// A new folder $TMPDIR/hitl-px4-XXXXXX (as the demo's and the report's, temp_directory_path()).
Expected<std::string> new_temp_folder() {
  std::string pattern = (std::filesystem::temp_directory_path() / "hitl-px4-XXXXXX").string();
  if (::mkdtemp(pattern.data()) == nullptr)
    return Error::unavailable("cannot create PX4's working folder '" + pattern + "': " + std::strerror(errno));
  return pattern;
}

}  // namespace

std::vector<px4::Px4Param> px4_params_for(const SessionConfig& config) {
  auto params = px4_vehicle_params(config.vehicle, config.world.gravity_m_s2);
  if (config.px4) params.insert(params.end(), config.px4->params.begin(), config.px4->params.end());
  return params;
}

Expected<std::unique_ptr<Px4Launch>> Px4Launch::claim(const SessionConfig& config, const OpenStack& open_stack,
                                                      std::unique_ptr<StackLink>& stack) {
  if (!config.px4) return Error::usage("no PX4 to start (--px4 DIR)");
  const px4::Px4Build& build = config.px4->build;
  if (!build.lockstep)
    return Error::input("'" + build.build_dir + "' is a PX4 build without lockstep (px4_sitl_nolockstep); hitl sim --px4 "
                        "needs px4_sitl_default, which scripts/px4-sitl.sh builds");
  auto launch = std::unique_ptr<Px4Launch>(new Px4Launch());
  launch->build_ = build;
  launch->connect_timeout_s_ = config.px4->connect_timeout_s;

  // The first instance that no PX4 holds and whose simulator port this session can listen on:
  // listening is the claim, so a second session at the same moment moves on to the next one.
  std::vector<std::string> busy;
  for (int index = 0; index <= px4::Px4Instance::kMax && !stack; ++index) {
    const px4::Px4Instance instance{index};
    if (const auto why = px4::px4_instance_busy(instance); !why.empty()) {
      if (busy.size() < 3) busy.push_back(why);
      continue;
    }
    auto opened = open_stack(instance);
    if (!opened) {
      if (busy.size() < 3) busy.push_back(opened.error().message);
      continue;
    }
    stack = std::move(opened.value());
    launch->options_.instance = instance;
  }
  if (!stack) {
    std::string why;
    for (const auto& b : busy) why += (why.empty() ? "" : "; ") + b;
    return Error::unavailable("no free PX4 instance among 0.." + std::to_string(px4::Px4Instance::kMax) + " (" + why + ")");
  }

  auto& o = launch->options_;
  o.params = px4_params_for(config);
  o.speed_factor = config.speed > 0 ? config.speed : 1.0;
  const std::string stem = config.record_path.empty() ? "" : recording_stem(config.record_path);
  if (!config.px4->work_dir.empty()) o.work_dir = config.px4->work_dir;
  else if (!stem.empty()) o.work_dir = stem + ".px4";
  else {
    auto dir = new_temp_folder();
    if (!dir) return dir.error();
    o.work_dir = *dir;
  }
  o.console_path = stem.empty() ? o.work_dir + "/console.log" : stem + ".px4.log";
  // A fresh PX4 each session: the parameters (and the missions) an earlier run left there go.
  for (const char* stale : {"parameters.bson", "parameters_backup.bson", "dataman"}) {
    std::error_code ec;
    std::filesystem::remove(std::filesystem::path(o.work_dir) / stale, ec);
  }
  return launch;
}

Px4Launch::~Px4Launch() {
  if (process_) process_->stop(true);
}

Status Px4Launch::start(EventSink& events) {
  if (process_) return Ok{};
  auto p = px4::Px4Process::start(build_, options_);
  if (!p) return p.error();
  process_ = std::move(p.value());
  started_s_ = monotonic_s();
  events.on_event({Severity::Info, "started PX4" + (build_.version.empty() ? std::string() : " " + build_.version) +
                                       " as instance " + std::to_string(options_.instance.index) + " (pid " +
                                       std::to_string(process_->pid()) + "); its console: " + options_.console_path});
  return Ok{};
}

std::string Px4Launch::last_lines_text() const {
  if (!process_) return "";
  std::string out;
  for (const auto& line : process_->console().last_lines(kLastLines)) out += "\n  " + line;
  return out.empty() ? " (its console is empty)" : "; its console (" + options_.console_path + ") ends:" + out;
}

std::optional<Error> Px4Launch::check(EventSink& events, bool connected, bool link_closed) {
  if (!process_) return std::nullopt;
  std::size_t shown = 0;
  for (const auto& line : process_->console().new_lines()) {
    if (const auto name = px4::px4_unknown_parameter(line)) {
      bool ours = false;
      for (const auto& p : options_.params) {
        if (p.name != *name) continue;
        ours = true;
        if (!refused_)
          refused_ = Error::input("PX4 " + build_.version + " has no parameter " + *name + " (set as " + p.name + "=" +
                                  p.value + ", --px4-param)");
      }
      // PX4's own start script sets the parameters of modules this build left out (scripts/px4-sitl.sh:
      // UXRCE_DDS_*, IMU_GYRO_FFT_EN): harmless, and kept in the console file only.
      if (!ours) continue;
    }
    const auto severity = px4::px4_console_severity(line);
    if (!severity) continue;
    if (shown < kMaxLinesPerCheck) {
      ++shown;
      events.on_event({*severity, "PX4: " + line});
    } else {
      ++lines_not_shown_;
    }
  }
  if (refused_) return refused_;
  if (connected) connected_ = true;
  if (link_closed) {  // PX4 closed its end: let it finish exiting, so the message can say how
    const double until_s = monotonic_s() + 2.0;
    while (!process_->exited() && monotonic_s() < until_s) sleep_until_monotonic_s(monotonic_s() + 0.02);
  }
  if (const auto code = process_->exited()) {
    return Error::failed("PX4 (instance " + std::to_string(options_.instance.index) + ") exited with code " +
                         std::to_string(*code) + (connected_ ? " during the session" : " before it connected") +
                         last_lines_text());
  }
  if (!connected_ && monotonic_s() - started_s_ > connect_timeout_s_) {
    char text[160];
    std::snprintf(text, sizeof text, "PX4 (instance %d) did not connect to TCP 127.0.0.1:%u within %g s (--px4-timeout)",
                  options_.instance.index, options_.instance.simulator_tcp_port(), connect_timeout_s_);
    return Error::failed(text + last_lines_text());
  }
  return std::nullopt;
}

void Px4Launch::stop(bool ran, EventSink& events) {
  if (!process_ || process_->exited()) return;
  const double from_s = monotonic_s();
  const int code = process_->stop(!ran, 3.0);
  char text[200];
  std::snprintf(text, sizeof text, "stopped PX4 (instance %d) with %s in %.1f s (exit code %d)", options_.instance.index,
                ran ? "SIGTERM" : "SIGKILL (before its first sensors PX4 ignores SIGTERM)", monotonic_s() - from_s, code);
  events.on_event({Severity::Info, text});
  if (lines_not_shown_ > 0)
    events.on_event({Severity::Info, std::to_string(lines_not_shown_) + " more PX4 warnings and errors are in " + options_.console_path});
}

std::string Px4Launch::describe() const {
  return ", PX4" + (build_.version.empty() ? std::string() : " " + build_.version) + " instance " +
         std::to_string(options_.instance.index) + " started by hitl (" + build_.build_dir + "; working folder " +
         options_.work_dir + ")";
}

}  // namespace hitl::hil
