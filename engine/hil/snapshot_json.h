// A session's snapshot as JSON: `hitl sim --json`'s status lines and its final summary, and a
// campaign flight's figures (docs/campaigns.md names them by their path in this object).
#pragma once

#include <nlohmann/json.hpp>

#include "engine/hil/session_snapshot.h"

namespace hitl::hil {

/// The snapshot as JSON: a "status" line, or the final "summary" (rates over the whole run).
nlohmann::json snapshot_json(const SessionSnapshot& s, bool final_summary);

}  // namespace hitl::hil
