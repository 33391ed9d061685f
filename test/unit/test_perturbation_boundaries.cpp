// The perturbation finder, the dip measurement and the perturbation windows at their boundaries:
// each test holds one rule at the exact value where it changes (found surviving as mutants).
#include <gtest/gtest.h>

#include <climits>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

#include "acc_identification/evidence/perturbation.h"
#include "acc_identification/evidence/perturbation_windows.h"

namespace
{
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
/// n samples of speed(t) every step_s from t = 0 (steps exact in binary: 0.5, 1.0).
void sampleAt(const std::function<double(double)>& speed, double step_s, int n, std::vector<double>* time_s,
              std::vector<double>* speed_mps)
{
  for (int i = 0; i < n; ++i)
  {
    time_s->push_back(step_s * i);
    speed_mps->push_back(speed(step_s * i));
  }
}
}  // namespace

// "More than drop_below_median_mps below the median": a speed exactly 1 m/s below is no drop.
TEST(PerturbationBoundaries, ASpeedExactlyTheDropThresholdBelowTheMedianIsNoPerturbation)
{
  std::vector<double> t, v;
  sampleAt([](double s) { return s >= 20.0 && s < 24.0 ? 9.0 : 10.0; }, 0.5, 200, &t, &v);
  EXPECT_TRUE(acc::findPerturbations(t, v).empty());
}

// Drops exactly merge_within_s apart (last sample below at 22.5 s, next first below at 27.5 s)
// are two perturbations; "closer than" 5 s merges.
TEST(PerturbationBoundaries, DropsExactlyTheMergeSpanApartAreTwoPerturbations)
{
  std::vector<double> t, v;
  sampleAt([](double s) { return (s >= 20.0 && s < 23.0) || (s >= 27.5 && s < 31.0) ? 7.0 : 10.0; }, 0.5, 200, &t, &v);
  const auto found = acc::findPerturbations(t, v);
  ASSERT_EQ(found.size(), 2u);
  EXPECT_DOUBLE_EQ(found[0].end_s, 23.0);
  EXPECT_DOUBLE_EQ(found[1].onset_s, 27.0);
}

// A drop whose first and last samples below are exactly min_duration_s apart is kept.
TEST(PerturbationBoundaries, ADropLastingExactlyTheMinimumDurationIsKept)
{
  std::vector<double> t, v;
  sampleAt([](double s) { return s >= 20.0 && s <= 21.0 ? 7.0 : 10.0; }, 0.5, 200, &t, &v);  // 20, 20.5, 21
  const auto found = acc::findPerturbations(t, v);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_DOUBLE_EQ(found[0].onset_s, 19.5);
  EXPECT_DOUBLE_EQ(found[0].end_s, 21.5);
}

// A sample exactly onset_below_median_mps below the median is near it: the onset.
TEST(PerturbationBoundaries, ASampleExactlyTheOnsetMarginBelowTheMedianIsTheOnset)
{
  std::vector<double> t, v;
  sampleAt([](double s) { return s == 19.0 ? 9.75 : s == 19.5 ? 9.5 : s >= 20.0 && s < 24.0 ? 6.0 : 10.0; }, 0.5, 200,
           &t, &v);
  const auto found = acc::findPerturbations(t, v);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_DOUBLE_EQ(found[0].onset_s, 19.0);
}

// The window's end: the last sample before end_s + extension_s (30 s), a dip's minimum there counts.
TEST(PerturbationBoundaries, TheDipWindowRunsToTheLastSampleBeforeTheEndPlusTheExtension)
{
  std::vector<double> t, v;
  sampleAt([](double s) { return s >= 20.0 && s < 24.0 ? 7.0 : 10.0; }, 0.5, 200, &t, &v);
  const auto found = acc::findPerturbations(t, v);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_DOUBLE_EQ(found[0].end_s, 24.0);
  EXPECT_DOUBLE_EQ(found[0].window_end_s, 53.5);
  EXPECT_EQ(found[0].window_end, 108u);
  EXPECT_FALSE(found[0].window_cut);
  // A follower whose lowest sample (5 m/s) is the window's last, rising after it.
  std::vector<double> late(t.size(), 10.0);
  late[106] = 7.0;
  late[107] = 5.0;
  late[108] = 4.0;  // outside the window
  EXPECT_DOUBLE_EQ(acc::dipDepthMps(t, late, found[0]), 5.0);
}

// The pre-perturbation speed: the mean over [onset - pre_window_s, onset], both ends included.
TEST(PerturbationBoundaries, ThePreWindowMeanHoldsTheOnsetAndTheSampleExactlyAPreWindowBefore)
{
  std::vector<double> t, v;
  sampleAt([](double s) { return s == 15.0 ? 12.0 : s == 20.0 ? 9.8 : s >= 21.0 && s < 25.0 ? 6.0 : 10.0; }, 1.0, 100,
           &t, &v);
  const auto found = acc::findPerturbations(t, v);
  ASSERT_EQ(found.size(), 1u);
  ASSERT_DOUBLE_EQ(found[0].onset_s, 20.0);
  const double pre = (12.0 + 4 * 10.0 + 9.8) / 6.0;
  EXPECT_NEAR(acc::dipDepthMps(t, v, found[0]), pre - 6.0, 1e-12);
  // The distance lost: every trapezoid from the onset to the window's end, of the speed below the
  // pre-perturbation mean (10.3 m/s, so the samples back at 10 m/s still count).
  double lost = 0.0;
  double previous = 9.8;
  for (std::size_t i = found[0].onset + 1; i < found[0].window_end; ++i)
  {
    lost += 0.5 * (std::max(0.0, pre - previous) + std::max(0.0, pre - v[i]));
    previous = v[i];
  }
  EXPECT_NEAR(acc::distanceLostM(t, v, found[0]), lost, 1e-12);
  const acc::WindowRows rows = acc::perturbationWindowRows(t, found[0]);
  EXPECT_EQ(rows.first, 15u);  // from exactly pre_window_s before the onset
  EXPECT_EQ(rows.end, found[0].window_end);
}

// A hole of exactly max_bridged_hole_s (1 s) is bridged; 1.5 s is not.
TEST(PerturbationBoundaries, AHoleOfExactlyTheBridgedLengthIsBridgedAndALongerOneIsNot)
{
  std::vector<double> t, v;
  sampleAt([](double s) { return s >= 20.0 && s < 24.0 ? 7.0 : 10.0; }, 0.5, 200, &t, &v);
  const auto found = acc::findPerturbations(t, v);
  ASSERT_EQ(found.size(), 1u);
  std::vector<double> one = v;
  one[60] = kNaN;  // 30 s: 29.5 to 30.5 s, 1.0 s
  EXPECT_TRUE(acc::windowCovered(t, one, found[0]));
  EXPECT_DOUBLE_EQ(acc::dipDepthMps(t, one, found[0]), 3.0);
  std::vector<double> longer = v;
  longer[60] = longer[61] = kNaN;  // 29.5 to 31 s, 1.5 s
  EXPECT_FALSE(acc::windowCovered(t, longer, found[0]));
  EXPECT_TRUE(std::isnan(acc::dipDepthMps(t, longer, found[0])));
}

// A window the data do not cut is not judged for cut dips: a follower still slowing at its end
// keeps its measured dip (the data go on past the window).
TEST(PerturbationBoundaries, AWindowTheDataDoNotCutIsNotJudgedForCutDips)
{
  std::vector<double> t, v;
  sampleAt([](double s) { return s >= 20.0 && s < 24.0 ? 7.0 : 10.0; }, 0.5, 200, &t, &v);
  auto found = acc::findPerturbations(t, v);
  ASSERT_EQ(found.size(), 1u);
  ASSERT_FALSE(found[0].window_cut);
  std::vector<double> slowing;
  for (double s : t)
    slowing.push_back(s < 30.0 ? 10.0 : 10.0 - 0.1 * (s - 30.0));
  acc::judgeCutWindows(found, t, {{"car 2", &slowing, 2}});
  EXPECT_EQ(found[0].first_cut_order, INT_MAX);
  EXPECT_EQ(found[0].incomplete, "");
}

// In a cut window a follower that rose again by a quarter of its dip or more after its lowest
// holds its dip whole: one that rose by 30 % of it is whole, one that rose by 20 % is not.
TEST(PerturbationBoundaries, ACutDipIsWholeOnceTheCarRoseAQuarterOfItBack)
{
  std::vector<double> t, v;
  sampleAt([](double s) { return s >= 20.0 && s < 24.0 ? 7.0 : 10.0; }, 0.5, 80, &t, &v);  // ends at 39.5 s
  const auto rising = [&](double share) {
    std::vector<double> car;
    for (double s : t)
      car.push_back(s < 26.0 ? 10.0 : s < 30.0 ? 10.0 - (s - 26.0) : s < 35.0 ? 6.0 : 6.0 + 4.0 * share);
    return car;
  };
  const std::vector<double> thirty = rising(0.3), twenty = rising(0.2);
  auto found = acc::findPerturbations(t, v);
  ASSERT_EQ(found.size(), 1u);
  ASSERT_TRUE(found[0].window_cut);
  acc::judgeCutWindows(found, t, {{"car 2", &thirty, 2}, {"car 3", &twenty, 3}});
  EXPECT_EQ(found[0].first_cut_order, 3);
}

// Data that begin one sample before the drop: that sample is the onset (the perturbation is
// whole), and the window's rows start at the data's first.
TEST(PerturbationBoundaries, AnOnsetAtTheDatasFirstSampleIsAnOnset)
{
  std::vector<double> t, v;
  sampleAt([](double s) { return s >= 1.0 && s < 5.0 ? 6.0 : 10.0; }, 1.0, 100, &t, &v);
  const auto found = acc::findPerturbations(t, v);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].onset, 0u);
  EXPECT_EQ(found[0].incomplete, "");
  EXPECT_DOUBLE_EQ(acc::dipDepthMps(t, v, found[0]), 4.0);
  std::vector<double> later, w;
  sampleAt([](double s) { return s >= 3.0 && s < 7.0 ? 6.0 : 10.0; }, 1.0, 100, &later, &w);
  const auto second = acc::findPerturbations(later, w);
  ASSERT_EQ(second.size(), 1u);
  EXPECT_EQ(second[0].onset, 2u);
  EXPECT_EQ(acc::perturbationWindowRows(later, second[0]).first, 0u);
}

// The dip window's first sample is the onset: a follower missing it is not measured, and one at
// its lowest there (still low from before) dips that deep.
TEST(PerturbationBoundaries, TheOnsetSampleIsTheWindowsFirst)
{
  std::vector<double> t, v;
  sampleAt([](double s) { return s >= 21.0 && s < 25.0 ? 6.0 : s == 20.0 ? 9.8 : 10.0; }, 1.0, 100, &t, &v);
  const auto found = acc::findPerturbations(t, v);
  ASSERT_EQ(found.size(), 1u);
  ASSERT_EQ(found[0].onset, 20u);
  std::vector<double> missing(t.size(), 10.0);
  missing[22] = 7.0;
  missing[20] = kNaN;
  EXPECT_FALSE(acc::windowCovered(t, missing, found[0]));
  EXPECT_TRUE(std::isnan(acc::dipDepthMps(t, missing, found[0])));
  std::vector<double> low_at_onset(t.size(), 10.0);
  low_at_onset[20] = 8.0;
  for (std::size_t i = 21; i < 40; ++i)
    low_at_onset[i] = 9.0;
  EXPECT_NEAR(acc::dipDepthMps(t, low_at_onset, found[0]), (50.0 + 8.0) / 6.0 - 8.0, 1e-12);
}

// A reference without loss leaves the relative improvement undefined, not minus infinity.
TEST(PerturbationBoundaries, AReferenceWithoutLossHasNoRelativeImprovement)
{
  const acc::PairedLossComparison c = acc::pairedLossMeans({{0.0, 2.0, 2}, {0.0, 1.0, 1}});
  EXPECT_DOUBLE_EQ(c.candidate_loss, 1.0);
  EXPECT_TRUE(std::isnan(c.relative_improvement));
}
