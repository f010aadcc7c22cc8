// HIL_GPS -> sensor_gps on the apps processor, as PX4's MavlinkReceiver::handle_message_hil_gps
// decodes it (the spec: "Bridges HIL_GPS to the standard sensor_gps topic"; no batching, one
// record per message, stamped on arrival).
//   lat/lon degE7 -> deg (x 1e-7); alt mm -> m (x 1e-3), used for MSL and ellipsoid;
//   eph/epv cm -> m (x 1e-2; 65535 passes through as 655.35 m, as in PX4);
//   vel/vn/ve/vd cm/s -> m/s (/ 100); cog cdeg -> rad wrapped to [0, 2pi), 65535 -> NaN;
//   satellites_visible -> satellites_used; s_variance 0.25 m/s, c_variance 0.5 rad (PX4's);
//   heading NaN (no GPS yaw); device_id kDeviceIdGps.
#pragma once

#include <cstdint>

#include "target/core/hil_inputs.h"
#include "target/core/px4_topics.h"

namespace hitl::target {

inline constexpr uint16_t kHilGpsCogUnknown = 65535;

/// HIL_GPS.cog (centidegrees) -> course over ground in radians in [0, 2pi); NaN when unknown.
float cog_rad_from_cdeg(uint16_t cog_cdeg);

/// The sensor_gps record for one HIL_GPS that arrived at `now_us`.
SensorGps to_sensor_gps(const HilGpsInput& gps, uint64_t now_us);

}  // namespace hitl::target
