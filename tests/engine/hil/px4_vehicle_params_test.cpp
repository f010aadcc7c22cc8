// The parameters hitl gives the PX4 it starts (engine/hil/px4_vehicle_params.h).
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "engine/model/x500_defaults.h"
#include "engine/hil/px4_vehicle_params.h"

namespace hitl::hil {
namespace {

TEST(Px4VehicleParams, TheX500sGeometryAndHoverAsDocsSimMdGivesThem) {
  std::map<std::string, std::string> p;
  for (const auto& q : px4_vehicle_params(model::x500_vehicle_config(), model::default_world_config().gravity_m_s2))
    p[q.name] = q.value;
  EXPECT_EQ(p["CA_ROTOR_COUNT"], "4");
  // docs/sim.md: rotor 0 front right CCW, 1 back left CCW, 2 front left CW, 3 back right CW.
  EXPECT_EQ(p["CA_ROTOR0_PX"], "0.174");
  EXPECT_EQ(p["CA_ROTOR0_PY"], "0.174");
  EXPECT_EQ(p["CA_ROTOR0_KM"], "0.05");
  EXPECT_EQ(p["CA_ROTOR1_PX"], "-0.174");
  EXPECT_EQ(p["CA_ROTOR1_PY"], "-0.174");
  EXPECT_EQ(p["CA_ROTOR1_KM"], "0.05");
  EXPECT_EQ(p["CA_ROTOR2_PX"], "0.174");
  EXPECT_EQ(p["CA_ROTOR2_PY"], "-0.174");
  EXPECT_EQ(p["CA_ROTOR2_KM"], "-0.05");
  EXPECT_EQ(p["CA_ROTOR3_PX"], "-0.174");
  EXPECT_EQ(p["CA_ROTOR3_PY"], "0.174");
  EXPECT_EQ(p["CA_ROTOR3_KM"], "-0.05");
  EXPECT_NEAR(std::stod(p["MPC_THR_HOVER"]), 0.59, 0.005);
  EXPECT_EQ(p["THR_MDL_FAC"], "1");
}

}  // namespace
}  // namespace hitl::hil
