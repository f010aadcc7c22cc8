// What `hitl board` knows about a VOXL2 running HITL (the spec's Quick Start steps 5-9): the files it
// writes or backs up, the packages it installs, the services it starts, in one place.
#pragma once

#include <array>

namespace hitl::board {

/// The spec's step 7: the two configuration files.
inline constexpr const char* kVisionHubConf = "/etc/modalai/voxl-vision-hub.conf";
inline constexpr const char* kVioServerConf = "/etc/modalai/voxl-hitl-vio-server.conf";

/// Where `hitl board install` keeps what `hitl board restore` needs: the original vision-hub
/// configuration byte for byte, and the board's state before the install (board_state.h). /data
/// survives reboots and system image updates on a VOXL2.
inline constexpr const char* kBackupDir = "/data/hitl-board";
inline constexpr const char* kVisionHubBackup = "/data/hitl-board/voxl-vision-hub.conf.orig";
inline constexpr const char* kStateFile = "/data/hitl-board/state";
/// Where packages and generated files are pushed before they are put in place; removed at the end.
inline constexpr const char* kStagingDir = "/tmp/hitl-board";

/// PX4's HITL parameter file (voxl-px4-hitl keeps the HITL set apart from voxl-px4's parameters).
inline constexpr const char* kHitlParamFile = "/data/px4/param/hitl_parameters";

/// The board packages this build makes (target/, docs/board-packages.md), in install order.
inline constexpr std::array<const char*, 2> kHitlPackages{"voxl-hitl-vio-server", "voxl-hitl-px4-scripts"};

/// The services, by the spec's start order (step 9): PX4 first, then the VIO server, then vision-hub.
inline constexpr const char* kPx4Service = "voxl-px4";            ///< ModalAI's normal PX4: stopped for HITL
inline constexpr const char* kPx4HitlUnit = "voxl-px4-hitl";      ///< PX4 in HITL: a transient unit (systemd-run)
inline constexpr const char* kVioServerService = "voxl-hitl-vio-server";
inline constexpr const char* kVisionHubService = "voxl-vision-hub";
/// The services whose enabled/active state install records and restore puts back.
inline constexpr std::array<const char*, 3> kRecordedServices{kPx4Service, kVioServerService, kVisionHubService};

/// voxl-px4-hitl as packaged (target/px4/scripts).
inline constexpr const char* kPx4HitlScript = "/usr/bin/voxl-px4-hitl";

}  // namespace hitl::board
