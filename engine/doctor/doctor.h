// `hitl doctor`: the spec's Troubleshooting list and Verification phases as checks, run in order
// (check_catalog.h). Host checks first; then one link to the autopilot (through a running session,
// or direct to its GCS instance, as every board-operating command connects) over which doctor
// listens, reads `qshell dsp_hitl status` twice, `mavlink status`, the parameters and, when the
// board is not ready, `commander check`; the VIO checks go through a shell on the apps processor
// (apps_shell.h). Doctor never talks to the board's HIL port: PX4 would take it as its simulator.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "engine/doctor/check_result.h"
#include "engine/px4/px4_process.h"
#include "engine/vehicle/vehicle_link.h"

namespace hitl::doctor {

struct DoctorOptions {
  vehicle::LinkOptions link;      ///< -i, --port, --connect, --session-port, ... (cli/link_options)
  uint16_t hil_port = kBoardHilPort;  ///< --hil-port: the board's HIL instance
  uint16_t vio_port = kBoardVioPort;  ///< --vio-port: voxl-hitl-vio-server
  bool vio = true;                ///< --no-vio: VIO not used, its checks skipped
  bool adb = false;               ///< --adb: check adb devices and use adb shell for the VIO checks
  std::string adb_serial;         ///< --adb-serial (implies --adb)
  double listen_s = 2.5;          ///< --listen: how long to listen to the board and the session
  std::string px4_dir;            ///< --px4 DIR: the PX4 SITL build hitl sim --px4 would start (empty: none)
  /// What hitl sim --px4 gives PX4: the x500's parameters, then --px4-param's (cli puts them together)
  std::vector<px4::Px4Param> px4_expected_params;
};

/// Each result as soon as it is decided; progress lines ("reading parameters") for stderr.
using ResultSink = std::function<void(const CheckResult&)>;
using ProgressSink = std::function<void(const std::string&)>;

/// Runs every check in order; returns them all.
std::vector<CheckResult> run_doctor(const DoctorOptions& options, const ResultSink& on_result, const ProgressSink& progress);

}  // namespace hitl::doctor
