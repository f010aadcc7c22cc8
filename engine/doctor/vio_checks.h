// The VIO path (spec Troubleshooting "VIO not working", Verification Phases 1 and 2): what a shell
// on the board's apps processor shows: voxl-hitl-vio-server's own report (`--status --json`), its
// systemd unit, the hitl_vio MPA pipe and voxl-vision-hub's en_hitl. Pure.
#pragma once

#include <optional>
#include <string>

#include "base/common/expected.h"
#include "engine/doctor/check_result.h"

namespace hitl::doctor {

/// What a command on the board's apps processor gave: its output, or why it could not run (no adb,
/// PX4's shell does not know the command), in which case the check is skipped with that reason.
using BoardOutput = Expected<std::string>;

/// vio-odometry: voxl-hitl-vio-server's report says it listens and ODOMETRY arrives at
/// `expected_hz` (250 Hz of simulated time: 250 x the session's pace).
CheckResult vio_odometry_check(const BoardOutput& status_json, double expected_hz);
/// vio-server: `systemctl is-active voxl-hitl-vio-server` says active.
CheckResult vio_server_check(const BoardOutput& is_active);
/// vio-pipe: `ls /run/mpa` lists hitl_vio.
CheckResult vio_pipe_check(const BoardOutput& mpa_listing);
/// vision-hub: /etc/modalai/voxl-vision-hub.conf (JSON) has "en_hitl": true.
CheckResult vision_hub_check(const BoardOutput& config_text);

/// All four skipped with `why` (VIO not used, or no shell on the apps processor).
CheckResult vio_skipped(const char* id, const std::string& why);

}  // namespace hitl::doctor
