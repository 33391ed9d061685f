// The fitted model against the data's own dips (calibration/model_dip_check.h): a model that made
// the data predicts their dips; one that answers a braking too softly is caught by the dip check
// of the adequacy; a "stable" verdict over dips the car amplified is called a contradiction.
#include <gtest/gtest.h>

#include <cmath>

#include "acc_identification/calibration/model_adequacy.h"
#include "acc_identification/calibration/model_dip_check.h"
#include "acc_identification/model/follower_simulation.h"
#include "acc_identification/model/paper_settings.h"

namespace acc
{
namespace
{
/// 300 s at 10 Hz: the leader cruises at 20 m/s and brakes by 2.5 m/s over 4 s and back at 60,
/// 140 and 220 s; the follower is the model p itself, started at equilibrium.
CarFollowingRun modelRun(const AccParameters& p)
{
  CarFollowingRun run;
  run.name = "model";
  for (int i = 0; i < 3000; ++i)
  {
    const double t = 0.1 * i;
    double leader = 20.0;
    for (double onset : {60.0, 140.0, 220.0})
    {
      const double into = t - onset;
      if (into > 0.0 && into < 8.0)
        leader -= 2.5 * (1.0 - std::fabs(into - 4.0) / 4.0);
    }
    run.time_s.push_back(t);
    run.leader_speed_mps.push_back(leader);
    run.follower_speed_mps.push_back(20.0);
    run.space_gap_m.push_back(p.eta_m + p.tau_e_s * 20.0);
  }
  const SimulatedFollower simulated = simulateFollower(p, run);
  run.follower_speed_mps = simulated.speed_mps;
  run.space_gap_m = simulated.space_gap_m;
  return run;
}

TEST(ModelDipCheck, TheModelThatMadeTheDataPredictsItsDips)
{
  const AccParameters truth = paperMinimumSetting();
  const CarFollowingRun run = modelRun(truth);
  const PairDipEvidence evidence = pairDipEvidence({run});
  ASSERT_EQ(evidence.dips.size(), 3u);
  const ModelDipCheck check = checkModelDips(truth, {run}, evidence);
  ASSERT_EQ(check.model_dips_mps.size(), 3u);
  EXPECT_EQ(check.scored, 3u);
  EXPECT_LT(check.median_abs_dip_error, 1e-9);
  EXPECT_NEAR(check.model_ratio_of_means, evidence.ratio.ratio_of_means, 1e-9);
}

TEST(ModelDipCheck, ASofterModelFailsTheAdequacyDipCheck)
{
  const AccParameters truth = paperMinimumSetting();
  const CarFollowingRun run = modelRun(truth);
  const PairDipEvidence evidence = pairDipEvidence({run});
  AccParameters soft = truth;
  soft.k1_per_s2 *= 0.2;
  soft.k2_per_s *= 0.2;
  const ModelDipCheck check = checkModelDips(soft, {run}, evidence);
  EXPECT_GT(check.median_abs_dip_error, 0.3) << "the soft model's dips: " << check.model_dips_mps[0];
  ModelAdequacy adequacy = assessModelAdequacy(truth, {run});
  ASSERT_TRUE(adequacy.adequate);
  addDipCheck(adequacy, check.scored, check.median_abs_dip_error);
  EXPECT_FALSE(adequacy.adequate);
  EXPECT_EQ(adequacy.checks.dip_perturbations, 3u);
}

TEST(ModelDipCheck, AStableVerdictOverAmplifiedDipsIsAContradiction)
{
  PairDipEvidence amplified;
  amplified.ratio.count = 4;
  amplified.ratio.ratio_of_means = 1.4;
  amplified.ratio.lower = 1.2;
  amplified.ratio.upper = 1.6;
  amplified.ratio.amplifies = DipAmplification::Amplifies;
  EXPECT_NE(verdictContradiction("stable", amplified).find("amplified"), std::string::npos);
  EXPECT_EQ(verdictContradiction("unstable", amplified), "");
  EXPECT_EQ(verdictContradiction("undecided", amplified), "");
  PairDipEvidence damped = amplified;
  damped.ratio.amplifies = DipAmplification::Attenuates;
  EXPECT_EQ(verdictContradiction("stable", damped), "");
}

}  // namespace
}  // namespace acc
