// The pair-level judge inside the leader's perturbations (perturbation_window_criterion.h). A model that is right
// where the leader brakes must be named on the windows; too few perturbations must say so; a
// prediction that ran away must lose, not win by its missing samples.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "acc_identification/diagnosis/perturbation_window_criterion.h"
#include "acc_identification/model/follower_simulation.h"

namespace acc
{
namespace
{
const AccParameters kParameters{0.08, 0.45, 1.2, 4.0};

/// A leader at 20 m/s that brakes to 14 m/s for 5 s at each of `brakings` times, the follower
/// driven by the model with a 1 s reaction delay (its recorded speed and gap).
CarFollowingRun delayedFollowerRun(const std::vector<double>& brakings_s)
{
  CarFollowingRun run;
  for (std::size_t k = 0; k < 3600; ++k)
  {
    const double t = 0.1 * static_cast<double>(k);
    bool braking = false;
    for (double start : brakings_s)
      braking = braking || (t >= start && t < start + 5.0);
    run.time_s.push_back(t);
    run.leader_speed_mps.push_back(braking ? 14.0 : 20.0);
    run.follower_speed_mps.push_back(20.0);
    run.space_gap_m.push_back(kParameters.eta_m + kParameters.tau_e_s * 20.0);
  }
  EffectSettings truth;
  truth.reaction_delay_s = 1.0;
  const SimulatedFollower sim = simulateFollower(kParameters, truth, run);
  run.follower_speed_mps = sim.speed_mps;
  run.space_gap_m = sim.space_gap_m;
  return run;
}

std::vector<SimulatedFollower> predict(const std::vector<CarFollowingRun>& runs, const EffectSettings& effects)
{
  std::vector<SimulatedFollower> out;
  for (const CarFollowingRun& run : runs)
    out.push_back(simulateFollower(kParameters, effects, run));
  return out;
}

EffectSettings delayOf(double seconds)
{
  EffectSettings s;
  s.reaction_delay_s = seconds;
  return s;
}
}  // namespace

TEST(PerturbationWindowCriterion, NamesTheModelThatIsRightWhereTheLeaderBrakes)
{
  const std::vector<CarFollowingRun> held_out = {delayedFollowerRun({60.0, 160.0, 260.0})};
  const std::vector<SimulatedFollower> base = predict(held_out, {});
  const std::vector<SimulatedFollower> delayed = predict(held_out, delayOf(1.0));
  const std::vector<SimulatedFollower> too_long = predict(held_out, delayOf(2.5));
  const PerturbationWindowCriterion c = judgeOnPerturbationWindows(
      held_out, base, {{EffectKind::actuation_lag, &too_long}, {EffectKind::reaction_delay, &delayed}});
  EXPECT_EQ(c.perturbations, 3u);
  EXPECT_TRUE(c.reason.empty()) << c.reason;
  ASSERT_EQ(c.effects.size(), 2u);
  EXPECT_EQ(c.effects[1].effect, EffectKind::reaction_delay);
  EXPECT_LT(c.effects[1].window_rmse_speed_mps, 1e-9);  // the truth itself
  EXPECT_GT(c.base_window_rmse_speed_mps, 0.05);
  EXPECT_TRUE(c.effects[1].significant);
  EXPECT_FALSE(c.effects[0].significant);
  EXPECT_EQ(c.named, EffectKind::reaction_delay);
  EXPECT_NE(c.rule.find("wild cluster bootstrap-t over perturbations"), std::string::npos);
}

TEST(PerturbationWindowCriterion, SaysWhyWithFewerThanTwoPerturbations)
{
  const std::vector<CarFollowingRun> held_out = {delayedFollowerRun({100.0})};
  const std::vector<SimulatedFollower> base = predict(held_out, {});
  const std::vector<SimulatedFollower> delayed = predict(held_out, delayOf(1.0));
  const PerturbationWindowCriterion c =
      judgeOnPerturbationWindows(held_out, base, {{EffectKind::reaction_delay, &delayed}});
  EXPECT_EQ(c.perturbations, 1u);
  EXPECT_NE(c.reason.find("at least 2 perturbations"), std::string::npos) << c.reason;
  EXPECT_EQ(c.named, EffectKind::none);
  EXPECT_FALSE(c.effects[0].significant);
}

TEST(PerturbationWindowCriterion, APredictionThatRanAwayLosesInsteadOfWinningByItsMissingSamples)
{
  const std::vector<CarFollowingRun> held_out = {delayedFollowerRun({60.0, 160.0, 260.0})};
  const std::vector<SimulatedFollower> base = predict(held_out, {});
  std::vector<SimulatedFollower> runaway = predict(held_out, delayOf(1.0));
  // Declared diverged from the first sample: its held rows must not be scored.
  runaway[0].diverged = true;
  runaway[0].diverged_at_index = 0;
  const PerturbationWindowCriterion c =
      judgeOnPerturbationWindows(held_out, base, {{EffectKind::reaction_delay, &runaway}});
  EXPECT_EQ(c.perturbations, 3u);
  EXPECT_FALSE(c.effects[0].significant);
  EXPECT_LT(c.effects[0].versus_base.relative_improvement, -1.0);
  EXPECT_EQ(c.named, EffectKind::none);
}

}  // namespace acc
