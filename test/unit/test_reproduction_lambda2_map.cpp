#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "acc_identification/reproduction/lambda2_map.h"
#include "acc_identification/model/string_stability.h"


// Fig. 1: the shaded (stable) region of the map is exactly k1 tau^2 + 2 k2 tau >= 2, and there
// lambda2 < 0; everywhere else lambda2 > 0.
TEST(Lambda2Map, StableRegionIsTheClosedFormRegion)
{
  acc::Lambda2MapGrid grid;
  grid.k1_points = grid.k2_points = 41;
  const auto map = acc::lambda2Map(grid);
  ASSERT_EQ(map.size(), grid.tau_e_s.size() * 41u * 41u);
  std::size_t stable = 0;
  for (const auto& s : map)
  {
    const double margin = s.k1_per_s2 * s.tau_e_s * s.tau_e_s + 2.0 * s.k2_per_s * s.tau_e_s - 2.0;
    EXPECT_EQ(s.string_stable, acc::inClosedFormStableRegion(s.k1_per_s2, s.k2_per_s, s.tau_e_s));
    if (std::abs(margin) > 1e-9)
    {
      EXPECT_EQ(s.lambda2 < 0.0, margin > 0.0) << s.k1_per_s2 << ' ' << s.k2_per_s << ' ' << s.tau_e_s;
    }
    stable += s.string_stable;
  }
  EXPECT_GT(stable, 0u);
  EXPECT_LT(stable, map.size());
}

// The paper: small gains need a larger tau_e; the stable share of the grid grows with tau_e and
// lambda2 tends to 0 for large tau_e.
TEST(Lambda2Map, LargerTimeGapStabilisesMoreOfTheGridAndLambda2TendsToZero)
{
  acc::Lambda2MapGrid grid;
  grid.tau_e_s = {0.5, 1.0, 2.0, 3.0};
  grid.k1_points = grid.k2_points = 21;
  const auto map = acc::lambda2Map(grid);
  double previous = -1.0;
  for (double tau : grid.tau_e_s)
  {
    const double fraction = acc::stableFraction(map, tau);
    EXPECT_GT(fraction, previous) << tau;
    previous = fraction;
  }
  EXPECT_NEAR(acc::stableFraction(map, 3.0), 1.0, 0.05);
  const acc::AccParameters gains{0.5, 0.5, 0.0, 0.0};
  double last = -std::numeric_limits<double>::infinity();
  for (double tau : {5.0, 10.0, 50.0, 200.0})
  {
    acc::AccParameters p = gains;
    p.tau_e_s = tau;
    EXPECT_LT(acc::lambda2(p), 0.0);
    EXPECT_GT(acc::lambda2(p), last - 1e-12);  // rising towards 0 from below
    last = acc::lambda2(p);
  }
  EXPECT_GT(last, -0.01);
}

// The paper: "increasing tau_e may initially reduce lambda2, before eventually increasing" it.
TEST(Lambda2Map, Lambda2FallsThenRisesWithTheTimeGap)
{
  auto at = [](double tau) { return acc::lambda2({0.5, 0.5, tau, 8.0}); };
  EXPECT_NEAR(at(0.5), 11.0, 1e-9);
  EXPECT_NEAR(at(2.0), -0.25, 1e-9);  // the minimum: d lambda2 / d tau = 0 at tau = 2 s
  EXPECT_LT(at(2.0), at(1.9));
  EXPECT_LT(at(2.0), at(2.1));
  EXPECT_GT(at(0.5), at(1.0));
  EXPECT_LT(at(3.0), at(10.0));
}

TEST(Lambda2Map, RejectsDegenerateGrids)
{
  acc::Lambda2MapGrid grid;
  grid.k1_points = 1;
  EXPECT_THROW(acc::lambda2Map(grid), std::invalid_argument);
  grid = acc::Lambda2MapGrid{};
  grid.k2_max_per_s = -1.0;
  EXPECT_THROW(acc::lambda2Map(grid), std::invalid_argument);
  grid = acc::Lambda2MapGrid{};
  grid.tau_e_s.clear();
  EXPECT_THROW(acc::lambda2Map(grid), std::invalid_argument);
}
