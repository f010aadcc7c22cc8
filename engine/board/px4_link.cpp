#include "engine/board/px4_link.h"

#include <algorithm>
#include <chrono>
#include <thread>

#include "base/common/clock.h"
#include "base/contract/dsp_hitl_status.h"
#include "base/mavlink/enums.h"
#include "engine/vehicle/param_client.h"
#include "engine/vehicle/params_file.h"
#include "engine/vehicle/params_push.h"
#include "engine/vehicle/shell_client.h"
#include "engine/vehicle/shell_poller.h"

namespace hitl::board {
namespace {

namespace msg = mavlink::msg;

/// How long one look waits for PX4's HEARTBEAT before it tries again.
constexpr double kLookTimeout_s = 2.0;
constexpr double kShellTimeout_s = 3.0;

/// `qshell dsp_hitl status` read: running or not; an Error when there was no answer to read.
Expected<bool> dsp_hitl_running(vehicle::VehicleLink& link) {
  vehicle::ShellClient shell(link);
  auto out = shell.run(vehicle::kDspHitlStatusCommand, kShellTimeout_s);
  if (!out) return out.error();
  target::DspHitlStatusReport report;
  std::string why;
  if (!target::parse_dsp_hitl_status(*out, &report, &why)) return Error::failed("`qshell dsp_hitl status` answered '" + *out + "' (" + why + ")");
  return report.running;
}

}  // namespace

Status wait_for_px4(const vehicle::LinkOptions& options, double timeout_s) {
  const double deadline = monotonic_s() + timeout_s;
  std::string last = "no HEARTBEAT from PX4";
  while (monotonic_s() < deadline) {
    vehicle::LinkOptions o = options;
    o.timeout_s = std::min(kLookTimeout_s, std::max(0.2, deadline - monotonic_s()));
    auto link = vehicle::VehicleLink::connect(o);
    if (!link) {
      last = link.error().message;
      continue;
    }
    auto running = dsp_hitl_running(**link);
    if (running && *running) return Ok{};
    last = running ? "PX4 is up (" + (*link)->description() + ") but `qshell dsp_hitl status` says Running: no" : running.error().message;
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
  }
  return Error::failed("PX4 not ready after " + std::to_string(static_cast<int>(timeout_s)) + " s: " + last);
}

Expected<std::vector<std::string>> push_hitl_params(const vehicle::LinkOptions& options) {
  auto link = vehicle::VehicleLink::connect(options);
  if (!link) return link.error();
  vehicle::ParamClient client(**link);
  auto board = client.download();
  if (!board) return board.error().prefixed("downloading PX4's parameters: ");
  const auto result = vehicle::push_params(client, **link, *board, vehicle::hitl_default_params(), {false, true});
  if (!result.failed.empty()) {
    std::string names;
    for (const auto& f : result.failed) names += (names.empty() ? "" : "; ") + f.name + ": " + f.error;
    return Error::failed("PX4 did not take " + names);
  }
  std::vector<std::string> set;
  for (const auto& c : result.set) set.push_back(c.name);
  return set;
}

Px4Status read_px4_status(const vehicle::LinkOptions& options) {
  Px4Status status;
  vehicle::LinkOptions o = options;
  auto link = vehicle::VehicleLink::connect(o);
  if (!link) {
    status.link_error = link.error().message;
    return status;
  }
  status.heartbeat = true;
  (*link)->wait(1.5, [&](const mavlink::Frame& f) {
    if (f.msgid != msg::Heartbeat::kId || f.desc == nullptr) return false;
    status.hil_mode = (f.as<msg::Heartbeat>().base_mode & mavlink::mode_flag::kHilEnabled) != 0;
    return true;
  });
  auto running = dsp_hitl_running(**link);
  if (running) status.dsp_hitl_running = *running;
  vehicle::ParamClient client(**link);
  auto board = client.download();
  if (board) {
    status.params_checked = true;
    status.params = vehicle::check_params(*board, vehicle::hitl_default_params());
  }
  return status;
}

}  // namespace hitl::board
