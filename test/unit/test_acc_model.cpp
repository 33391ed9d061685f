#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "acc_identification/model/acc_model.h"
#include "acc_identification/model/car_following_run.h"

using acc::AccParameters;

TEST(AccModel, AccelerationLawMatchesThePaper)
{
  const AccParameters p{0.1, 0.4, 1.5, 5.0};
  // k1 (s - eta - tau v) + k2 dv = 0.1 (40 - 5 - 30) + 0.4 (-2) = 0.5 - 0.8
  EXPECT_NEAR(acc::accelerationMps2(p, 40.0, 20.0, -2.0), -0.3, 1e-12);
  EXPECT_NEAR(acc::accelerationMps2(p, acc::equilibriumSpaceGapM(p, 20.0), 20.0, 0.0),
              0.0, 1e-12);
}

TEST(AccModel, PartialDerivativesAgreeWithFiniteDifferencesAtFixedRelativeSpeed)
{
  const AccParameters p{0.0782, 0.4445, 0.5162, 8.3365};
  const auto d = acc::accelerationPartials(p);
  const double s = 20.0, v = 15.0, dv = 0.7, h = 1e-6;
  auto f = [&](double s_, double v_, double dv_) { return acc::accelerationMps2(p, s_, v_, dv_); };
  EXPECT_NEAR(d.f_s, (f(s + h, v, dv) - f(s - h, v, dv)) / (2 * h), 1e-8);
  EXPECT_NEAR(d.f_v, (f(s, v + h, dv) - f(s, v - h, dv)) / (2 * h), 1e-8);
  EXPECT_NEAR(d.f_dv, (f(s, v, dv + h) - f(s, v, dv - h)) / (2 * h), 1e-8);
  // The common slip f_v = -(k1 tau + k2) must not creep in.
  EXPECT_NEAR(d.f_v, -0.0782 * 0.5162, 1e-12);
}

TEST(AccModel, RationalDrivingConstraints)
{
  EXPECT_TRUE(acc::satisfiesRationalDrivingConstraints({0.1, 0.2, 1.0, 2.0}));
  EXPECT_TRUE(acc::satisfiesRationalDrivingConstraints({0.0, 0.0, 0.0, 0.0}));
  EXPECT_FALSE(acc::satisfiesRationalDrivingConstraints({-0.1, 0.2, 1.0, 2.0}));
  EXPECT_FALSE(acc::satisfiesRationalDrivingConstraints({0.1, -0.2, 1.0, 2.0}));
  EXPECT_FALSE(acc::satisfiesRationalDrivingConstraints({0.1, 0.2, -1.0, 2.0}));
  EXPECT_FALSE(acc::satisfiesRationalDrivingConstraints({0.1, 0.2, 1.0, -2.0}));
  EXPECT_FALSE(acc::satisfiesRationalDrivingConstraints(
      {std::numeric_limits<double>::quiet_NaN(), 0.2, 1.0, 2.0}));
}

TEST(CarFollowingRun, DescribesEveryProblem)
{
  acc::CarFollowingRun run{"ok", {0.0, 0.1}, {10.0, 10.0}, {5.0, 5.0}, {5.0, 5.0}};
  EXPECT_EQ(acc::describeRunProblem(run), "");
  auto bad = run;
  bad.time_s[1] = 0.0;
  EXPECT_NE(acc::describeRunProblem(bad).find("time does not increase"), std::string::npos);
  bad = run;
  bad.space_gap_m[1] = std::nan("");
  EXPECT_NE(acc::describeRunProblem(bad).find("space_gap_m"), std::string::npos);
  bad = run;
  bad.leader_speed_mps.pop_back();
  EXPECT_EQ(acc::describeRunProblem(bad), "columns have different lengths");
  bad = run;
  for (auto* c : {&bad.time_s, &bad.space_gap_m, &bad.follower_speed_mps, &bad.leader_speed_mps}) c->pop_back();
  EXPECT_EQ(acc::describeRunProblem(bad), "fewer than two samples");
}

TEST(CarFollowingRun, SliceKeepsTheRowsOfEveryColumnAndRefusesRowsOutsideTheRun)
{
  acc::CarFollowingRun run{"part3", {0.0, 0.1, 0.2, 0.3}, {20, 21, 22, 23}, {10, 11, 12, 13}, {9, 8, 7, 6}};
  const acc::CarFollowingRun middle = run.slice(1, 3, " (middle)");
  EXPECT_EQ(middle.name, "part3 (middle)");
  EXPECT_EQ(middle.time_s, (std::vector<double>{0.1, 0.2}));
  EXPECT_EQ(middle.space_gap_m, (std::vector<double>{21, 22}));
  EXPECT_EQ(middle.follower_speed_mps, (std::vector<double>{11, 12}));
  EXPECT_EQ(middle.leader_speed_mps, (std::vector<double>{8, 7}));
  EXPECT_EQ(run.slice(4, 4).size(), 0u);
  EXPECT_THROW(run.slice(2, 5), std::out_of_range);
  EXPECT_THROW(acc::sliceRows(run.time_s, 3, 2), std::out_of_range);
}
