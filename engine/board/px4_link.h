// The host's side of `hitl board start` and `status`, over PX4's GCS MAVLink instance
// (engine/vehicle's link, shell and parameter clients): wait until PX4's HEARTBEAT arrives and
// `qshell dsp_hitl status` says "Running: yes"; set the HITL parameters that differ; read what
// `status` shows (HIL mode, dsp_hitl, the parameter check).
#pragma once

#include <atomic>
#include <optional>
#include <string>
#include <vector>

#include "base/common/expected.h"
#include "engine/vehicle/params_check.h"
#include "engine/vehicle/vehicle_link.h"

namespace hitl::board {

/// Retries the link and the shell until `timeout_s`; an Error saying what was last seen
/// ("no HEARTBEAT from PX4 on ...", "dsp_hitl status says Running: no").
Status wait_for_px4(const vehicle::LinkOptions& link, double timeout_s);

/// The HITL set against the board; sets what differs (read back); the names set. An Error when
/// the link, the download or a set failed.
Expected<std::vector<std::string>> push_hitl_params(const vehicle::LinkOptions& link);

struct Px4Status {
  bool heartbeat = false;
  std::string link_error;                     ///< why there is no HEARTBEAT
  bool hil_mode = false;                      ///< base_mode has MAV_MODE_FLAG_HIL_ENABLED
  std::optional<bool> dsp_hitl_running;       ///< none: the shell did not answer or the text did not parse
  bool params_checked = false;
  std::vector<vehicle::ParamCheckRow> params; ///< every row of the HITL set
};

/// One look (the link's discovery timeout): never fails, says what it saw.
Px4Status read_px4_status(const vehicle::LinkOptions& link);

}  // namespace hitl::board
