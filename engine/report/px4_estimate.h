// PX4's own estimate, from the ULog PX4 wrote (engine/ulog), merged onto a recording's time axis
// against hitl's truth (docs/report.md "PX4's ULog beside the truth"). `hitl sim --px4 --record
// FILE.tlog` runs PX4 in FILE.px4/, so its ULog lands in FILE.px4/log/<date>/<time>.ulg.
#pragma once

#include <optional>
#include <string>

#include "base/common/expected.h"
#include "engine/report/flight_log.h"

namespace hitl::report {

/// The newest FILE.px4/log/**.ulg beside the recording FILE.tlog (by modification time), or
/// nullopt when there is none.
std::optional<std::string> find_px4_ulog(const std::string& tlog_path);

/// PX4's estimate from the ULog at `ulog_path`, placed on `log`'s time axis and compared with its
/// truth. An Error when the ULog cannot be read or is refused (engine/ulog), when the recording has
/// no simulator's clock to place it on, or when the ULog's times do not overlap the recording's
/// (another session's log, or PX4 not in lockstep).
Expected<Px4Estimate> read_px4_estimate(const std::string& ulog_path, const FlightLog& log);

}  // namespace hitl::report
