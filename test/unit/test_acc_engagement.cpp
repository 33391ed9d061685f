// The ACC's engagement reports (io/acc_engagement.h): which samples the live node and the bag
// reader use, and what they count, for the sources a drive has (none, on change, periodic, dead).
#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>

#include "acc_identification/io/acc_engagement.h"

namespace
{
using Use = acc::AccEngagement::Use;

TEST(AccEngagement, WithoutASourceEverySampleIsUsedUnlessEngagementIsRequired)
{
  acc::AccEngagement optional;
  EXPECT_EQ(optional.judge(10.0).use, Use::kUsed);
  EXPECT_EQ(optional.latestReport(), "no report yet");

  acc::AccEngagementSettings settings;
  settings.required = true;
  acc::AccEngagement required(settings);
  const acc::AccEngagement::Judgement first = required.judge(10.0);
  EXPECT_EQ(first.use, Use::kStateUnknown);
  EXPECT_TRUE(first.starts_stretch);
  EXPECT_FALSE(required.judge(10.1).starts_stretch);  // said once per stretch
  EXPECT_EQ(required.samplesUnknown(), 2u);
  EXPECT_NE(required.describe(Use::kStateUnknown).find("no acc_engaged report yet"), std::string::npos);
  required.report(10.15, true);
  EXPECT_EQ(required.judge(10.2).use, Use::kUsed);
}

TEST(AccEngagement, ADisengagementStopsTheSamplesUntilTheAccIsEngagedAgain)
{
  acc::AccEngagement engagement;
  engagement.report(0.0, true);
  EXPECT_EQ(engagement.judge(0.1).use, Use::kUsed);
  engagement.report(0.15, false);  // the safety driver brakes
  const acc::AccEngagement::Judgement off = engagement.judge(0.2);
  EXPECT_EQ(off.use, Use::kAccOff);
  EXPECT_TRUE(off.starts_stretch);
  EXPECT_EQ(engagement.judge(0.3).use, Use::kAccOff);
  EXPECT_FALSE(engagement.judge(0.4).starts_stretch);
  engagement.report(0.45, false);  // a periodic source repeats itself: still one disengagement
  engagement.report(0.5, true);
  EXPECT_EQ(engagement.judge(0.6).use, Use::kUsed);
  engagement.report(0.65, false);
  EXPECT_TRUE(engagement.judge(0.7).starts_stretch);  // a second stretch is said again
  EXPECT_EQ(engagement.samplesOff(), 4u);
  EXPECT_EQ(engagement.samplesUnknown(), 0u);
  EXPECT_EQ(engagement.disengagements(), 2u);
  EXPECT_EQ(engagement.reports(), 5u);
  EXPECT_EQ(engagement.latestReport(), "off");
  EXPECT_NE(engagement.describe(Use::kAccOff).find("ACC off"), std::string::npos);
  EXPECT_EQ(engagement.describe(Use::kUsed), "");
}

TEST(AccEngagement, AReportOnChangeHoldsUntilTheNextWithoutATimeout)
{
  acc::AccEngagementSettings settings;
  settings.required = true;
  acc::AccEngagement engagement(settings);
  engagement.report(0.0, true);
  EXPECT_EQ(engagement.judge(3600.0).use, Use::kUsed);
}

TEST(AccEngagement, AStaleReportIsUnknownUsedOnlyWhenEngagementIsNotRequired)
{
  acc::AccEngagementSettings settings;
  settings.timeout_s = 1.0;
  acc::AccEngagement lenient(settings);
  lenient.report(0.0, false);
  EXPECT_EQ(lenient.judge(0.9).use, Use::kAccOff);
  EXPECT_EQ(lenient.judge(1.5).use, Use::kUsed);  // the source died: read as without one

  settings.required = true;
  acc::AccEngagement strict(settings);
  strict.report(0.0, true);
  EXPECT_EQ(strict.judge(1.0).use, Use::kUsed);
  const acc::AccEngagement::Judgement stale = strict.judge(1.01);
  EXPECT_EQ(stale.use, Use::kStateUnknown);
  EXPECT_TRUE(stale.starts_stretch);
  EXPECT_NE(strict.describe(Use::kStateUnknown).find("older than 1 s"), std::string::npos);
}

TEST(AccEngagement, AReportFromAfterTheSampleIsTheLatestOne)
{
  acc::AccEngagementSettings settings;
  settings.timeout_s = 1.0;
  settings.required = true;
  acc::AccEngagement engagement(settings);
  engagement.report(100.0, true);
  EXPECT_EQ(engagement.judge(5.0).use, Use::kUsed);  // a looping replay's clock went back
}

TEST(AccEngagement, UnusableSettingsAreRefusedWithTheReason)
{
  acc::AccEngagementSettings settings;
  settings.timeout_s = -1.0;
  EXPECT_NE(acc::describeAccEngagementSettingsProblem(settings).find("finite number >= 0"), std::string::npos);
  EXPECT_THROW(acc::AccEngagement{settings}, std::invalid_argument);
  settings.timeout_s = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(acc::AccEngagement{settings}, std::invalid_argument);
  settings.timeout_s = 0.0;
  EXPECT_EQ(acc::describeAccEngagementSettingsProblem(settings), "");
}
}  // namespace
