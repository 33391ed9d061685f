// When identifier_node asks its sequential verdict for a look: at most once per look period while
// the drive grows, once more when the data stop, and again when a look asked for was lost.
#include <gtest/gtest.h>

#include "acc_identification/ros/stability_look_schedule.h"

namespace
{
using acc::StabilityLookSchedule;

/// Periods of 1 s with 10 samples each, looks at most every 10 s: a look at 0 s and 10 s, none
/// between; when the count stops growing, one look at every sample, then none.
TEST(StabilityLookSchedule, LooksOncePerPeriodWhileTheDataComeAndOnceWhenTheyStop)
{
  StabilityLookSchedule schedule(10.0);
  int looks = 0;
  for (int t = 0; t <= 14; ++t)
  {
    const StabilityLookSchedule::Decision d = schedule.decide(t, 10u * (t + 1), false, true);
    EXPECT_TRUE(d.run_period);
    EXPECT_FALSE(d.data_stopped) << t;
    EXPECT_EQ(d.look, t == 0 || t == 10) << t;
    looks += d.look ? 1 : 0;
  }
  EXPECT_EQ(looks, 2);
  const StabilityLookSchedule::Decision stop = schedule.decide(15.0, 150u, false, true);
  EXPECT_TRUE(stop.look);
  EXPECT_TRUE(stop.data_stopped);
  EXPECT_FALSE(schedule.decide(16.0, 150u, false, true).look);
  EXPECT_FALSE(schedule.decide(17.0, 150u, true, true).run_period);  // a catch-up with nothing new
}

/// The drive's last samples came in the very period whose look was due: that look was made as if
/// more would come. The look at every sample is still owed when the data stop (live, 3 of 6 runs
/// used to end with the verdict at 1001 of 1051 samples), also on a catch-up under sim time.
TEST(StabilityLookSchedule, TheLookAtEverySampleIsOwedWhenTheLastSamplesCameInADuePeriod)
{
  for (const bool catch_up : {false, true})
  {
    StabilityLookSchedule schedule(10.0);
    EXPECT_TRUE(schedule.decide(0.0, 10u, false, true).look);
    EXPECT_FALSE(schedule.decide(5.0, 500u, false, true).look);
    const StabilityLookSchedule::Decision due = schedule.decide(10.0, 1051u, false, true);  // the last samples
    EXPECT_TRUE(due.look);
    EXPECT_FALSE(due.data_stopped);
    const StabilityLookSchedule::Decision owed = schedule.decide(11.0, 1051u, catch_up, true);
    EXPECT_TRUE(owed.run_period) << catch_up;
    EXPECT_TRUE(owed.look) << catch_up;
    EXPECT_TRUE(owed.data_stopped) << catch_up;
    EXPECT_FALSE(schedule.decide(12.0, 1051u, false, true).look) << catch_up;  // made once
  }
}

/// A look that went with a skipped period, or that the verdict's busy thread dropped, is asked again
/// in the next period, though nothing new came.
TEST(StabilityLookSchedule, ALostLookIsAskedAgain)
{
  StabilityLookSchedule schedule(10.0);
  EXPECT_TRUE(schedule.decide(0.0, 100u, false, true).look);
  EXPECT_TRUE(schedule.decide(1.0, 100u, false, true).look);  // stopped: the look at every sample
  schedule.lookLost();
  const StabilityLookSchedule::Decision again = schedule.decide(2.0, 100u, false, true);
  EXPECT_TRUE(again.look);
  EXPECT_TRUE(again.data_stopped);
  EXPECT_FALSE(schedule.decide(3.0, 100u, false, true).look);
}

/// A catch-up second with every look published and nothing new does nothing; with a look made and
/// not yet published the period runs (to publish it) without asking for another.
TEST(StabilityLookSchedule, ACatchUpRunsOnlyToPublishWhatIsNotPublished)
{
  StabilityLookSchedule schedule(10.0);
  EXPECT_TRUE(schedule.decide(0.0, 100u, false, true).look);
  EXPECT_TRUE(schedule.decide(1.0, 100u, true, true).look);  // the data stopped: the final look
  EXPECT_FALSE(schedule.decide(2.0, 100u, true, true).run_period);
  const StabilityLookSchedule::Decision publish = schedule.decide(3.0, 100u, true, false);
  EXPECT_TRUE(publish.run_period);
  EXPECT_FALSE(publish.look);
}

/// ROS time that goes back (a replay restarted) makes the next growth due at once.
TEST(StabilityLookSchedule, TimeThatGoesBackMakesTheNextLookDue)
{
  StabilityLookSchedule schedule(10.0);
  EXPECT_TRUE(schedule.decide(100.0, 10u, false, true).look);
  EXPECT_TRUE(schedule.decide(50.0, 20u, false, true).look);
}
}  // namespace
