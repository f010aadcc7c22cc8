// The sensor faults applied where a real sensor goes wrong: to what it reports, after the sensor
// model sampled the truth (a bias or an offset adds to the reading; a lost GPS sends nothing).
//   accel_FRD += accel_bias        gyro_FRD += gyro_bias        mag_FRD += mag_offset
//   pressure += baro_offset_Pa, pressure_alt = ISA altitude of that pressure
//   GPS: none under gps-loss; lat/lon moved by (north_m, east_m) on the WGS-84 ellipsoid
//        (meridian and prime-vertical radii at the fix's latitude); gps-degrade's report replaces
//        fix_type, satellites, eph and epv.
#pragma once

#include "engine/faults/fault_schedule.h"
#include "engine/model/world_config.h"
#include "engine/sensors/sensor_suite.h"

namespace hitl::faults {

void apply_sensor_faults(const ActiveFaults& active, const model::AtmosphereConfig& atmosphere, sensors::SensorFrame& frame);

/// `lat_deg`, `lon_deg` moved `north_m` and `east_m` (WGS-84; exact to millimetres over kilometres).
void offset_lat_lon(double& lat_deg, double& lon_deg, double north_m, double east_m);

}  // namespace hitl::faults
