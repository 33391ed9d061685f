// The engine both string-stability tests share (held_out_side_comparison.h): the held-out data's
// shortage, the paired bootstrap of squared errors, and the verdict rule; and the held-out scoring
// both use (side_fits.h), with or without effects, and its rule for a diverged prediction.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "acc_identification/calibration/held_out_side_comparison.h"
#include "acc_identification/calibration/side_fits.h"
#include "acc_identification/model/follower_simulation.h"

namespace acc
{
namespace
{
/// n samples at 10 Hz in segments of `length` samples each.
HeldOutSegments segmentsOf(std::size_t segments, std::size_t length)
{
  HeldOutSegments out;
  for (std::size_t i = 0; i < segments; ++i)
  {
    out.scored_lengths.push_back(length);
    out.scored_samples += length;
    out.duration_s += 0.1 * static_cast<double>(length);
  }
  return out;
}

/// Squared errors of a model whose error has this standard deviation, seeded.
std::vector<double> squaredErrors(std::size_t n, double sigma, std::uint64_t seed)
{
  std::mt19937_64 engine(seed);
  std::normal_distribution<double> normal(0.0, sigma);
  std::vector<double> out(n);
  for (double& value : out)
  {
    const double e = normal(engine);
    value = e * e;
  }
  return out;
}

/// 60 s at 10 Hz behind a leader that slows from 20 to 16 m/s and back, the follower in
/// equilibrium at the start.
CarFollowingRun brakingLeaderRun()
{
  CarFollowingRun run;
  for (std::size_t k = 0; k < 600; ++k)
  {
    const double t = 0.1 * static_cast<double>(k);
    run.time_s.push_back(t);
    run.leader_speed_mps.push_back(t > 20.0 && t < 26.0 ? 16.0 : 20.0);
    run.follower_speed_mps.push_back(20.0);
    run.space_gap_m.push_back(30.0);
  }
  return run;
}
}  // namespace

TEST(HeldOutSideComparison, ShortageSaysWhyInPlainNumbers)
{
  HeldOutComparisonOptions options;
  EXPECT_EQ(heldOutShortage(segmentsOf(4, 200), options), "");
  // 699 samples over 69.9 s: long enough in samples, too short in time.
  EXPECT_EQ(heldOutShortage(segmentsOf(1, 699), options),
            "too few held-out samples (699 over 69.9 s; need 300 samples and 80 s)");
}

TEST(HeldOutSideComparison, TheBetterSideIsFoundAndTheOtherRejected)
{
  const HeldOutSegments segments = segmentsOf(4, 1000);
  HeldOutComparisonOptions options;
  const std::vector<double> good = squaredErrors(4000, 0.2, 1), bad = squaredErrors(4000, 0.4, 2);
  const HeldOutSideComparison stable_better(good, bad, segments, options);
  EXPECT_TRUE(stable_better.stableWins());
  EXPECT_LT(stable_better.meanDifference(), 0.0);
  EXPECT_LE(stable_better.pValueUnstableRejected(), 0.01);
  EXPECT_GE(stable_better.pValueStableRejected(), 0.99);
  // The blocks: automatic, within [20, 60] s and at most a quarter of the 400 s held out.
  EXPECT_GE(stable_better.blockLengthS(), 20.0 - 1e-9);
  EXPECT_LE(stable_better.blockLengthS(), 60.0 + 1e-9);
  // The better side scored against itself is not worse; the worse side is.
  EXPECT_GT(stable_better.pValueWorseThanBetterSide(good), 0.4);
  EXPECT_LE(stable_better.pValueWorseThanBetterSide(bad), 0.01);

  const HeldOutSideComparison unstable_better(bad, good, segments, options);
  EXPECT_FALSE(unstable_better.stableWins());
  EXPECT_LE(unstable_better.pValueStableRejected(), 0.01);
}

TEST(HeldOutSideComparison, AFixedBlockLengthIsKeptUnlessTooFewBlocksFit)
{
  HeldOutComparisonOptions options;
  options.block_length_s = 30.0;
  const std::vector<double> a = squaredErrors(4000, 0.2, 3), b = squaredErrors(4000, 0.2, 4);
  EXPECT_NEAR(HeldOutSideComparison(a, b, segmentsOf(4, 1000), options).blockLengthS(), 30.0, 1e-9);
  // 100 s held out hold only four blocks of 25 s.
  const std::vector<double> c = squaredErrors(1000, 0.2, 5), d = squaredErrors(1000, 0.2, 6);
  EXPECT_NEAR(HeldOutSideComparison(c, d, segmentsOf(1, 1000), options).blockLengthS(), 25.0, 1e-9);
}

TEST(HeldOutSideComparison, AVerdictNeedsTheWinnerStrictlyInsideItsSide)
{
  HeldOutVerdict result;
  result.p_value_stable_rejected = 0.01;
  result.p_value_unstable_rejected = 0.99;
  EXPECT_EQ(decideSides(result, true, false), SideDecision::Decided);
  EXPECT_EQ(result.verdict, StabilityVerdict::Unstable);
  EXPECT_DOUBLE_EQ(result.p_value, 0.01);
  // The same p-values with the unstable winner on the boundary: undecided.
  EXPECT_EQ(decideSides(result, false, true), SideDecision::RejectedWinnerNotInside);
  EXPECT_EQ(result.verdict, StabilityVerdict::Undecided);
  EXPECT_DOUBLE_EQ(result.p_value, 0.01);
  result.p_value_stable_rejected = 0.2;
  EXPECT_EQ(decideSides(result, true, true), SideDecision::NeitherRejected);
  EXPECT_EQ(result.verdict, StabilityVerdict::Undecided);
  result.p_value_unstable_rejected = 0.04;
  EXPECT_EQ(decideSides(result, true, true), SideDecision::Decided);
  EXPECT_EQ(result.verdict, StabilityVerdict::Stable);
}

TEST(HeldOutSideComparison, AVerdictNotTestedHasNoPValue)
{
  const HeldOutVerdict untested;
  EXPECT_TRUE(std::isnan(untested.p_value));
  EXPECT_TRUE(std::isnan(untested.p_value_stable_rejected));
  EXPECT_EQ(untested.verdict, StabilityVerdict::Undecided);
  // Said in words, never as "nan"; a tested one names each p-value's hypothesis.
  EXPECT_EQ(pValuesText(untested), "(not tested, no p-values)");
  HeldOutVerdict tested;
  tested.p_value_stable_rejected = 0.002;
  tested.p_value_unstable_rejected = 0.97;
  EXPECT_EQ(pValuesText(tested), "(p (H0: stable) = 0.002; p (H0: unstable) = 0.97)");
}

TEST(HeldOutErrors, AModelWithoutEffectsIsScoredAsTheBaseModelAndEffectsEnterTheSimulation)
{
  const std::vector<CarFollowingRun> held_out = {brakingLeaderRun()};
  const AccParameters p{0.1, 0.5, 1.2, 6.0};
  const HeldOutErrors base = heldOutErrors(p, held_out);
  const HeldOutErrors none = heldOutErrors(p, EffectSettings{}, held_out);
  EXPECT_EQ(base.error, none.error);
  ASSERT_EQ(base.error.size(), 599u);  // every sample but the measured start
  EffectSettings delayed;
  delayed.reaction_delay_s = 0.8;
  const HeldOutErrors with_delay = heldOutErrors(p, delayed, held_out);
  const SimulatedFollower sim = simulateFollower(p, delayed, held_out[0]);
  ASSERT_EQ(with_delay.error.size(), 599u);
  EXPECT_DOUBLE_EQ(with_delay.error[250], held_out[0].follower_speed_mps[251] - sim.speed_mps[251]);
  EXPECT_NE(with_delay.error[250], base.error[250]);
  EXPECT_FALSE(with_delay.diverged);
}

TEST(HeldOutErrors, ADivergedPredictionStopsTheComparisonWithTheReason)
{
  const std::vector<CarFollowingRun> held_out = {brakingLeaderRun()};
  // k2 h = 3 > 2: the explicit Euler step itself is unstable and the simulation runs away.
  const HeldOutErrors runaway = heldOutErrors({0.1, 30.0, 1.2, 6.0}, held_out);
  const HeldOutErrors fine = heldOutErrors({0.1, 0.5, 1.2, 6.0}, held_out);
  ASSERT_TRUE(runaway.diverged);
  ASSERT_FALSE(fine.diverged);
  EXPECT_EQ(heldOutDivergence(fine, fine), "");
  EXPECT_EQ(heldOutDivergence(runaway, fine), "the best stable model's simulation diverges on the held-out data");
  EXPECT_EQ(heldOutDivergence(fine, runaway, "reaction_delay"),
            "the best unstable reaction_delay model's simulation diverges on the held-out data");
}
TEST(HeldOutErrors, BothSidesAreScoredAsTheComparisonTakesThem)
{
  HeldOutErrors stable, unstable;
  stable.error = {1.0, -3.0};
  unstable.error = {0.5, 0.5};
  const HeldOutSides sides = scoreHeldOutSides(stable, unstable);
  EXPECT_EQ(sides.stable_squared, (std::vector<double>{1.0, 9.0}));
  EXPECT_EQ(sides.unstable_squared, (std::vector<double>{0.25, 0.25}));
  EXPECT_DOUBLE_EQ(sides.stable_rmse_speed_mps, std::sqrt(5.0));
  EXPECT_DOUBLE_EQ(sides.unstable_rmse_speed_mps, 0.5);
  EXPECT_EQ(sides.divergence, "");
  unstable.diverged = true;
  EXPECT_EQ(scoreHeldOutSides(stable, unstable, "reaction_delay").divergence,
            "the best unstable reaction_delay model's simulation diverges on the held-out data");
}

}  // namespace acc
