#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "acc_identification/reproduction/lead_profiles.h"


namespace
{
constexpr double kMph = acc::kMetersPerSecondPerMph;

/// Longest run of consecutive samples within 1e-9 of speed, in seconds.
double longestHoldS(const std::vector<double>& speed, double value, double h)
{
  std::size_t best = 0, current = 0;
  for (double v : speed)
  {
    current = std::abs(v - value) < 1e-9 ? current + 1 : 0;
    best = std::max(best, current);
  }
  return best == 0 ? 0.0 : static_cast<double>(best - 1) * h;
}

double maxRate(const std::vector<double>& speed, double h, bool up)
{
  double rate = 0.0;
  for (std::size_t k = 1; k < speed.size(); ++k)
  {
    const double change = (speed[k] - speed[k - 1]) / h;
    rate = std::max(rate, up ? change : -change);
  }
  return rate;
}
}  // namespace

TEST(LeadProfiles, EveryProfileAToIExistsAndStaysWithinItsDescribedSpeeds)
{
  const std::map<char, std::pair<double, double>> range_mph{
      {'A', {5, 30}}, {'B', {35, 55}}, {'C', {60, 70}}, {'D', {20, 30}}, {'E', {45, 50}},
      {'F', {40, 50}}, {'G', {65, 70}}, {'H', {60, 70}}, {'I', {30, 50}}};
  for (char id : acc::leadProfileIds())
  {
    const auto speed = acc::leadProfile(id, 0.1);
    ASSERT_GT(speed.size(), 1000u) << id;
    const auto [low, high] = std::minmax_element(speed.begin(), speed.end());
    EXPECT_NEAR(*low, range_mph.at(id).first * kMph, 1e-9) << id;
    EXPECT_NEAR(*high, range_mph.at(id).second * kMph, 1e-9) << id;
    EXPECT_FALSE(acc::leadProfileDescription(id).empty());
  }
}

TEST(LeadProfiles, ProfileIHasFourDipsOfFiveToTwentyMphHeldFiveSeconds)
{
  const double h = 0.1;
  const auto speed = acc::leadProfile('I', h);
  for (double dip_mph : {5.0, 10.0, 15.0, 20.0})
  {
    EXPECT_NEAR(longestHoldS(speed, (50.0 - dip_mph) * kMph, h), 5.0, 0.11) << dip_mph;
  }
  EXPECT_NEAR(longestHoldS(speed, 50.0 * kMph, h), 45.0, 0.11);
  EXPECT_DOUBLE_EQ(speed.front(), 50.0 * kMph);
  EXPECT_DOUBLE_EQ(speed.back(), 50.0 * kMph);
  // Four separate excursions below 50 mph.
  int dips = 0;
  for (std::size_t k = 1; k < speed.size(); ++k)
  {
    dips += speed[k - 1] >= 50.0 * kMph - 1e-9 && speed[k] < 50.0 * kMph - 1e-9;
  }
  EXPECT_EQ(dips, 4);
  // Close to Table I's 255 s (minimum setting) / 307 s (maximum).
  const double duration = static_cast<double>(speed.size() - 1) * h;
  EXPECT_GT(duration, 240.0);
  EXPECT_LT(duration, 310.0);
}

TEST(LeadProfiles, RampsUseTheDocumentedPlausibleAccelerations)
{
  const double h = 0.1;
  const auto dips = acc::leadProfile('I', h);
  EXPECT_NEAR(maxRate(dips, h, false), acc::kRapidRamp.deceleration_mps2, 1e-6);
  EXPECT_NEAR(maxRate(dips, h, true), acc::kRapidRamp.acceleration_mps2, 1e-6);
  const auto steps = acc::leadProfile('B', h);
  EXPECT_NEAR(maxRate(steps, h, true), acc::kCruiseControlRamp.acceleration_mps2, 1e-6);
  const auto gentle = acc::leadProfile('I', h, {0.5, 0.5});
  EXPECT_NEAR(maxRate(gentle, h, false), 0.5, 1e-6);
  EXPECT_GT(gentle.size(), dips.size());  // slower ramps take longer
}

TEST(LeadProfiles, StepTestAGoesUpAndBackDownInFiveMphStepsHeldSixtySeconds)
{
  const double h = 0.5;
  const auto speed = acc::leadProfile('A', h);
  for (double v = 5.0; v <= 30.0; v += 5.0)
  {
    EXPECT_NEAR(longestHoldS(speed, v * kMph, h), 60.0, h) << v;  // each visit is held 60 s
  }
  const auto peak = std::max_element(speed.begin(), speed.end()) - speed.begin();
  EXPECT_GT(peak, 0);
  EXPECT_LT(static_cast<std::size_t>(peak), speed.size() - 1);
  EXPECT_DOUBLE_EQ(speed.back(), 5.0 * kMph);
}

TEST(LeadProfiles, OscillatoryProfileAlternatesEveryThirtySeconds)
{
  const double h = 0.1;
  const auto speed = acc::leadProfile('f', h);  // lower case accepted
  EXPECT_NEAR(longestHoldS(speed, 40.0 * kMph, h), 30.0, 0.11);
  EXPECT_NEAR(longestHoldS(speed, 50.0 * kMph, h), 30.0, 0.11);
}

TEST(LeadProfiles, RejectsUnknownIdsAndBadSteps)
{
  EXPECT_FALSE(acc::isLeadProfileId('J'));
  EXPECT_FALSE(acc::isLeadProfileId('\0'));
  EXPECT_TRUE(acc::isLeadProfileId('i'));
  EXPECT_THROW(acc::leadProfile('J', 0.1), std::invalid_argument);
  EXPECT_THROW(acc::leadProfile('I', 0.0), std::invalid_argument);
  EXPECT_THROW(acc::leadProfile('I', -1.0), std::invalid_argument);
  EXPECT_THROW(acc::leadProfile('I', 0.1, {0.0, 1.0}), std::invalid_argument);
}
