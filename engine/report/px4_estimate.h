// PX4's own estimate, from the ULog PX4 wrote (engine/ulog), merged onto a recording's time axis
// against hitl's truth (docs/report.md "PX4's ULog beside the truth"). `hitl sim --px4 --record
// FILE.tlog` runs PX4 in FILE.px4/, so its ULog lands in FILE.px4/log/<date>/<time>.ulg.
#pragma once

#include <optional>
#include <string>

#include "base/common/expected.h"
#include "engine/report/flight_log.h"

namespace hitl::report {

/// A field of PX4's estimator_innovations (or _test_ratios) the report draws: its name in words, the
/// plot it goes in and its unit (EKF2's innovations are NED, the magnetometer's body axes).
struct Px4InnovationField {
  const char* field;
  const char* name;
  const char* group;
  const char* unit;
};

inline constexpr Px4InnovationField kPx4InnovationFields[] = {
    {"gps_hvel[0]", "GPS velocity north", "velocity", "m/s"},   {"gps_hvel[1]", "GPS velocity east", "velocity", "m/s"},
    {"gps_vvel", "GPS velocity down", "velocity", "m/s"},       {"ev_hvel[0]", "vision velocity north", "velocity", "m/s"},
    {"ev_hvel[1]", "vision velocity east", "velocity", "m/s"},  {"ev_vvel", "vision velocity down", "velocity", "m/s"},
    {"gps_hpos[0]", "GPS position north", "position", "m"},     {"gps_hpos[1]", "GPS position east", "position", "m"},
    {"ev_hpos[0]", "vision position north", "position", "m"},   {"ev_hpos[1]", "vision position east", "position", "m"},
    {"gps_vpos", "GPS height", "height", "m"},                  {"baro_vpos", "barometer height", "height", "m"},
    {"ev_vpos", "vision height", "height", "m"},                {"rng_vpos", "range finder height", "height", "m"},
    {"mag_field[0]", "magnetometer x", "magnetometer", "gauss"}, {"mag_field[1]", "magnetometer y", "magnetometer", "gauss"},
    {"mag_field[2]", "magnetometer z", "magnetometer", "gauss"}, {"heading", "heading", "heading", "deg"},
};

/// The test ratios (a vector's ratio is in its first element, as EKF2 writes it): 1 or more rejects.
inline constexpr Px4InnovationField kPx4TestRatioFields[] = {
    {"gps_hvel[0]", "GPS velocity horizontal", "ratio", ""}, {"gps_vvel", "GPS velocity vertical", "ratio", ""},
    {"gps_hpos[0]", "GPS position", "ratio", ""},            {"gps_vpos", "GPS height", "ratio", ""},
    {"baro_vpos", "barometer height", "ratio", ""},          {"ev_hvel[0]", "vision velocity horizontal", "ratio", ""},
    {"ev_vvel", "vision velocity vertical", "ratio", ""},    {"ev_hpos[0]", "vision position", "ratio", ""},
    {"ev_vpos", "vision height", "ratio", ""},               {"rng_vpos", "range finder height", "ratio", ""},
    {"mag_field[0]", "magnetometer", "ratio", ""},           {"heading", "heading", "ratio", ""},
};

/// The newest FILE.px4/log/**.ulg beside the recording FILE.tlog (by modification time), or
/// nullopt when there is none.
std::optional<std::string> find_px4_ulog(const std::string& tlog_path);

/// PX4's estimate from the ULog at `ulog_path`, placed on `log`'s time axis and compared with its
/// truth. An Error when the ULog cannot be read or is refused (engine/ulog), when the recording has
/// no simulator's clock to place it on, or when the ULog's times do not overlap the recording's
/// (another session's log, or PX4 not in lockstep).
Expected<Px4Estimate> read_px4_estimate(const std::string& ulog_path, const FlightLog& log);

}  // namespace hitl::report
