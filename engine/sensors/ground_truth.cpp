#include "engine/sensors/ground_truth.h"

#include "engine/frames/frames.h"

namespace hitl::sensors {

GroundTruth ground_truth(const model::VehicleState& state, const LocalGeodesy& geodesy) {
  GroundTruth t;
  t.time_s = state.time_s;
  t.p_NED_m = frames::enu_to_ned(state.p_ENU_m);
  t.q_FRD_to_NED = frames::q_FRD_to_NED_from(state.q_FLU_to_ENU);
  t.v_NED_m_s = frames::enu_to_ned(state.v_ENU_m_s);
  t.v_FRD_m_s = t.q_FRD_to_NED.conjugate() * t.v_NED_m_s;
  t.w_FRD_rad_s = frames::flu_to_frd(state.w_FLU_rad_s);
  t.accel_FRD_m_s2 = frames::flu_to_frd(state.specific_force_FLU_m_s2);
  const Geodetic g = geodesy.to_geodetic(state.p_ENU_m);
  t.lat_deg = g.lat_deg;
  t.lon_deg = g.lon_deg;
  t.alt_m = g.alt_m;
  return t;
}

}  // namespace hitl::sensors
