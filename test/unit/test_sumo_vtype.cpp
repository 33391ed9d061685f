// SUMO export: SUMO 1.15's ACC law as the package replicates it, the mapping of an identified
// model onto a vType (what is exact, approximate, missing), and the additional file read back.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <unistd.h>

#include "acc_identification/model/follower_simulation.h"
#include "acc_identification/sumo/sumo_acc_simulation.h"
#include "acc_identification/sumo/sumo_vtype.h"

namespace acc
{
namespace
{
const AccParameters kModel{0.08, 0.45, 1.3, 6.0};

const SumoMappingNote* findNote(const SumoExport& exported, const std::string& part)
{
  for (const SumoMappingNote& note : exported.notes)
    if (note.part == part)
      return &note;
  return nullptr;
}

std::string temporaryPath(const std::string& name)
{
  return (std::filesystem::temp_directory_path() / ("acc_test_sumo_" + std::to_string(::getpid()) + name)).string();
}

TEST(SumoAccLaw, GapMarginIsXiaosAsSumo115HasIt)
{
  EXPECT_DOUBLE_EQ(sumoAccGapMargin(5.0), 2.0);
  EXPECT_DOUBLE_EQ(sumoAccGapMargin(10.79), 2.0);
  EXPECT_NEAR(sumoAccGapMargin(12.0), 75.0 / 12.0 - 5.0, 1e-12);
  EXPECT_NEAR(sumoAccGapMargin(15.0), 0.0, 1e-12);
  EXPECT_DOUBLE_EQ(sumoAccGapMargin(20.0), 0.0);
}

TEST(SumoAccLaw, ModesSwitchOnTheSpacingErrorAndTheGapThresholds)
{
  SumoAccGains gains;
  SumoAccState state{50.0, 20.0, 19.0, 30.0, 4.0, SumoAccMode::speed_control};
  // e = 50 - 1.2 * 20 - 4 = 22 > 0: gap closing, with its own gains.
  SumoAccCommand command = sumoAccCommand(gains, 1.2, state);
  EXPECT_EQ(command.mode, SumoAccMode::gap_closing);
  EXPECT_NEAR(command.spacing_error_m, 22.0, 1e-12);
  EXPECT_NEAR(command.acceleration_mps2, 0.8 * (19.0 - 20.0) + 0.04 * 22.0, 1e-12);
  state.gap2pred_m = 20.0;  // e = -8: collision avoidance
  command = sumoAccCommand(gains, 1.2, state);
  EXPECT_EQ(command.mode, SumoAccMode::collision_avoidance);
  EXPECT_NEAR(command.acceleration_mps2, 0.23 * (19.0 - 20.0) + 0.8 * -8.0, 1e-12);
  state.gap2pred_m = 130.0;  // beyond 120 m: speed control towards the desired speed
  command = sumoAccCommand(gains, 1.2, state);
  EXPECT_EQ(command.mode, SumoAccMode::speed_control);
  EXPECT_NEAR(command.acceleration_mps2, -0.4 * (20.0 - 30.0), 1e-12);
  state.gap2pred_m = 110.0;  // between 100 and 120 m: the previous law
  EXPECT_EQ(sumoAccCommand(gains, 1.2, state).mode, SumoAccMode::speed_control);
  state.previous_mode = SumoAccMode::collision_avoidance;
  EXPECT_EQ(sumoAccCommand(gains, 1.2, state).mode, SumoAccMode::gap_closing);
}

TEST(SumoExport, BaseModelMapsOntoEveryGapControlMode)
{
  const SumoExport exported = exportToSumo("Hyundai Nexo/min", kModel, {}, {}, {2.0, 3.0});
  const SumoAccVType& v = exported.vtype;
  EXPECT_EQ(v.id, "Hyundai Nexo/min");
  EXPECT_DOUBLE_EQ(v.tau_s, 1.3);
  EXPECT_DOUBLE_EQ(v.min_gap_m + v.length_m, 6.0);
  EXPECT_DOUBLE_EQ(v.length_m, 4.5);
  for (double gain : {v.gains.gap_closing_gain_space_per_s2, v.gains.gap_control_gain_space_per_s2,
                      v.gains.collision_avoidance_gain_space_per_s2})
    EXPECT_DOUBLE_EQ(gain, 0.08);
  for (double gain : {v.gains.gap_closing_gain_speed_per_s, v.gains.gap_control_gain_speed_per_s,
                      v.gains.collision_avoidance_gain_speed_per_s})
    EXPECT_DOUBLE_EQ(gain, 0.45);
  EXPECT_DOUBLE_EQ(v.accel_mps2, 2.0);
  EXPECT_DOUBLE_EQ(v.decel_mps2, 3.0);
  EXPECT_DOUBLE_EQ(v.emergency_decel_mps2, 9.0);  // SUMO's default: the data show no emergency
  EXPECT_TRUE(std::isnan(v.max_speed_mps));
  ASSERT_NE(findNote(exported, "free-road speed"), nullptr);
  EXPECT_EQ(findNote(exported, "free-road speed")->mapping, SumoMapping::none);
  EXPECT_EQ(sumoId("Hyundai Nexo/min"), "Hyundai_Nexo_min");
}

TEST(SumoExport, ShortJamDistanceGoesIntoTheLength)
{
  const SumoExport exported = exportToSumo("a", {0.08, 0.45, 1.3, 2.0}, {}, {}, {});
  EXPECT_DOUBLE_EQ(exported.vtype.length_m, 2.0);
  EXPECT_DOUBLE_EQ(exported.vtype.min_gap_m, 0.0);
  EXPECT_EQ(findNote(exported, "eta")->mapping, SumoMapping::exact);
  // No data: the floors, never NaN, in a file SUMO must read.
  EXPECT_DOUBLE_EQ(exported.vtype.accel_mps2, SumoExportOptions{}.min_accel_mps2);
  EXPECT_DOUBLE_EQ(exported.vtype.decel_mps2, SumoExportOptions{}.min_decel_mps2);
}

TEST(SumoExport, EffectsMapWhereSumoHasThemAndAreNamedWhereNot)
{
  const std::vector<EffectKind> effects{EffectKind::asymmetric_response, EffectKind::reaction_delay,
                                        EffectKind::acceleration_limits};
  const SumoExport exported = exportToSumo("a", kModel, effects, {0.5, 2.5, 0.6, 1.5, 4.0}, {3.0, 5.0});
  EXPECT_DOUBLE_EQ(exported.vtype.gains.collision_avoidance_gain_space_per_s2, 0.08 * 2.5);
  EXPECT_DOUBLE_EQ(exported.vtype.gains.collision_avoidance_gain_speed_per_s, 0.45);
  EXPECT_EQ(findNote(exported, "asymmetric_response.short_gap_gain_ratio")->mapping, SumoMapping::exact);
  EXPECT_EQ(findNote(exported, "asymmetric_response.closing_gain_ratio")->mapping, SumoMapping::none);
  EXPECT_EQ(findNote(exported, "reaction_delay")->mapping, SumoMapping::approximate);
  EXPECT_NEAR(exported.vtype.action_step_length_s, 1.2, 1e-12);  // 2 d: decisions d old on average
  EXPECT_EQ(findNote(exported, "acceleration_limits")->mapping, SumoMapping::exact);
  EXPECT_DOUBLE_EQ(exported.vtype.accel_mps2, 1.5);  // the fitted limits, not the data's
  EXPECT_DOUBLE_EQ(exported.vtype.emergency_decel_mps2, 4.0);
}

TEST(SumoExport, EffectsSumoLacksAreNamedAndAShortDelayIsNoActionStep)
{
  const SumoExport lag = exportToSumo("a", kModel, {EffectKind::actuation_lag}, {0.5}, {});
  EXPECT_EQ(findNote(lag, "actuation_lag")->mapping, SumoMapping::none);
  EXPECT_TRUE(std::isnan(lag.vtype.action_step_length_s));
  const SumoExport short_delay = exportToSumo("a", kModel, {EffectKind::reaction_delay}, {0.04}, {});
  EXPECT_EQ(findNote(short_delay, "reaction_delay")->mapping, SumoMapping::none);
  EXPECT_TRUE(std::isnan(short_delay.vtype.action_step_length_s));
}

TEST(SumoExport, SetSpeedBecomesMaxSpeedAndTheSpeedControlGain)
{
  const SumoExport exported = exportToSumo("a", kModel, {EffectKind::set_speed_cruise}, {33.0, 0.3}, {});
  EXPECT_DOUBLE_EQ(exported.vtype.max_speed_mps, 33.0);
  EXPECT_DOUBLE_EQ(exported.vtype.gains.speed_control_gain_per_s, -0.3);
  EXPECT_EQ(findNote(exported, "set_speed_cruise")->mapping, SumoMapping::approximate);
}

TEST(SumoExport, ObservedLimitsUseOneSecondDifferences)
{
  CarFollowingRun run;
  for (int k = 0; k <= 100; ++k)
  {
    const double t = 0.1 * k;
    run.time_s.push_back(t);
    // 2 m/s^2 up for 4 s, then 3 m/s^2 down, with +-0.05 m/s of sample noise that a 0.1 s
    // difference would turn into 1 m/s^2.
    const double v = t < 4.0 ? 10.0 + 2.0 * t : 18.0 - 3.0 * (t - 4.0);
    run.follower_speed_mps.push_back(v + (k % 2 == 0 ? 0.05 : -0.05));
  }
  const ObservedAccelerationLimits limits = observedAccelerationLimits({run});
  EXPECT_NEAR(limits.max_acceleration_mps2, 2.0, 0.11);
  EXPECT_NEAR(limits.max_deceleration_mps2, 3.0, 0.11);
  EXPECT_TRUE(std::isnan(observedAccelerationLimits({}).max_acceleration_mps2));
}

TEST(SumoVTypeFile, RoundTripKeepsEveryNumberAndTheSourceModel)
{
  const std::vector<EffectKind> effects{EffectKind::asymmetric_response};
  const SumoExport exported = exportToSumo("car.1", {0.0812345678901234, 0.45, 1.3, 6.0}, effects, {1.0, 2.5},
                                           {1.9, 3.7});
  const std::string path = temporaryPath("roundtrip.add.xml");
  writeSumoAdditional({exported}, path, "made from test data");
  const std::vector<SumoAccVType> read = readSumoAccVTypes(path);
  std::remove(path.c_str());
  ASSERT_EQ(read.size(), 1u);
  const SumoAccVType& v = read.front();
  EXPECT_EQ(v.id, "car.1");
  EXPECT_EQ(v.gains.gap_closing_gain_space_per_s2, 0.0812345678901234);
  EXPECT_EQ(v.gains.collision_avoidance_gain_space_per_s2, exported.vtype.gains.collision_avoidance_gain_space_per_s2);
  EXPECT_EQ(v.accel_mps2, 1.9);
  EXPECT_TRUE(std::isnan(v.action_step_length_s));
  EXPECT_EQ(v.min_gap_m, exported.vtype.min_gap_m);
  ASSERT_TRUE(v.has_source_model);
  EXPECT_EQ(v.source_effects, effects);
  EXPECT_EQ(v.source_effect_values, (std::vector<double>{1.0, 2.5}));
  EXPECT_EQ(v.source_parameters.k1_per_s2, 0.0812345678901234);
  const PackageModel model = packageModelOf(v);
  EXPECT_EQ(model.effects, effects);
}

TEST(SumoVTypeFile, AForeignVTypeGetsSumosDefaultsAndItsNearestModel)
{
  const std::string path = temporaryPath("foreign.rou.xml");
  std::ofstream(path) << "<routes><vType id=\"k\" carFollowModel=\"Krauss\"/>"
                         "<vTypeDistribution id=\"d\"><vType id=\"acc\" carFollowModel=\"ACC\" tau=\"1.5\"/>"
                         "</vTypeDistribution></routes>\n";
  const std::vector<SumoAccVType> read = readSumoAccVTypes(path);
  std::remove(path.c_str());
  ASSERT_EQ(read.size(), 1u);
  EXPECT_EQ(read[0].id, "acc");
  EXPECT_FALSE(read[0].has_source_model);
  EXPECT_DOUBLE_EQ(read[0].gains.gap_closing_gain_speed_per_s, 0.8);
  const PackageModel model = packageModelOf(read[0]);
  EXPECT_DOUBLE_EQ(model.parameters.k1_per_s2, 0.04);
  EXPECT_DOUBLE_EQ(model.parameters.tau_e_s, 1.5);
  EXPECT_DOUBLE_EQ(model.parameters.eta_m, 2.5 + 5.0);
  // Collision avoidance's space gain 0.8 against gap closing's 0.04: an asymmetric response.
  ASSERT_EQ(model.effects.size(), 2u);
  EXPECT_EQ(model.effects[1], EffectKind::asymmetric_response);
  EXPECT_DOUBLE_EQ(model.effect_values[3], 20.0);
}

TEST(SumoVTypeFile, BadFilesAreRefusedWithTheReason)
{
  const std::string path = temporaryPath("bad.add.xml");
  std::ofstream(path) << "<additional><vType id=\"a\" carFollowModel=\"ACC\" tau=\"fast\"/></additional>\n";
  try
  {
    readSumoAccVTypes(path);
    FAIL() << "a non-numeric tau was accepted";
  }
  catch (const std::runtime_error& error)
  {
    EXPECT_NE(std::string(error.what()).find("tau=\"fast\" is not a number"), std::string::npos) << error.what();
  }
  // Without an id the message still says what is wrong (it once built the message from a null id).
  std::ofstream(path) << "<additional><vType carFollowModel=\"ACC\" minGap=\"near\"/></additional>\n";
  try
  {
    readSumoAccVTypes(path);
    FAIL() << "a non-numeric minGap was accepted";
  }
  catch (const std::runtime_error& error)
  {
    EXPECT_NE(std::string(error.what()).find("vType '': minGap=\"near\" is not a number"), std::string::npos)
        << error.what();
  }
  // What SUMO would read otherwise: a truck's class defaults, a nested model element, an emergency
  // braking weaker than the normal one (SUMO stops on an assertion).
  const auto refusal = [&path](const std::string& xml) {
    std::ofstream(path) << xml;
    try
    {
      readSumoAccVTypes(path);
    }
    catch (const std::runtime_error& error)
    {
      return std::string(error.what());
    }
    return std::string();
  };
  EXPECT_NE(refusal("<additional><vType id=\"T\" vClass=\"truck\" carFollowModel=\"ACC\" tau=\"1.2\"/>"
                    "</additional>\n")
                .find("vClass \"truck\" leaves length to its class default"),
            std::string::npos);
  EXPECT_NE(refusal("<additional><vType id=\"K\" carFollowModel=\"ACC\"><carFollowing-Krauss/></vType>"
                    "</additional>\n")
                .find("holds a nested <carFollowing-Krauss> element"),
            std::string::npos);
  EXPECT_NE(refusal("<additional><vType id=\"E\" carFollowModel=\"ACC\" decel=\"4.5\" emergencyDecel=\"0.5\"/>"
                    "</additional>\n")
                .find("emergencyDecel 0.5 below decel 4.5"),
            std::string::npos);
  // A truck's maxSpeed (36.11 m/s) capped it behind a faster leader, blamed on SUMO's safe speed.
  EXPECT_NE(refusal("<additional><vType id=\"T\" vClass=\"truck\" carFollowModel=\"ACC\" length=\"5\" accel=\"2\" "
                    "decel=\"4\" emergencyDecel=\"9\"/></additional>\n")
                .find("leaves maxSpeed to its class default"),
            std::string::npos);
  // A model parameter that is not finite: the model's trace was NaN from its first step, and the
  // replay scored 0 m/s over its start alone, exit 0.
  EXPECT_NE(refusal("<additional><vType id=\"N\" carFollowModel=\"ACC\"><param key=\"acc_identification.k1_per_s2\" "
                    "value=\"nan\"/></vType></additional>\n")
                .find("'nan' is not a finite number"),
            std::string::npos);
  EXPECT_EQ(refusal("<additional><vType id=\"P\" vClass=\"passenger\" carFollowModel=\"ACC\"/></additional>\n"), "");
  std::ofstream(path) << "<additional><vType id=\"a\"";
  EXPECT_THROW(readSumoAccVTypes(path), std::runtime_error);
  std::remove(path.c_str());
  EXPECT_THROW(readSumoAccVTypes(path), std::runtime_error);
}

// SUMO rounds an action step that is not a multiple of the step DOWN, in whole milliseconds: 0.9 s
// at 0.2 s steps acts every 0.8 s (rounded to the nearest, the replica acted every 1.0 s and
// blamed the difference on SUMO's safe speed); 0.8 s at 0.1 s steps is 8 steps, not 7.
TEST(SumoAccSimulation, AnActionStepIsRoundedDownAsSumoRoundsIt)
{
  SumoAccVType vtype;
  vtype.action_step_length_s = 0.9;
  EXPECT_EQ(sumoActionEvery(vtype, 0.2), 4u);
  vtype.action_step_length_s = 0.25;
  EXPECT_EQ(sumoActionEvery(vtype, 0.1), 2u);
  vtype.action_step_length_s = 0.8;
  EXPECT_EQ(sumoActionEvery(vtype, 0.1), 8u);
  vtype.action_step_length_s = 0.05;
  EXPECT_EQ(sumoActionEvery(vtype, 0.1), 1u);
}

/// Where the laws coincide (above 15 m/s, within the bounds), the package's replica of SUMO's step
/// differs from the package's model only by the position update: a step's acceleration times h^2.
TEST(SumoAccSimulation, ReplicaTracksThePackageModelAbove15Mps)
{
  CarFollowingRun run;
  for (int k = 0; k < 3000; ++k)
  {
    const double t = 0.1 * k;
    run.time_s.push_back(t);
    run.leader_speed_mps.push_back(25.0 + 3.0 * std::sin(0.15 * t));
  }
  run.space_gap_m.assign(run.size(), 6.0 + 1.3 * 25.0);
  run.follower_speed_mps.assign(run.size(), 25.0);
  const SumoExport exported = exportToSumo("a", kModel, {}, {}, {5.0, 8.0});
  const SumoAccTrace replica =
      simulateSumoAcc(exported.vtype, run.leader_speed_mps, 0.1, run.space_gap_m[0], 25.0, 70.0);
  const SimulatedFollower model = simulateFollower(kModel, run);
  double worst = 0.0;
  for (std::size_t k = 0; k < run.size(); ++k)
  {
    worst = std::max(worst, std::abs(replica.speed_mps[k] - model.speed_mps[k]));
    EXPECT_FALSE(replica.speed_bound_active[k]);
    EXPECT_NE(replica.mode[k], SumoAccMode::speed_control);
  }
  EXPECT_LT(worst, 0.05);
  EXPECT_GT(worst, 0.0);  // the two position updates differ: the test would see identical code
}

}  // namespace
}  // namespace acc
