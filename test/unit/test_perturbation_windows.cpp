// What the campaign's platoon diagnosis and diagnose share to judge models inside a leader's
// perturbations (perturbation_windows.h): the window's speed MSE and the paired comparison of two
// models over perturbations with its wild cluster bootstrap, and the samples inside the windows.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "acc_identification/evidence/perturbation_windows.h"

namespace acc
{
TEST(PerturbationWindowMse, AveragesOverTheWindowFromBeforeTheOnsetSkippingMissingSamples)
{
  std::vector<double> time_s, measured, predicted;
  for (std::size_t k = 0; k < 100; ++k)
  {
    time_s.push_back(static_cast<double>(k));
    measured.push_back(10.0);
    predicted.push_back(k < 40 ? 10.0 : 11.0);  // off by 1 m/s from t = 40 s
  }
  predicted[50] = std::numeric_limits<double>::quiet_NaN();
  Perturbation p;
  p.onset = 45;
  p.window_end = 60;
  PerturbationCriteria criteria;
  criteria.pre_window_s = 10.0;  // the window is rows 35 .. 59
  // Rows 35-39 are right, 40-59 off by 1 except the missing row 50: 19 of 24 scored rows.
  EXPECT_DOUBLE_EQ(perturbationWindowMse(time_s, predicted, measured, p, criteria), 19.0 / 24.0);
  std::vector<double> none(100, std::numeric_limits<double>::quiet_NaN());
  EXPECT_TRUE(std::isnan(perturbationWindowMse(time_s, none, measured, p, criteria)));
}

// The samples a braking decides: from the pre-window before each perturbation's onset to the end
// of its dip window, as the window MSE scores them, and none where the leader does not brake.
TEST(InsidePerturbationWindows, MarksEachPerturbationsWindowAndNothingElse)
{
  std::vector<double> time_s, lead;
  for (std::size_t k = 0; k < 1200; ++k)
  {
    const double t = 0.1 * static_cast<double>(k);
    time_s.push_back(t);
    lead.push_back(t >= 40.0 && t < 44.0 ? 15.0 : 20.0);  // one braking of 4 s, 5 m/s deep
  }
  const std::vector<Perturbation> perturbations = findPerturbations(time_s, lead);
  ASSERT_EQ(perturbations.size(), 1u);
  const WindowRows rows = perturbationWindowRows(time_s, perturbations[0]);
  EXPECT_NEAR(time_s[perturbations[0].onset] - time_s[rows.first], PerturbationCriteria{}.pre_window_s, 0.1 + 1e-9);
  EXPECT_EQ(rows.end, perturbations[0].window_end);
  const std::vector<bool> inside = insidePerturbationWindows(time_s, lead);
  ASSERT_EQ(inside.size(), time_s.size());
  for (std::size_t k = 0; k < inside.size(); ++k)
    EXPECT_EQ(inside[k], k >= rows.first && k < rows.end) << "row " << k;
  const std::vector<bool> steady = insidePerturbationWindows(time_s, std::vector<double>(time_s.size(), 20.0));
  EXPECT_EQ(std::count(steady.begin(), steady.end(), true), 0);
}

TEST(PairedLossComparison, MeansImprovementAndTheWildBootstrapOverClusters)
{
  // Three clusters, the candidate better in each: the means per entry, and the p of the wild
  // cluster bootstrap-t on the clusters' differences (against - candidate), in order.
  const std::vector<LossCluster> better = {{2.0, 1.0, 1}, {4.0, 3.0, 2}, {1.0, 0.5, 1}};
  const PairedLossComparison c = comparePairedLosses(better, 999, 7);
  EXPECT_EQ(c.clusters, 3u);
  EXPECT_EQ(c.entries, 4u);
  EXPECT_DOUBLE_EQ(c.against_loss, 7.0 / 4.0);
  EXPECT_DOUBLE_EQ(c.candidate_loss, 4.5 / 4.0);
  EXPECT_DOUBLE_EQ(c.relative_improvement, 1.0 - 4.5 / 7.0);
  const ClusteredDifferences d = differencesOf(better);
  EXPECT_EQ(d.clusters, (std::vector<std::size_t>{0, 1, 2}));
  EXPECT_EQ(d.sums, (std::vector<double>{1.0, 1.0, 0.5}));
  EXPECT_EQ(d.sizes, (std::vector<std::size_t>{1, 2, 1}));
  EXPECT_DOUBLE_EQ(c.p_value, wildClusterTest(d.sums, d.sizes, 999, 7).p_value);
  EXPECT_LT(c.p_value, 0.1);  // three of three improve: 1 in 8 by chance, and the spread is small
  // Swapped: no improvement.
  std::vector<LossCluster> worse;
  for (const LossCluster& k : better)
    worse.push_back({k.candidate, k.against, k.n});
  EXPECT_GT(comparePairedLosses(worse, 999, 7).p_value, 0.9);
  // One cluster has no spread to weigh.
  EXPECT_DOUBLE_EQ(comparePairedLosses({better[0]}, 999, 7).p_value, 1.0);
}

}  // namespace acc
