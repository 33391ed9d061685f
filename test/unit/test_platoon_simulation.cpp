#include <gtest/gtest.h>

#include <cmath>

#include "acc_identification/model/acc_model.h"
#include "acc_identification/model/paper_settings.h"
#include "acc_identification/model/platoon_simulation.h"


namespace
{
// Fig. 2 of the paper: a lead vehicle cruising at 25 m/s steps down by 5 m/s and back up.
acc::PlatoonTrajectory figureTwoPlatoon(double tau_e_s)
{
  const auto lead = acc::stepDownUpLeadProfile(25.0, 5.0, 20.0, 60.0, 200.0, 0.1);
  return acc::simulatePlatoon(acc::paperFigure2Setting(tau_e_s), lead, 0.1, 9);
}
}  // namespace

TEST(PlatoonSimulation, StartsAtEquilibriumAndStaysThereUnderConstantLead)
{
  const acc::AccParameters p = acc::paperMinimumSetting();
  const auto platoon = acc::simulatePlatoon(p, std::vector<double>(1000, 22.0), 0.1, 5);
  ASSERT_EQ(platoon.vehicleCount(), 6u);
  ASSERT_EQ(platoon.sampleCount(), 1000u);
  EXPECT_TRUE(std::isnan(platoon.space_gap_m[0][0]));
  for (std::size_t i = 1; i < platoon.vehicleCount(); ++i)
  {
    EXPECT_NEAR(platoon.speed_mps[i].back(), 22.0, 1e-9);
    EXPECT_NEAR(platoon.space_gap_m[i].back(), acc::equilibriumSpaceGapM(p, 22.0), 1e-9);
  }
}

TEST(PlatoonSimulation, LeadProfileIsAStepDownAndBackUp)
{
  const auto lead = acc::stepDownUpLeadProfile(25.0, 5.0, 20.0, 60.0, 100.0, 0.1);
  ASSERT_EQ(lead.size(), 1001u);
  EXPECT_DOUBLE_EQ(lead[199], 25.0);
  EXPECT_DOUBLE_EQ(lead[201], 20.0);
  EXPECT_DOUBLE_EQ(lead[599], 20.0);
  EXPECT_DOUBLE_EQ(lead[601], 25.0);
}

// tau_e = 0.75 s is string unstable: the undershoot grows from vehicle to vehicle.
TEST(PlatoonSimulation, FigureTwoUnstableSettingAmplifiesTheDip)
{
  const auto minimum = acc::minimumSpeedPerVehicle(figureTwoPlatoon(0.75));
  ASSERT_EQ(minimum.size(), 10u);
  for (std::size_t i = 1; i < minimum.size(); ++i)
  {
    EXPECT_LT(minimum[i], minimum[i - 1]) << "vehicle " << i;
  }
  EXPECT_LT(minimum.back(), 20.0 - 1.0);  // a clear overshoot below the lead's 20 m/s
}

// tau_e = 3.2 s is string stable: nobody goes below the lead's low speed.
TEST(PlatoonSimulation, FigureTwoStableSettingDoesNotAmplifyTheDip)
{
  const auto minimum = acc::minimumSpeedPerVehicle(figureTwoPlatoon(3.2));
  for (std::size_t i = 1; i < minimum.size(); ++i)
  {
    EXPECT_GE(minimum[i], minimum[i - 1] - 1e-9) << "vehicle " << i;
  }
}
