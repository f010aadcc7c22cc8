// Putting a parameter set onto a board (hitl params load and reset, and the board workflow): what
// differs from the board's values is set and verified by reading it back; what already matches is
// left alone; a parameter the board does not have is a failure, or, for the HITL set whose
// parameters some firmware lacks (base/contract/hitl-defaults.params' #absent notes), reported as
// absent with the firmware's version and what replaces it there.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "engine/vehicle/param_client.h"
#include "engine/vehicle/param_notes.h"
#include "engine/vehicle/params_file.h"
#include "engine/vehicle/vehicle_link.h"

namespace hitl::vehicle {

struct ParamChange {
  std::string name;
  ParamValue from;  ///< the board's value before
  ParamValue to;
};

struct ParamPushFailure {
  std::string name;
  std::string error;  ///< the client's error, "read back 3" or "the board has no such parameter"
};

struct AbsentParam {
  std::string name;
  const AbsentParamNote* note = nullptr;  ///< the firmware known to lack it and its replacement, if noted
};

struct ParamPushOptions {
  bool dry_run = false;    ///< plan only: `set` lists what would be set
  bool absent_ok = false;  ///< a parameter the board lacks is `absent`, not `failed`
};

struct ParamPushResult {
  std::vector<ParamChange> set;  ///< set and read back equal (with dry_run: would be set)
  std::vector<std::string> unchanged;
  std::vector<ParamPushFailure> failed;
  std::vector<AbsentParam> absent;
  std::optional<std::string> firmware;  ///< AUTOPILOT_VERSION's, asked once when a parameter is absent
  /// Nothing failed and, when `strict`, nothing is absent either.
  bool ok(bool strict) const { return failed.empty() && (absent.empty() || !strict); }
};

/// Pushes `wanted` onto the board whose current parameters are `board` (a download).
ParamPushResult push_params(ParamClient& client, VehicleLink& link, const std::vector<Param>& board,
                            const std::vector<Param>& wanted, const ParamPushOptions& options);

}  // namespace hitl::vehicle
